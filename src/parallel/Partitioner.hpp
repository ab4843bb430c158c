#pragma once
/// \file Partitioner.hpp
/// \brief Element decomposition over ranks (set-up step 1): METIS k-way on the element dual
/// graph, plus "joint" edges between elements of different parts whose external faces coincide
/// or nearly coincide, so blocks in contact tend to share a rank (fewer ghost faces and
/// cross-rank common planes).
#include "mesh/HostMesh.hpp"

#include <mpi.h>

#include <vector>

namespace scpdyn
{

/// \brief Knobs of the element partition (defaults are the production values).
struct PartitionOptions
{
  /// Edge weight between two elements of one part sharing a face (or two parts whose nodes
  /// were merged): cutting it makes shared nodes.
  int face_weight = 1;
  /// Edge weight between elements whose external faces face each other across a joint;
  /// 0 switches joint edges off. Cutting it makes a ghost face and a cross-rank common plane,
  /// which costs more than a shared node, hence the default 2.
  int joint_weight = 2;
  /// Two external faces of different parts are joint neighbours when their normals are
  /// opposite (n1.n2 < -0.9), their centroids are closer than `joint_overlap` x the larger
  /// face size in the face plane (so they overlap), and the normal gap is below
  /// `joint_gap` x the larger face size (nearly closed joint). Face size = max distance of a
  /// node from the centroid x 2.
  Real joint_overlap = 0.5;
  Real joint_gap = 0.1;
  int seed = 7;     ///< METIS_OPTION_SEED: every rank computes the same partition
  int ufactor = 30; ///< METIS_OPTION_UFACTOR: allowed imbalance 1 + ufactor/1000
};

/// \brief Rank (0..nparts-1) of each mesh element, elements numbered in part order as in
/// extractExternalFaces. `external_faces` must be extractExternalFaces(mesh). The result is a
/// pure function of the inputs (fixed METIS seed), so every rank may compute it from the
/// same deck; nparts = 1 gives all zeros without calling METIS. Throws std::runtime_error if
/// METIS fails or nparts < 1.
std::vector<int> partitionElements(const HostMesh &mesh,
                                   const std::vector<HostFace> &external_faces, int nparts,
                                   const PartitionOptions &options = PartitionOptions());

/// \brief partitionElements for the ranks of `comm`, computed on rank 0 only and broadcast
/// (collective). Same result as every rank calling partitionElements(..., size), without
/// running METIS size times on the same node; prefer it in the solver set-up.
std::vector<int> partitionElementsOnRoot(const HostMesh &mesh,
                                         const std::vector<HostFace> &external_faces,
                                         MPI_Comm comm = MPI_COMM_WORLD,
                                         const PartitionOptions &options = PartitionOptions());

/// \brief Pairs (a, b), a < b, of indices into `external_faces` that are joint neighbours in
/// the sense of PartitionOptions (different parts, facing each other, overlapping, nearly
/// closed). Sorted. Used for the joint edges and to measure how many joints a partition cuts.
std::vector<std::pair<Index, Index>>
jointFacePairs(const HostMesh &mesh, const std::vector<HostFace> &external_faces,
               const PartitionOptions &options = PartitionOptions());

} // namespace scpdyn
