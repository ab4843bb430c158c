#pragma once
/// \file LocalDomain.hpp
/// \brief One rank's piece of the decomposed mesh (set-up step 2): its own elements, the nodes
/// they use, the node and face sets restricted to them, the local <-> global maps, and the
/// nodes it shares with other ranks.
///
/// Shared nodes are found from the global mesh, which every rank builds from the same deck at
/// set-up: a node is shared when elements of two or more ranks use it. This is exact (no
/// geometric tolerance, merged nodes across parts included), costs O(global mesh) once, and
/// needs no communication; the bounding-box / occupied-bin exchange of the paper is only needed
/// when no rank holds the whole mesh. Nodes that coincide without being merged (jointed blocks)
/// are distinct nodes and are never shared; they interact through contact (ghost faces).
#include "mesh/HostMesh.hpp"

#include <vector>

namespace scpdyn
{

/// \brief The local nodes that other ranks hold too, in ascending local (= global) id.
struct SharedNodes
{
  std::vector<Index> local;        ///< local node id
  std::vector<Index> global;       ///< global node id
  std::vector<Index> rank_offsets; ///< CRS into `ranks`, size() + 1 entries
  std::vector<int> ranks;          ///< ascending ranks holding the node, this rank included

  Index size() const { return Index(local.size()); }
};

/// \brief A rank's local mesh and its maps to the global numbering.
struct LocalDomain
{
  int rank = 0;
  /// 1 + the largest rank in the element partition (ranks without elements beyond it hold
  /// nothing and share nothing).
  int num_ranks = 1;
  /// Same parts in the same order as the global mesh (possibly empty), only local elements
  /// in ascending global order, nodes numbered in ascending global id; node sets hold the
  /// local members, face sets the faces of local elements (nodes and element renumbered).
  HostMesh mesh;
  std::vector<Index> global_node;    ///< local node -> global node (ascending)
  std::vector<Index> global_element; ///< local element -> global element (ascending)
  SharedNodes shared;

  /// \brief Local id of a global node, or -1 if this rank does not hold it (O(log n)).
  Index localNode(Index global) const;
  /// \brief Local id of a global element, or -1 if it is on another rank (O(log n)).
  Index localElement(Index global) const;
};

/// \brief Cut rank `rank`'s piece out of the global mesh. `element_rank` gives the rank of
/// every global element (elements numbered in part order, e.g. from partitionElements).
/// Nodes used by no element belong to no rank. Throws std::runtime_error if element_rank has
/// the wrong size.
LocalDomain buildLocalDomain(const HostMesh &global, const std::vector<int> &element_rank,
                             int rank);

/// \brief The other ranks that hold a node of `shared`, ascending (the neighbours of the
/// shared-node exchanges).
std::vector<int> neighbourRanks(const SharedNodes &shared, int rank);

/// \brief Per local node: 1 if this rank owns it (not shared, or this is the lowest rank holding
/// it), else 0. Every node has exactly one owner, so sums over owned nodes (kinetic energy,
/// momentum, output) count each node once.
std::vector<char> ownedNodes(const LocalDomain &domain);

/// \brief The faces of `global_faces` whose element is local, in their order, with nodes and
/// element renumbered to local ids (part and local_face kept). Use it for the external faces:
/// extractExternalFaces on the local mesh would wrongly call partition-boundary faces external.
std::vector<HostFace> localFaces(const std::vector<HostFace> &global_faces,
                                 const LocalDomain &domain);

} // namespace scpdyn
