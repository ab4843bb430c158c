// Ghost contact faces: selection by global bins (step 4) and the owner -> ghost node copy
// (step 8). See GhostFaces.hpp.
#include "parallel/GhostFaces.hpp"
#include "core/HostCopy.hpp"

#include "parallel/Mpi.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace scpdyn
{
namespace
{

constexpr int kFaceNodes = 5; ///< 4 face nodes + the 1D back node
constexpr int kFaceHead = 7;  ///< key, part, surface, nodes, rigid, mass, depth
constexpr int kFaceWords = kFaceHead + kFaceNodes * 5; ///< doubles per face descriptor
constexpr int kTagCount = 7401, kTagData = 7402, kTagGather = 7403;

using Bins = std::vector<long long>;

bool finalised()
{
  int f = 0;
  MPI_Finalized(&f);
  return f != 0;
}

/// Exchange one vector per neighbour (sizes first); `out[j]` receives neighbour j's vector.
template <class T>
void exchange(MPI_Comm comm, const std::vector<int> &nbr, const std::vector<std::vector<T>> &in,
              std::vector<std::vector<T>> &out, MPI_Datatype type, std::size_t &bytes)
{
  const size_t n = nbr.size();
  std::vector<long long> send_count(n), recv_count(n);
  std::vector<MPI_Request> req(2 * n, MPI_REQUEST_NULL);
  for (size_t j = 0; j < n; ++j)
  {
    send_count[j] = (long long)in[j].size();
    MPI_Irecv(&recv_count[j], 1, MPI_LONG_LONG, nbr[j], kTagCount, comm, &req[j]);
    MPI_Isend(&send_count[j], 1, MPI_LONG_LONG, nbr[j], kTagCount, comm, &req[n + j]);
  }
  MPI_Waitall(int(req.size()), req.data(), MPI_STATUSES_IGNORE);
  out.assign(n, {});
  for (size_t j = 0; j < n; ++j)
  {
    out[j].resize(size_t(recv_count[j]));
    MPI_Irecv(out[j].data(), int(recv_count[j]), type, nbr[j], kTagData, comm, &req[j]);
    MPI_Isend(in[j].data(), int(in[j].size()), type, nbr[j], kTagData, comm, &req[n + j]);
    bytes += sizeof(long long) + in[j].size() * sizeof(T);
  }
  MPI_Waitall(int(req.size()), req.data(), MPI_STATUSES_IGNORE);
}

} // namespace

GhostFaces::GhostFaces(MPI_Comm comm, std::vector<Index> global_node, std::vector<Real> node_mass,
                       std::vector<std::array<int, 3>> node_bc)
    : _global_node(std::move(global_node)), _node_mass(std::move(node_mass)),
      _node_bc(std::move(node_bc))
{
  MPI_Comm_dup(comm, &_comm);
  MPI_Comm_rank(_comm, &_rank);
  MPI_Comm_size(_comm, &_size);
  if (_node_mass.size() != _global_node.size() || _node_bc.size() != _global_node.size())
    throw std::runtime_error("GhostFaces: node data sizes differ");
}

GhostFaces::~GhostFaces()
{
  if (_comm != MPI_COMM_NULL && !finalised())
    MPI_Comm_free(&_comm);
}

void GhostFaces::rebuild(const std::vector<GhostFaceDesc> &faces,
                         const std::vector<std::array<Real, 3>> &centroids, Real bin_size, int dim)
{
  _bytes_rebuild = 0;
  // the global grid: the same origin and edge on every rank
  std::array<Real, 3> lo = {1e300, 1e300, 1e300}, hi = {-1e300, -1e300, -1e300};
  for (const auto &c : centroids)
    for (int d = 0; d < 3; ++d)
    {
      lo[size_t(d)] = std::min(lo[size_t(d)], c[size_t(d)]);
      hi[size_t(d)] = std::max(hi[size_t(d)], c[size_t(d)]);
    }
  allReduceBox(lo, hi, _comm);
  const Real size = bin_size > 0 ? bin_size : 1.0;
  long long n[3] = {1, 1, 1};
  const bool any = lo[0] <= hi[0];
  for (int d = 0; d < dim && any; ++d)
    n[d] = (long long)std::floor((hi[size_t(d)] - lo[size_t(d)]) / size) + 1;
  auto cell = [&](const std::array<Real, 3> &c, int d) {
    if (d >= dim)
      return 0LL;
    const long long i = (long long)std::floor((c[size_t(d)] - lo[size_t(d)]) / size);
    return std::min(std::max(i, 0LL), n[d] - 1);
  };
  std::vector<std::array<long long, 3>> cells(faces.size());
  Bins mine;
  long long box[7] = {faces.empty() ? 0 : 1, n[0], n[1], n[2], -1, -1, -1};
  for (size_t f = 0; f < faces.size(); ++f)
  {
    for (int d = 0; d < 3; ++d)
    {
      const long long i = cell(centroids[f], d);
      cells[f][size_t(d)] = i;
      box[1 + d] = std::min(box[1 + d], i);
      box[4 + d] = std::max(box[4 + d], i);
    }
    mine.push_back(cells[f][0] + n[0] * (cells[f][1] + n[1] * cells[f][2]));
  }
  std::sort(mine.begin(), mine.end());
  mine.erase(std::unique(mine.begin(), mine.end()), mine.end());

  // bounding boxes (in bins) of every rank; neighbours: boxes within one bin of each other
  std::vector<long long> boxes(size_t(7 * _size));
  MPI_Allgather(box, 7, MPI_LONG_LONG, boxes.data(), 7, MPI_LONG_LONG, _comm);
  _bytes_rebuild += sizeof box;
  _neighbours.clear();
  for (int r = 0; r < _size; ++r)
  {
    const long long *b = &boxes[size_t(7 * r)];
    if (r == _rank || !box[0] || !b[0])
      continue;
    bool overlap = true;
    for (int d = 0; d < 3; ++d)
      overlap = overlap && b[1 + d] <= box[4 + d] + 1 && b[4 + d] >= box[1 + d] - 1;
    if (overlap)
      _neighbours.push_back(r);
  }
  const size_t nn = _neighbours.size();

  // occupied bins with the neighbours, then the faces each of them needs
  std::vector<Bins> bins_out(nn, mine), bins_in;
  exchange(_comm, _neighbours, bins_out, bins_in, MPI_LONG_LONG, _bytes_rebuild);
  std::vector<std::vector<double>> desc_out(nn), desc_in;
  std::vector<std::vector<Index>> sent_nodes(nn); // global ids, per neighbour
  _send_face.clear();
  _send_face_offset.assign(1, 0);
  for (size_t j = 0; j < nn; ++j)
  {
    const Bins &theirs = bins_in[j];
    for (size_t f = 0; f < faces.size(); ++f)
    {
      bool near = false;
      for (int dz = -1; dz <= 1 && !near; ++dz)
        for (int dy = -1; dy <= 1 && !near; ++dy)
          for (int dx = -1; dx <= 1 && !near; ++dx)
          {
            const long long i = cells[f][0] + dx, k = cells[f][1] + dy, l = cells[f][2] + dz;
            if (i < 0 || k < 0 || l < 0 || i >= n[0] || k >= n[1] || l >= n[2])
              continue;
            near = std::binary_search(theirs.begin(), theirs.end(), i + n[0] * (k + n[1] * l));
          }
      if (!near || !faces[f].active)
        continue;
      _send_face.push_back(Index(f));
      const GhostFaceDesc &g = faces[f];
      std::vector<double> &o = desc_out[j];
      o.insert(o.end(), {double(g.key), double(g.part), double(g.surface), double(g.num_nodes),
                         double(g.rigid), g.mass, g.depth});
      for (int a = 0; a < kFaceNodes; ++a)
      {
        const bool used = a < 4 ? a < g.num_nodes : g.back >= 0;
        const Index k = used ? (a < 4 ? g.nodes[a] : g.back) : 0;
        const Index id = used ? _global_node[size_t(k)] : -1;
        o.insert(o.end(), {double(id), used ? _node_mass[size_t(k)] : 0.0,
                           double(used ? _node_bc[size_t(k)][0] : -1),
                           double(used ? _node_bc[size_t(k)][1] : -1),
                           double(used ? _node_bc[size_t(k)][2] : -1)});
        if (used)
          sent_nodes[j].push_back(id);
      }
    }
    _send_face_offset.push_back(Index(_send_face.size()));
  }
  exchange(_comm, _neighbours, desc_out, desc_in, MPI_DOUBLE, _bytes_rebuild);

  // ghost nodes: the remote face nodes this rank does not hold, ascending global id
  const Index num_local = numLocalNodes();
  auto localOf = [&](Index id) {
    const auto it = std::lower_bound(_global_node.begin(), _global_node.end(), id);
    return it != _global_node.end() && *it == id ? Index(it - _global_node.begin()) : Index(-1);
  };
  std::map<Index, std::pair<Real, std::array<int, 3>>> ghost; // global id -> mass, bc
  for (const auto &in : desc_in)
    for (size_t q = 0; q + kFaceWords <= in.size(); q += kFaceWords)
      for (int a = 0; a < kFaceNodes; ++a)
      {
        const double *w = &in[q + kFaceHead + size_t(5 * a)];
        const Index id = Index(w[0]);
        if (id >= 0 && localOf(id) < 0)
          ghost[id] = {w[1], {int(w[2]), int(w[3]), int(w[4])}};
      }
  _ghost_global.clear();
  _ghost_mass.clear();
  _ghost_bc.clear();
  for (const auto &kv : ghost)
  {
    _ghost_global.push_back(kv.first);
    _ghost_mass.push_back(kv.second.first);
    _ghost_bc.push_back(kv.second.second);
  }
  auto nodeOf = [&](Index id) {
    const Index l = localOf(id);
    if (l >= 0)
      return l;
    return num_local + Index(std::lower_bound(_ghost_global.begin(), _ghost_global.end(), id) -
                             _ghost_global.begin());
  };

  _faces.clear();
  std::vector<std::vector<Index>> recv_nodes(nn); // global ids, per neighbour
  for (size_t j = 0; j < nn; ++j)
    for (size_t q = 0; q + kFaceWords <= desc_in[j].size(); q += kFaceWords)
    {
      const double *w = &desc_in[j][q];
      GhostFaceDesc g;
      g.key = long(w[0]);
      g.part = int(w[1]);
      g.surface = int(w[2]);
      g.num_nodes = int(w[3]);
      g.rigid = int(w[4]);
      g.mass = w[5];
      g.depth = w[6];
      for (int a = 0; a < kFaceNodes; ++a)
      {
        const Index id = Index(w[kFaceHead + 5 * a]);
        if (id < 0)
          continue;
        (a < 4 ? g.nodes[a] : g.back) = nodeOf(id);
        recv_nodes[j].push_back(id);
      }
      _faces.push_back(g);
    }
  std::sort(_faces.begin(), _faces.end(),
            [](const GhostFaceDesc &a, const GhostFaceDesc &b) { return a.key < b.key; });
  _recv_face.clear();
  _recv_face_offset.assign(1, 0);
  for (size_t j = 0; j < nn; ++j)
  {
    for (size_t q = 0; q + kFaceWords <= desc_in[j].size(); q += kFaceWords)
    {
      const long key = long(desc_in[j][q]);
      const auto it = std::lower_bound(_faces.begin(), _faces.end(), key,
                                       [](const GhostFaceDesc &a, long k) { return a.key < k; });
      _recv_face.push_back(Index(it - _faces.begin()));
    }
    _recv_face_offset.push_back(Index(_recv_face.size()));
  }

  // per-cycle lists: the nodes of the faces exchanged with each neighbour, ascending global
  // id on both ends; a ghost node sent by several ranks is taken from the lowest of them
  std::vector<Index> send_node, recv_slot;
  std::vector<char> taken(_ghost_global.size(), 0);
  _send_offset.assign(1, 0);
  _recv_offset.assign(1, 0);
  for (size_t j = 0; j < nn; ++j)
  {
    for (auto *list : {&sent_nodes[j], &recv_nodes[j]})
    {
      std::sort(list->begin(), list->end());
      list->erase(std::unique(list->begin(), list->end()), list->end());
    }
    for (Index id : sent_nodes[j])
      send_node.push_back(localOf(id));
    for (Index id : recv_nodes[j])
    {
      const Index k = nodeOf(id);
      const bool take = k >= num_local && !taken[size_t(k - num_local)];
      if (take)
        taken[size_t(k - num_local)] = 1;
      recv_slot.push_back(take ? k : -1);
    }
    _send_offset.push_back(Index(send_node.size()));
    _recv_offset.push_back(Index(recv_slot.size()));
  }
  _send_node = toDevice(send_node, "scpdyn::comm::ghost::send_node");
  _recv_slot = toDevice(recv_slot, "scpdyn::comm::ghost::recv_slot");
  _send_full = std::move(send_node);
  _recv_full = std::move(recv_slot);
  _send_full_offset = _send_offset;
  _recv_full_offset = _recv_offset;
}

void GhostFaces::restrictTo(const std::vector<char> &needed)
{
  const Index nl = numLocalNodes();
  std::vector<char> need(_ghost_global.size(), 0);
  for (size_t f = 0; f < _faces.size() && f < needed.size(); ++f)
    if (needed[f])
    {
      const GhostFaceDesc &g = _faces[f];
      for (int a = 0; a < 5; ++a)
      {
        const Index k = a < 4 ? (a < g.num_nodes ? g.nodes[a] : -1) : g.back;
        if (k >= nl)
          need[size_t(k - nl)] = 1;
      }
    }
  // positions (in the rebuild's list of each neighbour) of the nodes still needed
  const size_t nn = _neighbours.size();
  std::vector<std::vector<Index>> keep_out(nn), keep_in;
  std::vector<Index> recv_slot, send_node;
  _recv_offset.assign(1, 0);
  for (size_t j = 0; j < nn; ++j)
  {
    for (Index k = _recv_full_offset[j]; k < _recv_full_offset[j + 1]; ++k)
    {
      const Index g = _recv_full[size_t(k)];
      if (g >= nl && need[size_t(g - nl)])
      {
        keep_out[j].push_back(k - _recv_full_offset[j]);
        recv_slot.push_back(g);
      }
    }
    _recv_offset.push_back(Index(recv_slot.size()));
  }
  _bytes_restrict = 0;
  exchange(_comm, _neighbours, keep_out, keep_in, MPI_INT, _bytes_restrict);
  _send_offset.assign(1, 0);
  for (size_t j = 0; j < nn; ++j)
  {
    for (Index q : keep_in[j])
      send_node.push_back(_send_full[size_t(_send_full_offset[j] + q)]);
    _send_offset.push_back(Index(send_node.size()));
  }
  _send_node = toDevice(send_node, "scpdyn::comm::ghost::send_node");
  _recv_slot = toDevice(recv_slot, "scpdyn::comm::ghost::recv_slot");
}

void GhostFaces::gatherFaces(const std::vector<Real> &local, std::vector<Real> &ghost)
{
  const size_t nn = _neighbours.size();
  std::vector<Real> send(_send_face.size()), recv(_recv_face.size());
  for (size_t k = 0; k < _send_face.size(); ++k)
    send[k] = local[size_t(_send_face[k])];
  std::vector<MPI_Request> req(2 * nn, MPI_REQUEST_NULL);
  for (size_t j = 0; j < nn; ++j)
  {
    const Index r0 = _recv_face_offset[j], s0 = _send_face_offset[j];
    MPI_Irecv(recv.data() + r0, int(_recv_face_offset[j + 1] - r0), MPI_DOUBLE, _neighbours[j],
              kTagGather + 1, _comm, &req[j]);
    MPI_Isend(send.data() + s0, int(_send_face_offset[j + 1] - s0), MPI_DOUBLE, _neighbours[j],
              kTagGather + 1, _comm, &req[nn + j]);
  }
  MPI_Waitall(int(req.size()), req.data(), MPI_STATUSES_IGNORE);
  ghost.assign(_faces.size(), 0.0);
  for (size_t k = 0; k < _recv_face.size(); ++k)
    ghost[size_t(_recv_face[k])] = recv[k];
}

void GhostFaces::gather(const VectorView *fields, int count, bool sum_last_two)
{
  const size_t nn = _neighbours.size();
  const int packed = sum_last_two ? count - 1 : count; // fields on the wire
  const int nc = 3 * packed;
  const Index ns = Index(_send_node.extent(0)), nr = Index(_recv_slot.extent(0));
  if (_send_buf.extent(0) < size_t(ns * nc))
    _send_buf = DeviceView<Real *>("scpdyn::comm::ghost::send", size_t(ns * nc));
  if (_recv_buf.extent(0) < size_t(nr * nc))
    _recv_buf = DeviceView<Real *>("scpdyn::comm::ghost::recv", size_t(nr * nc));
  auto send = _send_buf, recv = _recv_buf;
  auto send_node = _send_node, recv_slot = _recv_slot;
  auto send_host = Kokkos::create_mirror_view(send);
  auto recv_host = Kokkos::create_mirror_view(recv);
  std::vector<MPI_Request> req(2 * nn, MPI_REQUEST_NULL);
  for (size_t j = 0; j < nn; ++j)
  {
    const Index first = _recv_offset[j];
    MPI_Irecv(recv_host.data() + size_t(first * nc), int((_recv_offset[j + 1] - first) * nc),
              MPI_DOUBLE, _neighbours[j], kTagGather, _comm, &req[j]);
  }
  for (int f = 0; f < packed; ++f)
  {
    const VectorView field = fields[f];
    const VectorView other = sum_last_two && f == packed - 1 ? fields[count - 1] : VectorView();
    const bool add = other.extent(0) > 0;
    Kokkos::parallel_for(
        "scpdyn::comm::ghost::pack", Kokkos::RangePolicy<ExecSpace>(0, ns),
        KOKKOS_LAMBDA(const Index k) {
          const Index n = send_node(k);
          for (int c = 0; c < 3; ++c)
            send(k * nc + 3 * f + c) = add ? field(n, c) + other(n, c) : field(n, c);
        });
  }
  Kokkos::deep_copy(send_host, send);
  for (size_t j = 0; j < nn; ++j)
  {
    const Index first = _send_offset[j];
    const int words = int((_send_offset[j + 1] - first) * nc);
    MPI_Isend(send_host.data() + size_t(first * nc), words, MPI_DOUBLE, _neighbours[j], kTagGather,
              _comm, &req[nn + j]);
  }
  _bytes_gather = size_t(ns) * size_t(nc) * sizeof(Real);
  _bytes_total += _bytes_gather;
  MPI_Waitall(int(req.size()), req.data(), MPI_STATUSES_IGNORE);
  Kokkos::deep_copy(recv, recv_host);
  for (int f = 0; f < count; ++f)
  {
    const VectorView field = fields[f];
    if (Index(field.extent(0)) < numLocalNodes() + numGhostNodes())
      throw std::logic_error("GhostFaces::gather: a field has no room for the ghost nodes");
    const bool zero = f == packed; // the second of a summed pair
    Kokkos::parallel_for(
        "scpdyn::comm::ghost::unpack", Kokkos::RangePolicy<ExecSpace>(0, nr),
        KOKKOS_LAMBDA(const Index k) {
          const Index g = recv_slot(k);
          if (g >= 0)
            for (int c = 0; c < 3; ++c)
              field(g, c) = zero ? 0.0 : recv(k * nc + 3 * f + c);
        });
  }
  Kokkos::fence();
}

} // namespace scpdyn
