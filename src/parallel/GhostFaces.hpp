#pragma once
/// \file GhostFaces.hpp
/// \brief Ghost contact faces of a decomposed run (cycle steps 4 and 8, docs/theory.md 2.2 and
/// the parallel rules): which remote contact faces a rank needs, and the owner -> ghost copy
/// of their node data every cycle.
///
/// Step 4 (`rebuild`, on search cycles, collective): every rank sorts its own contact faces
/// into global bins (the same grid on every rank: origin from an all-reduce, edge = the
/// search distance), exchanges bounding boxes of its occupied bins with all ranks, then the
/// lists of occupied bins with the ranks whose boxes overlap its own, and sends each such rank
/// the faces lying in a bin that equals or neighbours (3^d stencil) one of that rank's bins.
/// The rule is symmetric, so a pair of faces of two ranks is seen by both or by neither.
///
/// Ghost faces reference ghost NODES, numbered after the local nodes (num_local + i, i in
/// ascending global id); a node of a ghost face that this rank holds itself (a shared node)
/// keeps its local id. Ghost nodes have no element; their constant data (total mass, velocity
/// BC flags) come with the faces, their per-cycle data by `gather`.
///
/// Step 8 (`gather`): for every ghost node, the owner's values of nodal vector fields (x, v,
/// f_int, f_ext; during the contact's constraint solve, velocity increments). The values are
/// copies, so both ranks of a cross-rank common plane compute it from the same bits.
#include "core/Types.hpp"

#include <mpi.h>

#include <array>
#include <cstdint>
#include <vector>

namespace scpdyn
{

/// \brief A contact face as the exchange sees it.
struct GhostFaceDesc
{
  long key = 0;     ///< global face key: global element * 8 + local face
  int part = -1;    ///< mesh part
  int surface = -1; ///< contact surface (face-BC id)
  int num_nodes = 0;
  int rigid = 0;  ///< every node component prescribed (10.1)
  int active = 1; ///< 0: not searched now (erosion, 11.6): never sent as a ghost face
  Real mass = 0;  ///< face mass M_f [kg]
  Real depth = 0; ///< depth of the element behind (ContactFaceData::depth) [m]
  Index nodes[4] = {-1, -1, -1, -1}; ///< local node id, or ghost slot (>= num_local) on receipt
  /// 1D: the other node of the element behind the point face (orients it), else -1; numbered
  /// like `nodes`
  Index back = -1;
};

class GhostFaces
{
public:
  /// \brief `global_node`: global id of every local node (ascending); `node_mass` the total
  /// nodal masses [kg] and `node_bc` the velocity-BC flags (NodeFields::bc) of the local
  /// nodes. Collective over `comm` (duplicated).
  GhostFaces(MPI_Comm comm, std::vector<Index> global_node, std::vector<Real> node_mass,
             std::vector<std::array<int, 3>> node_bc);
  ~GhostFaces();
  GhostFaces(const GhostFaces &) = delete;
  GhostFaces &operator=(const GhostFaces &) = delete;

  /// \brief Step 4 (collective): choose the ghost faces. `faces` are this rank's contact faces
  /// (nodes = local ids), `centroids` their centroids [m], `bin_size` an upper bound of the
  /// centroid distance of any two faces that may form a common plane [m], `dim` 1, 2 or 3.
  void rebuild(const std::vector<GhostFaceDesc> &faces,
               const std::vector<std::array<Real, 3>> &centroids, Real bin_size, int dim);

  Index numLocalNodes() const { return Index(_global_node.size()); }
  /// \brief The ghost faces, ascending key, nodes in local + ghost numbering.
  const std::vector<GhostFaceDesc> &faces() const { return _faces; }
  /// \brief Ghost nodes, ascending global id (ghost node i has id numLocalNodes() + i).
  Index numGhostNodes() const { return Index(_ghost_global.size()); }
  const std::vector<Index> &ghostGlobal() const { return _ghost_global; }
  const std::vector<Real> &ghostMass() const { return _ghost_mass; }
  const std::vector<std::array<int, 3>> &ghostBc() const { return _ghost_bc; }
  /// \brief Ranks this rank sends faces to / receives faces from (the same set).
  const std::vector<int> &neighbours() const { return _neighbours; }

  /// \brief Step 8 (collective): copy `count` nodal vector fields from the owners to the ghost
  /// nodes. Every View must have room for the ghost nodes. With `sum_last_two` the last two
  /// fields travel as their sum, which the ghosts receive in the first of them (the second is
  /// zeroed): a + b + 0 has the bits of a + b, and a quarter fewer bytes go for x, v, f_int,
  /// f_ext.
  void gather(const VectorView *fields, int count, bool sum_last_two = false);

  /// \brief After a search (collective): until the next rebuild only the nodes of the ghost
  /// faces flagged in `needed` (indexed like faces(), e.g. those of a live common plane) are
  /// copied by gather(); each rank tells its neighbours which of their nodes it still needs.
  void restrictTo(const std::vector<char> &needed);
  std::size_t bytesLastRestrict() const { return _bytes_restrict; }

  /// \brief Owner -> ghost copy of one value per face (collective): `local` indexed like the
  /// `faces` of the last rebuild, `ghost` (resized) like faces().
  void gatherFaces(const std::vector<Real> &local, std::vector<Real> &ghost);

  /// \brief Bytes this rank sent in the last gather / in the last rebuild (descriptors and
  /// bin lists), and in all gathers so far.
  std::size_t bytesLastGather() const { return _bytes_gather; }
  std::size_t bytesLastRebuild() const { return _bytes_rebuild; }
  std::uint64_t bytesGathered() const { return _bytes_total; }
  /// \brief Nodes sent per gather (summed over neighbours).
  Index numSendNodes() const { return Index(_send_node.extent(0)); }

private:
  MPI_Comm _comm = MPI_COMM_NULL;
  int _rank = 0, _size = 1;
  std::vector<Index> _global_node;
  std::vector<Real> _node_mass;
  std::vector<std::array<int, 3>> _node_bc;

  std::vector<GhostFaceDesc> _faces;
  std::vector<Index> _ghost_global;
  std::vector<Real> _ghost_mass;
  std::vector<std::array<int, 3>> _ghost_bc;
  std::vector<int> _neighbours;
  std::vector<Index> _send_offset, _recv_offset; ///< per neighbour into the node lists
  std::vector<Index> _send_face, _recv_face;     ///< per neighbour, in message order
  std::vector<Index> _send_face_offset, _recv_face_offset;
  std::vector<Index> _send_full, _recv_full; ///< the rebuild's node lists
  std::vector<Index> _send_full_offset, _recv_full_offset;
  std::size_t _bytes_restrict = 0;
  IndexView _send_node; ///< local node of each send slot
  IndexView _recv_slot; ///< ghost node (index into the node Views) of each receive slot, or -1
  DeviceView<Real *> _send_buf, _recv_buf;
  std::size_t _bytes_gather = 0, _bytes_rebuild = 0;
  std::uint64_t _bytes_total = 0;
};

} // namespace scpdyn
