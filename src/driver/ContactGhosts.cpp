// Contact of a decomposed run (issue 4, scp-method.md 2.2 steps 3, 4 and 8): the ghost contact
// faces a rank needs, the ghost nodes they reference, and the per-cycle owner -> ghost copy.
#include "driver/Decomposition.hpp"
#include "driver/Solver.hpp"

#include "contact/ContactSystem.hpp"
#include "parallel/GhostFaces.hpp"
#include "parallel/Mpi.hpp"

#include <algorithm>
#include <cmath>

namespace scpdyn
{

void Solver::setupContactGhosts()
{
  const Index n = _nodes.count;
  auto h_mass = Kokkos::create_mirror_view_and_copy(HostSpace(), _nodes.mass);
  auto h_bc = Kokkos::create_mirror_view_and_copy(HostSpace(), _nodes.bc);
  std::vector<Real> mass(static_cast<size_t>(n));
  std::vector<std::array<int, 3>> bc(static_cast<size_t>(n));
  for (Index k = 0; k < n; ++k)
  {
    mass[size_t(k)] = h_mass(k);
    bc[size_t(k)] = {h_bc(k, 0), h_bc(k, 1), h_bc(k, 2)};
  }
  _dd->ghosts = std::make_unique<GhostFaces>(_comm, _dd->global_node, mass, bc);
  _dd->own_faces = _contact->ownFaces();
  auto shared = Kokkos::create_mirror_view_and_copy(HostSpace(), _dd->shared_nodes);
  _dd->shared_host.assign(shared.data(), shared.data() + shared.extent(0));
  ContactComm cc;
  SolverDecomposition *dd = _dd.get();
  cc.sum_nodes = [dd](const VectorView &f) {
    dd->halo->sum(f);
    dd->ghosts->gather(&f, 1);
  };
  MPI_Comm comm = _comm;
  cc.sum = [comm](Real *v, int count) { allReduceSum(v, count, comm); };
  cc.max = [comm](Real v) { return allReduceMax(v, comm); };
  _contact->setComm(cc);
}

void Solver::ensureNodeCapacity(Index count)
{
  // ghost nodes live after the local ones in x, v, f_int, f_ext, f_contact, mass and bc; the
  // Views grow
  // (by half again) when a search needs more, and never shrink
  if (Index(_nodes.x.extent(0)) >= count)
    return;
  const size_t n = size_t(std::max<Index>(count, Index(1.5 * _nodes.x.extent(0))));
  auto grow = [n](auto &view) {
    auto bigger = std::decay_t<decltype(view)>(std::string(view.label()), n);
    const auto keep = std::make_pair(size_t(0), size_t(view.extent(0)));
    Kokkos::deep_copy(Kokkos::subview(bigger, keep, Kokkos::ALL), view);
    view = bigger;
  };
  grow(_nodes.x);
  grow(_nodes.v);
  grow(_nodes.f_int);
  grow(_nodes.f_ext);
  if (_nodes.f_contact.extent(0) != 0)
    grow(_nodes.f_contact);
  grow(_nodes.bc);
  RealView mass(std::string(_nodes.mass.label()), n);
  Kokkos::deep_copy(Kokkos::subview(mass, std::make_pair(size_t(0), size_t(_nodes.mass.extent(0)))),
                    _nodes.mass);
  _nodes.mass = mass;
}

void Solver::stepExchangeFaceConnectivity()
{
  if (!_contact || !_dd || !_contact->searchDue(_cycle))
    return;
  ScopedStep t(_timers, "04_face_connectivity");
  // this rank's faces at the half step (as the search will see them): centroid (node mean)
  // and size (twice the largest node distance from it, with the 1D element's other node)
  const std::vector<GhostFaceDesc> &own = _dd->own_faces;
  const Index nf = Index(own.size());
  DeviceView<Index * [5]> nodes("ghost_face_nodes", size_t(nf));
  auto h_nodes = Kokkos::create_mirror_view(nodes);
  for (Index f = 0; f < nf; ++f)
    for (int a = 0; a < 5; ++a)
      h_nodes(f, a) = a < 4 ? (a < own[size_t(f)].num_nodes ? own[size_t(f)].nodes[a] : -1)
                            : own[size_t(f)].back;
  Kokkos::deep_copy(nodes, h_nodes);
  DeviceView<Real * [4]> geo("ghost_face_centroid", size_t(nf));
  auto x = _nodes.x, v = _nodes.v;
  const Real h = 0.5 * _dt;
  Kokkos::parallel_for(
      "scpdyn::comm::ghost::faceCentroids", Kokkos::RangePolicy<ExecSpace>(0, nf),
      KOKKOS_LAMBDA(const Index f) {
        Real c[3] = {0, 0, 0}, p[5][3];
        int count = 0, with_back = 0;
        for (int a = 0; a < 5; ++a)
        {
          const Index k = nodes(f, a);
          if (k < 0)
            continue;
          for (int d = 0; d < 3; ++d)
            p[with_back][d] = x(k, d) + h * v(k, d);
          if (a < 4)
          {
            for (int d = 0; d < 3; ++d)
              c[d] += p[with_back][d];
            ++count;
          }
          ++with_back;
        }
        Real r = 0;
        for (int d = 0; d < 3; ++d)
          c[d] /= count;
        for (int a = 0; a < with_back; ++a)
        {
          Real s = 0;
          for (int d = 0; d < 3; ++d)
            s += (p[a][d] - c[d]) * (p[a][d] - c[d]);
          r = s > r ? s : r;
        }
        for (int d = 0; d < 3; ++d)
          geo(f, d) = c[d];
        geo(f, 3) = 2 * kmath::sqrt(r);
      });
  auto h_geo = Kokkos::create_mirror_view_and_copy(HostSpace(), geo);
  std::vector<std::array<Real, 3>> centroids(static_cast<size_t>(nf));
  Real size = 0;
  for (Index f = 0; f < nf; ++f)
  {
    centroids[size_t(f)] = {h_geo(f, 0), h_geo(f, 1), h_geo(f, 2)};
    size = std::max(size, h_geo(f, 3));
  }
  size = allReduceMax(size, _comm);
  // a common plane needs overlapping faces within the search gap: centroids closer than two
  // face sizes plus the gap (the search's own gap defaults to its largest face size)
  const Real gap = _deck.contact.search_gap > 0 ? _deck.contact.search_gap : size;
  _dd->ghosts->rebuild(own, centroids, 2 * size + gap, _deck.dimension);
  _dd->rebuild_bytes += _dd->ghosts->bytesLastRebuild();

  const Index nl = _nodes.count, ng = _dd->ghosts->numGhostNodes();
  ensureNodeCapacity(nl + ng);
  if (ng > 0)
  {
    const auto range = std::make_pair(size_t(nl), size_t(nl + ng));
    auto m = Kokkos::create_mirror_view(Kokkos::subview(_nodes.mass, range));
    auto b = Kokkos::create_mirror_view(Kokkos::subview(_nodes.bc, range, Kokkos::ALL));
    for (Index i = 0; i < ng; ++i)
    {
      m(i) = _dd->ghosts->ghostMass()[size_t(i)];
      for (int d = 0; d < 3; ++d)
        b(i, d) = _dd->ghosts->ghostBc()[size_t(i)][size_t(d)];
    }
    Kokkos::deep_copy(Kokkos::subview(_nodes.mass, range), m);
    Kokkos::deep_copy(Kokkos::subview(_nodes.bc, range, Kokkos::ALL), b);
  }
  _contact->setGhostFaces(_dd->ghosts->faces(), Index(_nodes.x.extent(0)), _dd->shared_host);
}

void Solver::restrictGhosts()
{
  _dd->ghosts->restrictTo(_contact->ghostFacesInPlanes());
  _dd->rebuild_bytes += _dd->ghosts->bytesLastRestrict();
}

void Solver::stepExchangeGhostFaceData()
{
  if (!_contact || !_dd)
    return;
  ScopedStep t(_timers, "08_ghost_face_data");
  // x^n, v^n and the complete nodal force of step 7 (for the contact's v*, which adds
  // f_int + f_ext), exact copies
  const VectorView fields[4] = {_nodes.x, _nodes.v, _nodes.f_int, _nodes.f_ext};
  _dd->ghosts->gather(fields, 4, true);
  if (_contact->hasExplicit())
  {
    std::vector<Real> ghost;
    _dd->ghosts->gatherFaces(_contact->ownFaceDensity(_elems), ghost);
    _contact->setGhostDensity(ghost);
  }
}

} // namespace scpdyn
