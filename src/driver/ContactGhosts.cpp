// Contact of a decomposed run (docs/theory.md 2.2, steps 3, 4 and 8): the ghost contact
// faces a rank needs, the ghost nodes they reference, and the per-cycle owner -> ghost copy.
#include "parallel/Decomposition.hpp"
#include "driver/Solver.hpp"

#include "contact/ContactSystem.hpp"
#include "parallel/GhostFaces.hpp"
#include "parallel/Mpi.hpp"

#include <algorithm>
#include <cmath>

namespace scpdyn
{

void Solver::ensureNodeCapacity(Index count)
{
  // ghost nodes live after the local ones in x, v, f_int, f_ext, f_contact, mass and bc; the
  // Views grow
  // (by half again) when a search needs more, and never shrink
  if (Index(_m.nodes.x.extent(0)) >= count)
    return;
  const size_t n = size_t(std::max<Index>(count, Index(1.5 * _m.nodes.x.extent(0))));
  auto grow = [n](auto &view) {
    auto bigger = std::decay_t<decltype(view)>(std::string(view.label()), n);
    const auto keep = std::make_pair(size_t(0), size_t(view.extent(0)));
    Kokkos::deep_copy(Kokkos::subview(bigger, keep, Kokkos::ALL), view);
    view = bigger;
  };
  grow(_m.nodes.x);
  grow(_m.nodes.v);
  grow(_m.nodes.f_int);
  grow(_m.nodes.f_ext);
  if (_m.nodes.f_contact.extent(0) != 0)
    grow(_m.nodes.f_contact);
  grow(_m.nodes.bc);
  RealView mass(std::string(_m.nodes.mass.label()), n);
  Kokkos::deep_copy(
      Kokkos::subview(mass, std::make_pair(size_t(0), size_t(_m.nodes.mass.extent(0)))),
      _m.nodes.mass);
  _m.nodes.mass = mass;
}

void Solver::stepExchangeFaceConnectivity()
{
  if (!_m.contact || !_m.dd || !_m.contact->searchDue(_cycle))
    return;
  ScopedStep t(_timers, "04_face_connectivity");
  rebuildGhostFaces();
}

void Solver::rebuildGhostFaces()
{
  // this rank's faces at the half step (as the search will see them): centroid (node mean)
  // and size (twice the largest node distance from it, with the 1D element's other node)
  const std::vector<GhostFaceDesc> &own = _m.dd->own_faces;
  const Index nf = Index(own.size());
  DeviceView<Index *[5]> nodes("ghost_face_nodes", size_t(nf));
  auto h_nodes = Kokkos::create_mirror_view(nodes);
  for (Index f = 0; f < nf; ++f)
    for (int a = 0; a < 5; ++a)
      h_nodes(f, a) = a < 4 ? (a < own[size_t(f)].num_nodes ? own[size_t(f)].nodes[a] : -1)
                            : own[size_t(f)].back;
  Kokkos::deep_copy(nodes, h_nodes);
  DeviceView<Real *[4]> geo("ghost_face_centroid", size_t(nf));
  auto x = _m.nodes.x, v = _m.nodes.v;
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
  size = allReduceMax(size, _m.comm);
  // a common plane needs overlapping faces within the search gap: centroids closer than two
  // face sizes plus the gap (2 r >= a face's diameter: at least the search's own gap)
  const Real gap = _m.contact->searchGap(size);
  _m.dd->ghosts->rebuild(own, centroids, 2 * size + gap, _m.deck.dimension);
  _m.dd->rebuild_bytes += _m.dd->ghosts->bytesLastRebuild();

  const Index nl = _m.nodes.count, ng = _m.dd->ghosts->numGhostNodes();
  ensureNodeCapacity(nl + ng);
  if (ng > 0)
  {
    const auto range = std::make_pair(size_t(nl), size_t(nl + ng));
    auto m = Kokkos::create_mirror_view(Kokkos::subview(_m.nodes.mass, range));
    auto b = Kokkos::create_mirror_view(Kokkos::subview(_m.nodes.bc, range, Kokkos::ALL));
    for (Index i = 0; i < ng; ++i)
    {
      m(i) = _m.dd->ghosts->ghostMass()[size_t(i)];
      for (int d = 0; d < 3; ++d)
        b(i, d) = _m.dd->ghosts->ghostBc()[size_t(i)][size_t(d)];
    }
    Kokkos::deep_copy(Kokkos::subview(_m.nodes.mass, range), m);
    Kokkos::deep_copy(Kokkos::subview(_m.nodes.bc, range, Kokkos::ALL), b);
  }
  _m.contact->setGhostFaces(_m.dd->ghosts->faces(), Index(_m.nodes.x.extent(0)),
                            _m.dd->shared_host);
}

void Solver::restrictGhosts()
{
  _m.dd->ghosts->restrictTo(_m.contact->ghostFacesInPlanes());
  _m.dd->rebuild_bytes += _m.dd->ghosts->bytesLastRestrict();
}

void Solver::stepExchangeGhostFaceData()
{
  if (!_m.contact || !_m.dd)
    return;
  ScopedStep t(_timers, "08_ghost_face_data");
  // x^n, v^n and the complete nodal force of step 7 (for the contact's v*, which adds
  // f_int + f_ext), exact copies
  const VectorView fields[4] = {_m.nodes.x, _m.nodes.v, _m.nodes.f_int, _m.nodes.f_ext};
  _m.dd->ghosts->gather(fields, 4, true);
  if (_m.contact->hasExplicit())
  {
    std::vector<Real> ghost;
    _m.dd->ghosts->gatherFaces(_m.contact->ownFaceDensity(_m.elems), ghost);
    _m.contact->setGhostDensity(ghost);
  }
  if (_m.contact->needsFailureMeasures()) // the sleepy switch sees both faces' elements
    for (int column = 0; column < 2; ++column)
    {
      std::vector<Real> ghost;
      _m.dd->ghosts->gatherFaces(_m.contact->ownFaceFailure(_m.elems, column), ghost);
      _m.contact->setGhostFailure(column, ghost);
    }
}

} // namespace scpdyn
