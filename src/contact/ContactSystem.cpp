// Contact runtime: set-up, detection with history matching, outputs (scp-method.md 3, 12).
// The per-cycle force kernels are in ContactForces.cpp.
#include "contact/ContactSystem.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace scpdyn
{
namespace
{

/// Index of the pair (f1, f2) in the sorted CP list, or -1 (3.3: the face-pair key is the match).
KOKKOS_INLINE_FUNCTION Index findPair(const IndexView &a1, const IndexView &a2, Index n, Index f1,
                                      Index f2)
{
  Index lo = 0, hi = n;
  while (lo < hi)
  {
    const Index mid = lo + (hi - lo) / 2;
    const bool less = a1(mid) < f1 || (a1(mid) == f1 && a2(mid) < f2);
    if (less)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo < n && a1(lo) == f1 && a2(lo) == f2 ? lo : -1;
}

CommonPlaneData allocatePlanes(Index n)
{
  CommonPlaneData c;
  const size_t m = size_t(n);
  c.count = n;
  c.face1 = IndexView("cp_face1", m);
  c.face2 = IndexView("cp_face2", m);
  c.state = DeviceView<CpState *>("cp_state", m);
  c.params = DeviceView<JointParams *>("cp_params", m);
  c.normal = VectorView("cp_normal", m);
  c.poc = VectorView("cp_poc", m);
  c.force = VectorView("cp_force", m);
  c.area = RealView("cp_area", m);
  c.face_area1 = RealView("cp_face_area1", m);
  c.face_area2 = RealView("cp_face_area2", m);
  c.mstar = RealView("cp_mstar", m);
  c.stored = RealView("cp_stored", m);
  c.w1 = DeviceView<Real * [kMaxFaceNodes]>("cp_w1", m);
  c.w2 = DeviceView<Real * [kMaxFaceNodes]>("cp_w2", m);
  c.status = IndexView("cp_status", m);
  return c;
}

} // namespace

ContactSystem::ContactSystem(const ContactMeshInput &in)
{
  const Deck &deck = *in.deck;
  _dim = deck.dimension;
  _axisym = _dim == 2 && deck.geometry == Geometry2D::Axisymmetric;
  _search_interval = deck.contact.search_interval;
  _passes = deck.contact.constraint_passes;
  _search_gap = deck.contact.search_gap;
  for (const auto &p : in.mesh->parts)
    _part_names.push_back(p.name);
  _faces = buildContactFaces(in, _info);
  for (size_t s = 0; s < deck.contact.surfaces.size(); ++s)
  {
    const std::string &o = deck.contact.surfaces[s].option;
    _has_constraints = _has_constraints || o == "sticky" || o == "slide_line";
    _has_explicit = _has_explicit || o == "explicit";
    _has_sticky = _has_sticky || o == "sticky";
    _has_slide = _has_slide || o == "slide_line";
  }
  const size_t n = size_t(in.nodes.count);
  _vstar = VectorView("contact_vstar", n);
  _dv = VectorView("contact_dv", n);
  _fc = VectorView("contact_force", n);
  _impulse = VectorView("contact_impulse", n);
  _cp = allocatePlanes(0);
}

bool ContactSystem::searchDue(long cycle) const
{
  return cycle == 0 || (_search_interval > 0 && cycle % _search_interval == 0);
}

void ContactSystem::sortIntoBins(const NodeFields &nodes, Real dt, long cycle)
{
  if (!searchDue(cycle) || _faces.count == 0)
    return;
  computeFaceGeometry(_faces, nodes, dt, _dim, _axisym, _geom);
  const Real gap = _search_gap > 0 ? _search_gap : _geom.h_max;
  // (3.2) every pair with overlap and gap <= g_search lies in the same or a neighbouring bin
  sortFacesIntoBins(_geom, _faces.count, _dim, std::max(2.0 * _geom.h_max, _geom.h_max + gap),
                    _bins);
  _binned_cycle = cycle;
}

void ContactSystem::detect(const NodeFields &nodes, Real dt)
{
  const Real gap = _search_gap > 0 ? _search_gap : _geom.h_max;
  const CandidatePairs P =
      findCandidatePairs(_faces, _geom, _bins, nodes, dt, _dim, _axisym, gap);
  const CommonPlaneData old = _cp;
  CommonPlaneData cp = allocatePlanes(P.count);
  const ContactFaceData F = _faces;
  auto x = nodes.x, v = nodes.v;
  const Real half_dt = 0.5 * dt;
  const int dim = _dim;
  const bool axisym = _axisym;
  Kokkos::parallel_for(
      "scpdyn::contact::matchPlanes", Kokkos::RangePolicy<ExecSpace>(0, P.count),
      KOKKOS_LAMBDA(const Index q) {
        const Index f1 = P.face1(q), f2 = P.face2(q);
        cp.face1(q) = f1;
        cp.face2(q) = f2;
        cp.params(q) = averageParams(F.params(F.surface(f1)), F.params(F.surface(f2)));
        const Index o = findPair(old.face1, old.face2, old.count, f1, f2);
        if (o >= 0)
        { // (3.3) the same face pair keeps its CP and history
          cp.state(q) = old.state(o);
          return;
        }
        Real x1[kMaxFaceNodes][3], x2[kMaxFaceNodes][3];
        const CpGeometry g = pairGeometry(F, f1, f2, x, v, half_dt, dim, axisym, x1, x2);
        cp.state(q) = initialCpState(g.u0, g.n, g.Ac); // (12), (D12)
      });
  _cp = cp;
  _max_count = std::max(_max_count, _cp.count);
}

ContactPointsHost ContactSystem::points() const
{
  ContactPointsHost h;
  const size_t n = size_t(_cp.count);
  auto poc = Kokkos::create_mirror_view_and_copy(HostSpace(), _cp.poc);
  auto area = Kokkos::create_mirror_view_and_copy(HostSpace(), _cp.area);
  auto state = Kokkos::create_mirror_view_and_copy(HostSpace(), _cp.state);
  auto params = Kokkos::create_mirror_view_and_copy(HostSpace(), _cp.params);
  auto status = Kokkos::create_mirror_view_and_copy(HostSpace(), _cp.status);
  auto f1 = Kokkos::create_mirror_view_and_copy(HostSpace(), _cp.face1);
  auto f2 = Kokkos::create_mirror_view_and_copy(HostSpace(), _cp.face2);
  for (size_t p = 0; p < n; ++p)
  {
    for (int d = 0; d < 3; ++d)
      h.poc.push_back(poc(p, d));
    const CpState &s = state(p);
    const bool active = status(p) != CpInactive;
    h.area.push_back(active ? area(p) : 0.0);
    h.normal_force.push_back(active ? s.Fn : 0.0);
    h.shear_force.push_back(active ? std::sqrt(s.Fs[0] * s.Fs[0] + s.Fs[1] * s.Fs[1] + s.Fs[2] * s.Fs[2]) : 0.0);
    h.closure.push_back(s.u);
    h.slip.push_back(s.usp * params(p).a);
    h.state.push_back(status(p));
    h.key1.push_back(double(_info[size_t(f1(p))].key));
    h.key2.push_back(double(_info[size_t(f2(p))].key));
  }
  return h;
}

std::string ContactSystem::describe(Index cp) const
{
  auto f1 = Kokkos::create_mirror_view_and_copy(HostSpace(), _cp.face1);
  auto f2 = Kokkos::create_mirror_view_and_copy(HostSpace(), _cp.face2);
  std::ostringstream os;
  auto face = [&](Index f) {
    const ContactFaceInfo &i = _info[size_t(f)];
    os << "(element " << i.mesh_element << " face " << i.local_face << " of part '"
       << _part_names[size_t(i.part)] << "')";
  };
  os << "common plane " << cp << " between faces ";
  face(f1(cp));
  os << " and ";
  face(f2(cp));
  return os.str();
}

} // namespace scpdyn
