// Shared-node sums in the serial order (see OrderedNodeSum.hpp).
#include "parallel/OrderedNodeSum.hpp"
#include "core/HostCopy.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace scpdyn
{
namespace
{

// tags of this plan's messages: every exchange completes before its call returns, and the
// messages between two ranks arrive in the order they were sent, so a tag per message kind is
// enough on the caller's communicator
constexpr int kKeyTag = 7402, kValueTag = 7403;

} // namespace

OrderedNodeSum::OrderedNodeSum(MPI_Comm comm, const SharedNodes &sh,
                               const std::vector<std::vector<NodeTerm>> &terms,
                               std::uint64_t *bytes_sent)
    : _comm(comm), _bytes_sent(bytes_sent)
{
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (Index(terms.size()) != sh.size())
    throw std::runtime_error("OrderedNodeSum: " + std::to_string(terms.size()) +
                             " term lists for " + std::to_string(sh.size()) + " shared nodes");
  _neighbours = neighbourRanks(sh, rank);
  const size_t nn = _neighbours.size();
  auto neighbour = [&](int r) {
    return size_t(std::lower_bound(_neighbours.begin(), _neighbours.end(), r) -
                  _neighbours.begin());
  };
  // the shared nodes each neighbour holds, ascending (= ascending global id on both ends)
  std::vector<std::vector<Index>> nodes_of(nn);
  for (Index s = 0; s < sh.size(); ++s)
    for (Index k = sh.rank_offsets[size_t(s)]; k < sh.rank_offsets[size_t(s) + 1]; ++k)
      if (sh.ranks[size_t(k)] != rank)
        nodes_of[neighbour(sh.ranks[size_t(k)])].push_back(s);
  std::vector<std::vector<NodeTerm>> own(terms);
  for (auto &t : own)
    std::sort(t.begin(), t.end(),
              [](const NodeTerm &a, const NodeTerm &b) { return a.key < b.key; });

  // 1. one message per neighbour: the term count of each node it shares, then the terms' keys
  // node by node (sized on arrival by a probe, so one round); the slots sent, in key order
  _send_offset.assign(nn + 1, 0);
  _recv_offset.assign(nn + 1, 0);
  std::vector<std::vector<std::int64_t>> sent(nn), got(nn);
  std::vector<MPI_Request> req(nn, MPI_REQUEST_NULL);
  for (size_t j = 0; j < nn; ++j)
  {
    for (Index s : nodes_of[j])
      sent[j].push_back(std::int64_t(own[size_t(s)].size()));
    for (Index s : nodes_of[j])
      for (const NodeTerm &t : own[size_t(s)])
      {
        sent[j].insert(sent[j].end(), t.key.begin(), t.key.end());
        _send_slot_host.push_back(t.slot);
      }
    _send_offset[j + 1] = Index(_send_slot_host.size());
    MPI_Isend(sent[j].data(), int(sent[j].size()), MPI_INT64_T, _neighbours[j], kKeyTag, comm,
              &req[j]);
  }
  std::vector<std::vector<Index>> recv_count(nn);
  std::vector<std::vector<std::int64_t>> recv_keys(nn);
  for (size_t j = 0; j < nn; ++j)
  {
    MPI_Status st;
    MPI_Probe(_neighbours[j], kKeyTag, comm, &st);
    int n = 0;
    MPI_Get_count(&st, MPI_INT64_T, &n);
    got[j].resize(size_t(n));
    MPI_Recv(got[j].data(), n, MPI_INT64_T, _neighbours[j], kKeyTag, comm, MPI_STATUS_IGNORE);
    const size_t nodes = nodes_of[j].size();
    if (size_t(n) < nodes)
      throw std::runtime_error("OrderedNodeSum: a short key message from rank " +
                               std::to_string(_neighbours[j]));
    Index received = 0;
    for (size_t q = 0; q < nodes; ++q)
    {
      recv_count[j].push_back(Index(got[j][q]));
      received += recv_count[j].back();
    }
    recv_keys[j].assign(got[j].begin() + long(nodes), got[j].end());
    if (recv_keys[j].size() != 3 * size_t(received))
      throw std::runtime_error("OrderedNodeSum: the key message of rank " +
                               std::to_string(_neighbours[j]) + " does not match its counts");
    _recv_offset[j + 1] = _recv_offset[j] + received;
  }
  MPI_Waitall(int(req.size()), req.data(), MPI_STATUSES_IGNORE);

  // 3. the recipe of each shared node: its own and received terms merged by key
  std::vector<std::vector<std::pair<TermKey, Index>>> merged(size_t(sh.size()));
  for (Index s = 0; s < sh.size(); ++s)
    for (const NodeTerm &t : own[size_t(s)])
      merged[size_t(s)].push_back({t.key, -(t.slot + 1)});
  for (size_t j = 0; j < nn; ++j)
  {
    Index at = _recv_offset[j];
    for (size_t q = 0; q < nodes_of[j].size(); ++q)
      for (Index c = 0; c < recv_count[j][q]; ++c, ++at)
      {
        const size_t k = 3 * size_t(at - _recv_offset[j]);
        const TermKey key{recv_keys[j][k], recv_keys[j][k + 1], recv_keys[j][k + 2]};
        merged[size_t(nodes_of[j][q])].push_back({key, at});
      }
  }
  _sum_offset_host.push_back(0);
  for (Index s = 0; s < sh.size(); ++s)
  {
    auto &m = merged[size_t(s)];
    std::sort(m.begin(), m.end(), [](const auto &a, const auto &b) { return a.first < b.first; });
    for (size_t i = 1; i < m.size(); ++i)
      if (m[i].first == m[i - 1].first)
        throw std::runtime_error("OrderedNodeSum: two terms of global node " +
                                 std::to_string(sh.global[size_t(s)]) + " have the same key");
    for (const auto &t : m)
      _sum_source_host.push_back(t.second);
    _sum_offset_host.push_back(Index(_sum_source_host.size()));
  }
  _node_host = sh.local;
  _node = toDevice(_node_host, "scpdyn::comm::orderedSum::node");
  _sum_offset = toDevice(_sum_offset_host, "scpdyn::comm::orderedSum::offset");
  _sum_source = toDevice(_sum_source_host, "scpdyn::comm::orderedSum::source");
  _send_slot = toDevice(_send_slot_host, "scpdyn::comm::orderedSum::send_slot");
  _send = RealView("scpdyn::comm::orderedSum::send", 3 * _send_slot_host.size());
  _recv = RealView("scpdyn::comm::orderedSum::recv", 3 * size_t(_recv_offset.back()));
  _send_host = Kokkos::create_mirror_view(HostSpace(), _send);
  _requests.assign(2 * nn, MPI_REQUEST_NULL);
  _recv_host = Kokkos::create_mirror_view(HostSpace(), _recv);
}

void OrderedNodeSum::exchange(const Real *send, Real *recv, int nc)
{
  std::vector<MPI_Request> &req = _requests;
  for (size_t j = 0; j < _neighbours.size(); ++j)
  {
    MPI_Irecv(recv + nc * _recv_offset[j], int(nc * (_recv_offset[j + 1] - _recv_offset[j])),
              MPI_DOUBLE, _neighbours[j], kValueTag, _comm, &req[j]);
    MPI_Isend(send + nc * _send_offset[j], int(nc * (_send_offset[j + 1] - _send_offset[j])),
              MPI_DOUBLE, _neighbours[j], kValueTag, _comm, &req[_neighbours.size() + j]);
  }
  MPI_Waitall(int(req.size()), req.data(), MPI_STATUSES_IGNORE);
}

void OrderedNodeSum::sum(const VectorView &values, const VectorView &out, bool from_zero)
{
  const auto slot = _send_slot;
  const auto send = _send;
  Kokkos::parallel_for(
      "scpdyn::comm::orderedSum::pack",
      Kokkos::RangePolicy<ExecSpace>(0, Index(_send_slot_host.size())),
      KOKKOS_LAMBDA(const Index k) {
        for (int d = 0; d < 3; ++d)
          send(3 * k + d) = values(slot(k), d);
      });
  ExecSpace().fence();
  if (_send_host.data() != _send.data())
    Kokkos::deep_copy(_send_host, _send);
  exchange(_send_host.data(), _recv_host.data(), 3);
  if (_bytes_sent)
    *_bytes_sent += bytesPerVectorSum();
  if (_recv_host.data() != _recv.data())
    Kokkos::deep_copy(_recv, _recv_host);
  const auto node = _node;
  const auto offset = _sum_offset;
  const auto source = _sum_source;
  const auto recv = _recv;
  // additions only, in the recipe's order on every rank: the serial run's bits
  Kokkos::parallel_for(
      "scpdyn::comm::orderedSum::sum", Kokkos::RangePolicy<ExecSpace>(0, Index(node.extent(0))),
      KOKKOS_LAMBDA(const Index s) {
        const Index n = node(s);
        Real t[3] = {0, 0, 0};
        if (!from_zero)
          for (int d = 0; d < 3; ++d)
            t[d] = out(n, d);
        for (Index k = offset(s); k < offset(s + 1); ++k)
        {
          const Index src = source(k);
          for (int d = 0; d < 3; ++d)
            t[d] += src < 0 ? values(-src - 1, d) : recv(3 * src + d);
        }
        for (int d = 0; d < 3; ++d)
          out(n, d) = t[d];
      });
}

void OrderedNodeSum::sumHost(const std::vector<Real> &values, int nc, std::vector<Real> &out)
{
  std::vector<Real> send(size_t(nc) * _send_slot_host.size());
  for (size_t k = 0; k < _send_slot_host.size(); ++k)
    for (int d = 0; d < nc; ++d)
      send[size_t(nc) * k + size_t(d)] = values[size_t(nc * _send_slot_host[k] + d)];
  std::vector<Real> recv(size_t(nc) * size_t(_recv_offset.back()));
  exchange(send.data(), recv.data(), nc);
  for (size_t s = 0; s < _node_host.size(); ++s)
    for (int d = 0; d < nc; ++d)
    {
      Real t = 0;
      for (Index k = _sum_offset_host[s]; k < _sum_offset_host[s + 1]; ++k)
      {
        const Index src = _sum_source_host[size_t(k)];
        t += src < 0 ? values[size_t(nc * (-src - 1) + d)] : recv[size_t(nc * src + d)];
      }
      out[size_t(nc * _node_host[s] + d)] = t;
    }
}

} // namespace scpdyn
