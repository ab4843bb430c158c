#pragma once
/// \file NodeHalo.hpp
/// \brief Shared-node sum (cycle steps 7, 9b and 10, set-up node masses): a communication plan
/// built once from a LocalDomain, with persistent buffers and persistent MPI requests.
///
/// Every copy of a shared node ends with the same bits: after the exchange each rank adds the
/// partial values of all ranks holding the node in ascending rank order, starting from zero,
/// with its own partial at its own position (scatter(Sum) and gather in one step, since every
/// holder receives every partial). One message per neighbour rank and direction; the nodes of
/// a message are the nodes shared with that neighbour in ascending global id, so sender and
/// receiver agree on the order without sending ids.
///
/// Split phase, no barrier: beginSum() starts the receives, packs, starts the sends;
/// endSum() waits and unpacks. Other work (and the other field kind) may run in between; the
/// field must not change between begin and end. Nothing is allocated after construction.
#include "core/Types.hpp"
#include "parallel/LocalDomain.hpp"

#include <mpi.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace scpdyn
{

class NodeHalo
{
public:
  /// Memory space of the message buffers. The buffers are staged through host mirrors when
  /// this space is not host accessible (no GPU-aware MPI assumed); with a GPU-aware MPI set it
  /// to the device space and drop the staging.
  using CommMemSpace = MemSpace;
  using Buffer = Kokkos::View<Real *, Layout, CommMemSpace>;
  using HostBuffer = Kokkos::View<Real *, Layout, HostSpace>;

  /// \brief Build the plan (collective over `comm`: it is duplicated so the plan's messages
  /// never match anyone else's). Call on every rank of `comm`, with `domain.rank` equal to the
  /// rank in `comm`.
  NodeHalo(const LocalDomain &domain, MPI_Comm comm = MPI_COMM_WORLD);
  ~NodeHalo();
  NodeHalo(const NodeHalo &) = delete;
  NodeHalo &operator=(const NodeHalo &) = delete;

  /// \brief Start summing a nodal vector field over the copies of every shared node [any unit].
  void beginSum(const VectorView &f);
  /// \brief Finish: every shared node of `f` (the same View) holds the total of all copies.
  void endSum(const VectorView &f);
  /// \brief beginSum + endSum.
  void sum(const VectorView &f)
  {
    beginSum(f);
    endSum(f);
  }
  /// \brief The same for a nodal scalar (e.g. lumped masses at set-up) [any unit].
  void beginSum(const RealView &m);
  void endSum(const RealView &m);
  void sum(const RealView &m)
  {
    beginSum(m);
    endSum(m);
  }

  int numNeighbours() const { return int(_neighbours.size()); }
  const std::vector<int> &neighbours() const { return _neighbours; }
  Index numSharedNodes() const { return _num_shared; }
  /// \brief Bytes this rank sends per vector sum (3 reals per node per neighbour).
  std::size_t bytesPerVectorSum() const { return 3 * sizeof(Real) * std::size_t(_num_slots); }
  /// \brief Bytes this rank sends per scalar sum.
  std::size_t bytesPerScalarSum() const { return sizeof(Real) * std::size_t(_num_slots); }
  /// \brief Bytes sent by this plan since construction.
  std::uint64_t bytesSent() const { return _bytes_sent; }
  /// \brief Buffer addresses, for tests that check nothing is reallocated.
  const Real *vectorSendData() const { return _vec.send.data(); }
  const Real *vectorRecvData() const { return _vec.recv.data(); }
  const Real *scalarSendData() const { return _scal.send.data(); }
  const Real *scalarRecvData() const { return _scal.recv.data(); }

private:
  /// Buffers and persistent requests of one field kind (ncomp = 3 or 1).
  struct Channel
  {
    int ncomp = 0;
    int tag = 0;
    Buffer send, recv;
    HostBuffer send_host, recv_host;   ///< alias the buffers when CommMemSpace is host memory
    std::vector<MPI_Request> requests; ///< receives first, then sends
    bool in_flight = false;
    const Real *field = nullptr; ///< the field being summed, to catch mismatched begin/end
  };

  void setupChannel(Channel &c, int ncomp, int tag, const char *label);
  void start(Channel &c, const Real *field);
  void finish(Channel &c, const Real *field);
  /// The vector and scalar sums are one code: `f` is a VectorView (NC = 3) or a RealView (1).
  template <int NC, class Field>
  void packAndSend(Channel &c, const Field &f, const char *label);
  template <int NC, class Field>
  void receiveAndSum(Channel &c, const Field &f, const char *label);

  MPI_Comm _comm = MPI_COMM_NULL;
  int _rank = 0;
  Index _num_shared = 0;
  Index _num_slots = 0;                 ///< sum over neighbours of the nodes shared with each
  std::vector<int> _neighbours;         ///< ascending
  std::vector<Index> _neighbour_offset; ///< slot range of each neighbour, size + 1
  IndexView _slot_node;                 ///< local node of each message slot
  IndexView _shared_node;               ///< local node of each shared node
  IndexView _sum_offset;                ///< CRS over shared nodes into _sum_source
  IndexView _sum_source; ///< per holder in ascending rank order: slot, or -1 for own value
  Channel _vec, _scal;
  std::uint64_t _bytes_sent = 0;
};

} // namespace scpdyn
