// Shared-node sum plan (see NodeHalo.hpp).
#include "parallel/NodeHalo.hpp"
#include "core/HostCopy.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace scpdyn
{
namespace
{

bool finalised()
{
  int f = 0;
  MPI_Finalized(&f);
  return f != 0;
}

} // namespace

NodeHalo::NodeHalo(const LocalDomain &domain, MPI_Comm comm)
{
  MPI_Comm_dup(comm, &_comm);
  MPI_Comm_rank(_comm, &_rank);
  if (_rank != domain.rank)
    throw std::runtime_error("NodeHalo: domain of rank " + std::to_string(domain.rank) +
                             " built on rank " + std::to_string(_rank));
  const SharedNodes &sh = domain.shared;
  _num_shared = sh.size();
  _neighbours = neighbourRanks(sh, _rank);

  // Slots: for each neighbour, the shared nodes it holds in ascending shared index (= global
  // id), so both ends list the same nodes in the same order.
  const size_t nn = _neighbours.size();
  std::vector<std::vector<Index>> nodes_of(nn);
  for (Index s = 0; s < sh.size(); ++s)
    for (Index k = sh.rank_offsets[size_t(s)]; k < sh.rank_offsets[size_t(s) + 1]; ++k)
    {
      const int r = sh.ranks[size_t(k)];
      if (r == _rank)
        continue;
      const size_t j =
          size_t(std::lower_bound(_neighbours.begin(), _neighbours.end(), r) - _neighbours.begin());
      nodes_of[j].push_back(s);
    }
  _neighbour_offset.assign(nn + 1, 0);
  std::vector<Index> slot_node;
  for (size_t j = 0; j < nn; ++j)
  {
    for (Index s : nodes_of[j])
      slot_node.push_back(sh.local[size_t(s)]);
    _neighbour_offset[j + 1] = Index(slot_node.size());
  }
  _num_slots = Index(slot_node.size());

  // Sum recipe per shared node: its holders in ascending rank order, own value as -1. The slot
  // of (node s, neighbour j) is found by walking the neighbours' lists in step with s.
  std::vector<size_t> cursor(nn, 0);
  std::vector<Index> sum_offset(1, 0), sum_source;
  bool holds_self = true;
  for (Index s = 0; s < sh.size(); ++s)
  {
    bool self = false;
    for (Index k = sh.rank_offsets[size_t(s)]; k < sh.rank_offsets[size_t(s) + 1]; ++k)
    {
      const int r = sh.ranks[size_t(k)];
      if (r == _rank)
      {
        sum_source.push_back(-1);
        self = true;
        continue;
      }
      const size_t j =
          size_t(std::lower_bound(_neighbours.begin(), _neighbours.end(), r) - _neighbours.begin());
      sum_source.push_back(_neighbour_offset[j] + Index(cursor[j]++));
    }
    holds_self = holds_self && self;
    sum_offset.push_back(Index(sum_source.size()));
  }
  if (!holds_self)
    throw std::runtime_error("NodeHalo: a shared node's rank list misses its own rank");

  _slot_node = toDevice(slot_node, "scpdyn::comm::nodeHalo::slot_node");
  _shared_node = toDevice(sh.local, "scpdyn::comm::nodeHalo::shared_node");
  _sum_offset = toDevice(sum_offset, "scpdyn::comm::nodeHalo::sum_offset");
  _sum_source = toDevice(sum_source, "scpdyn::comm::nodeHalo::sum_source");
  setupChannel(_vec, 3, 7301, "scpdyn::comm::nodeHalo::vector");
  setupChannel(_scal, 1, 7302, "scpdyn::comm::nodeHalo::scalar");
}

void NodeHalo::setupChannel(Channel &c, int ncomp, int tag, const char *label)
{
  c.ncomp = ncomp;
  c.tag = tag;
  const size_t n = size_t(ncomp) * size_t(_num_slots);
  c.send = Buffer(std::string(label) + "_send", n);
  c.recv = Buffer(std::string(label) + "_recv", n);
  c.send_host = Kokkos::create_mirror_view(HostSpace(), c.send);
  c.recv_host = Kokkos::create_mirror_view(HostSpace(), c.recv);
  const size_t nn = _neighbours.size();
  c.requests.assign(2 * nn, MPI_REQUEST_NULL);
  for (size_t j = 0; j < nn; ++j)
  {
    const Index first = _neighbour_offset[j] * ncomp;
    const int count = int((_neighbour_offset[j + 1] - _neighbour_offset[j]) * ncomp);
    MPI_Recv_init(c.recv_host.data() + first, count, MPI_DOUBLE, _neighbours[j], tag, _comm,
                  &c.requests[j]);
    MPI_Send_init(c.send_host.data() + first, count, MPI_DOUBLE, _neighbours[j], tag, _comm,
                  &c.requests[nn + j]);
  }
}

NodeHalo::~NodeHalo()
{
  if (finalised())
    return;
  for (Channel *c : {&_vec, &_scal})
  {
    if (c->in_flight && !c->requests.empty())
      MPI_Waitall(int(c->requests.size()), c->requests.data(), MPI_STATUSES_IGNORE);
    for (MPI_Request &r : c->requests)
      if (r != MPI_REQUEST_NULL)
        MPI_Request_free(&r);
  }
  if (_comm != MPI_COMM_NULL)
    MPI_Comm_free(&_comm);
}

void NodeHalo::start(Channel &c, const Real *field)
{
  if (c.in_flight)
    throw std::logic_error("NodeHalo::beginSum: the previous sum of this kind is not finished");
  c.in_flight = true;
  c.field = field;
  const int nn = int(_neighbours.size());
  if (nn > 0)
    MPI_Startall(nn, c.requests.data());
}

void NodeHalo::finish(Channel &c, const Real *field)
{
  if (!c.in_flight || c.field != field)
    throw std::logic_error("NodeHalo::endSum without a matching beginSum on the same field");
  if (!c.requests.empty())
    MPI_Waitall(int(c.requests.size()), c.requests.data(), MPI_STATUSES_IGNORE);
  if (c.recv_host.data() != c.recv.data())
    Kokkos::deep_copy(c.recv, c.recv_host);
  c.in_flight = false;
  c.field = nullptr;
}

namespace
{
/// Component i of node n of a nodal field with NC components (a RealView when NC = 1).
template <int NC, class Field>
KOKKOS_INLINE_FUNCTION Real &component(const Field &f, Index n, int i)
{
  if constexpr (NC == 1)
    return f(n);
  else
    return f(n, i);
}
} // namespace

template <int NC, class Field>
void NodeHalo::packAndSend(Channel &c, const Field &f, const char *label)
{
  start(c, f.data());
  const auto slot_node = _slot_node;
  const auto buf = c.send;
  Kokkos::parallel_for(
      label, Kokkos::RangePolicy<ExecSpace>(0, _num_slots), KOKKOS_LAMBDA(const Index k) {
        const Index n = slot_node(k);
        for (int i = 0; i < NC; ++i)
          buf(NC * k + i) = component<NC>(f, n, i);
      });
  ExecSpace().fence();
  if (c.send_host.data() != c.send.data())
    Kokkos::deep_copy(c.send_host, c.send);
  const int nn = int(_neighbours.size());
  if (nn > 0)
    MPI_Startall(nn, c.requests.data() + nn);
  _bytes_sent += NC * sizeof(Real) * std::size_t(_num_slots);
}

template <int NC, class Field>
void NodeHalo::receiveAndSum(Channel &c, const Field &f, const char *label)
{
  finish(c, f.data());
  const auto shared_node = _shared_node;
  const auto offset = _sum_offset;
  const auto source = _sum_source;
  const auto buf = c.recv;
  // total = ((0 + p_r0) + p_r1) + ... over the holders r0 < r1 < ...: the same additions in the
  // same order on every rank, hence the same bits (additions only, nothing to contract).
  Kokkos::parallel_for(
      label, Kokkos::RangePolicy<ExecSpace>(0, _num_shared), KOKKOS_LAMBDA(const Index s) {
        const Index n = shared_node(s);
        Real t[NC] = {};
        for (Index k = offset(s); k < offset(s + 1); ++k)
        {
          const Index src = source(k);
          for (int i = 0; i < NC; ++i)
            t[i] += src < 0 ? component<NC>(f, n, i) : buf(NC * src + i);
        }
        for (int i = 0; i < NC; ++i)
          component<NC>(f, n, i) = t[i];
      });
}

void NodeHalo::beginSum(const VectorView &f)
{
  packAndSend<3>(_vec, f, "scpdyn::comm::nodeHalo::packVector");
}

void NodeHalo::endSum(const VectorView &f)
{
  receiveAndSum<3>(_vec, f, "scpdyn::comm::nodeHalo::sumVector");
}

void NodeHalo::beginSum(const RealView &m)
{
  packAndSend<1>(_scal, m, "scpdyn::comm::nodeHalo::packScalar");
}

void NodeHalo::endSum(const RealView &m)
{
  receiveAndSum<1>(_scal, m, "scpdyn::comm::nodeHalo::sumScalar");
}

} // namespace scpdyn
