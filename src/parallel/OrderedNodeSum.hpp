#pragma once
/// \file OrderedNodeSum.hpp
/// \brief Shared-node sums that give the serial run's bits (docs/theory.md 2.2): at a node that
/// several ranks hold, the terms of every rank (element corners, CP shares) are added one by one
/// from zero in the order the serial run adds them, instead of each rank adding its own terms
/// and the ranks then adding their partial sums (NodeHalo), whose bits depend on where the
/// partition cuts.
///
/// Every term carries a key that orders it as the serial run does (an element corner: its
/// element's serial index, then the corner; a CP share: the CP's face keys, then its row and
/// side). The plan is built once per set of terms (collective): each rank sends its
/// neighbours the keys of its terms at the nodes they share, and every holder of a node merges
/// the keys into one recipe, the same on every rank. Each sum then sends only the terms'
/// values: one message per neighbour rank and direction, the nodes of a message in ascending
/// global id as NodeHalo's, a node's terms in ascending key.
#include "core/Types.hpp"
#include "parallel/LocalDomain.hpp"

#include <mpi.h>

#include <array>
#include <cstdint>
#include <vector>

namespace scpdyn
{

/// \brief The serial order of a term, compared lexicographically.
using TermKey = std::array<std::int64_t, 3>;

/// \brief One term of a shared node: its key and its slot in the value arrays of sum().
struct NodeTerm
{
  TermKey key;
  Index slot;
};

class OrderedNodeSum
{
public:
  /// \brief Build the plan (collective over `comm`). `terms[s]` are this rank's terms of the
  /// shared node `shared.local[s]` (any order; no two ranks may give a node the same key).
  /// Throws std::runtime_error when keys repeat at a node.
  /// `bytes_sent`, when given, counts the bytes of the values each sum() sends (traffic
  /// accounting, docs/scaling.md).
  OrderedNodeSum(MPI_Comm comm, const SharedNodes &shared,
                 const std::vector<std::vector<NodeTerm>> &terms,
                 std::uint64_t *bytes_sent = nullptr);
  OrderedNodeSum(const OrderedNodeSum &) = delete;
  OrderedNodeSum &operator=(const OrderedNodeSum &) = delete;

  /// \brief At every shared node n: out(n) = the sum from zero (or from out(n), which must be
  /// the same on every copy), in key order, of the terms of all ranks, this rank's read from
  /// `values` at their slots [any unit]. Collective.
  void sum(const VectorView &values, const VectorView &out, bool from_zero = true);
  /// \brief The same on the host for set-up sums: `values` holds nc reals per slot, `out` nc per
  /// local node.
  void sumHost(const std::vector<Real> &values, int nc, std::vector<Real> &out);

  /// \brief Bytes this rank sends per vector sum.
  std::size_t bytesPerVectorSum() const { return 3 * sizeof(Real) * _send_slot_host.size(); }

private:
  void exchange(const Real *send, Real *recv, int nc);

  MPI_Comm _comm = MPI_COMM_NULL;
  std::vector<int> _neighbours;
  std::vector<Index> _send_offset, _recv_offset; ///< per neighbour, terms (size + 1)
  std::vector<Index> _send_slot_host;            ///< the slot of each term sent, message order
  std::vector<Index> _node_host, _sum_offset_host, _sum_source_host;
  IndexView _send_slot;
  IndexView _node;       ///< local node of each shared node
  IndexView _sum_offset; ///< CRS over the shared nodes into _sum_source
  IndexView _sum_source; ///< in key order: >= 0 received term, < 0 own slot -(source + 1)
  RealView _send, _recv; ///< 3 reals per term, message order
  std::vector<MPI_Request> _requests;          ///< receives, then sends
  std::uint64_t *_bytes_sent = nullptr;        ///< the traffic counter, or null
  RealView::HostMirror _send_host, _recv_host; ///< alias them when the device is the host
};

} // namespace scpdyn
