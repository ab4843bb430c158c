#pragma once
/// \file Decomposition.hpp
/// \brief What a decomposed run keeps about its piece of the mesh: the maps to the
/// global numbering, which nodes this rank owns (for sums and output), the shared-node sum
/// plan of steps 7, 9b and 10, and the arrays the sums of 9b and 10 need. Null in the serial Solver.
#include "core/Types.hpp"
#include "parallel/GhostFaces.hpp"
#include "parallel/NodeHalo.hpp"
#include "parallel/OrderedNodeSum.hpp"

#include <cstdint>
#include <memory>
#include <vector>

namespace scpdyn
{

struct DomainDecomposition
{
  std::vector<Index> global_node;    ///< local node -> global node (ascending)
  std::vector<Index> global_element; ///< local mesh element -> global mesh element (ascending)
  std::vector<char> owned;           ///< per local node: 1 if this rank owns it
  IndexView owned_device;            ///< the same on device (sums over nodes)
  long global_nodes = 0, global_elements = 0;
  /// Per local device element: its index in the serial device order (elements grouped by
  /// type, ascending global id within a type), which is the cell order of the output files.
  std::vector<Index> output_cell;
  std::unique_ptr<NodeHalo> halo;
  IndexView shared_nodes;          ///< local ids of the shared nodes
  SharedNodes shared;              ///< the same with the ranks holding each
  std::vector<Index> shared_index; ///< per local node: its index in `shared`, or -1
  /// Step 7 under numerics.scatter gather: the element corners of the shared nodes summed in
  /// the serial order (OrderedNodeSum), so a decomposed run has the serial run's bits.
  std::unique_ptr<OrderedNodeSum> corner_sum;
  /// Steps 9b and 10: the partial contact / pressure forces of this rank, summed over the copies in
  /// their own arrays so no force is counted twice.
  VectorView f_contact, f_load;
  /// Contact (steps 4 and 8): the ghost faces and nodes, this rank's own contact faces and the
  /// shared nodes on the host.
  std::unique_ptr<GhostFaces> ghosts;
  std::vector<GhostFaceDesc> own_faces;
  std::vector<Index> shared_host;
  /// Traffic accounting (docs/scaling.md): shared-node bytes sent during set-up (excluded from
  /// the per-cycle figure) and bytes of the ghost-face rebuilds so far.
  std::uint64_t halo_bytes_setup = 0, rebuild_bytes = 0;
  /// Bytes of the shared-node sums in the serial order (OrderedNodeSum) in the cycles so far.
  std::uint64_t ordered_bytes = 0;
};

} // namespace scpdyn
