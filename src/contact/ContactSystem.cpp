// Contact runtime: set-up, detection with history matching, outputs (docs/theory.md 3, 12).
// The per-cycle force kernels are in ContactForces.cpp.
#include "contact/ContactSystem.hpp"
#include "core/HostCopy.hpp"
#include "contact/ContactKernels.hpp"

#include "parallel/GhostFaces.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace scpdyn
{
namespace
{

/// Index of the pair (k1, k2) of face keys in the sorted CP list, or -1 (3.3: the face-pair key
/// is the match; keys, not face indices, because a decomposed run's face list changes with its
/// ghost faces from one search to the next).
KOKKOS_INLINE_FUNCTION Index findPair(const DeviceView<long *> &a1, const DeviceView<long *> &a2,
                                      Index n, long f1, long f2)
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

} // namespace

ContactSystem::ContactSystem(const ContactMeshInput &in)
{
  const Deck &deck = *in.deck;
  _dim = deck.dimension;
  _axisym = _dim == 2 && deck.geometry == Geometry2D::Axisymmetric;
  _search_interval = deck.contact.search_interval;
  _passes = deck.contact.constraint_passes;
  _search_gap = deck.contact.search_gap;
  _gap_from_motion = deck.contact.search_gap_motion;
  _tie_points = _dim == 2 ? 2 : 1;
  // decomposed (in.global_count set), the shared nodes' sums in the serial order need the
  // slots at any thread count
  _gather_forces = orderedAssembly(deck, bool(in.global_count));
  for (const auto &p : in.mesh->parts)
    _part_names.push_back(p.name);
  _faces = buildContactFaces(in, _info);
  _own = _faces;
  _own_info = _info;
  _ghost_of_face.assign(_info.size(), -1);
  for (size_t s = 0; s < deck.contact.surfaces.size(); ++s)
  {
    const std::string &o = deck.contact.surfaces[s].option;
    const SurfaceSpec &spec = deck.contact.surfaces[s];
    _has_explicit = _has_explicit || o == "explicit";
    _has_slide = _has_slide || o == "slide_line";
    _has_sleepy = _has_sleepy || o == "sleepy";
    _failure_from_elements =
        _failure_from_elements || (o == "sleepy" && spec.failure_measure != "time");
    _has_friction = _has_friction || ((o == "slide_line" || o == "sleepy") && spec.mu_static > 0) ||
                    ((o == "explicit" || o == "implicit") && spec.phi1 > 0); // self-contact, 11.5
    _surface_labels.push_back("'" + deck.contact.surfaces[s].name + "' (option " + o + ")");
  }
  _damage_slot = toDevice(std::vector<Index>(in.damage_slot.begin(), in.damage_slot.end()),
                          "contact_damage_slot");
  const size_t n = size_t(in.nodes.count);
  _vstar = VectorView("contact_vstar", n);
  _dv = VectorView("contact_dv", n);
  _fc = VectorView("contact_force", n);
  _impulse = VectorView("contact_impulse", n);
  _cp = allocatePlanes(0);
  ++_cp_generation;
}

void ContactSystem::declareLateNodes(LateNodes &late) const
{
  late.declare("contact", _faces.nodes_used);
  late.declare("contact (1D face orientation)", _faces.back);
}

void ContactSystem::sortIntoBins(const NodeFields &nodes, Real dt, long cycle)
{
  if (!searchDue(cycle) || (_faces.count == 0 && !_comm.max))
    return;
  computeFaceGeometry(_faces, nodes, dt, _dim, _axisym, _geom);
  if (_comm.max) // the search distance g_search = h_max must not depend on the decomposition
    _geom.h_max = _comm.max(std::max(_geom.h_max, 0.0));
  const Real gap = searchGap(_geom.h_max);
  // (3.2) every pair with overlap and gap <= g_search lies in the same or a neighbouring bin
  sortFacesIntoBins(_geom, _faces.count, _dim, std::max(2.0 * _geom.h_max, _geom.h_max + gap),
                    _bins);
  _binned_cycle = cycle;
}

void ContactSystem::detect(const NodeFields &nodes, Real dt)
{
  const Real gap = searchGap(_geom.h_max);
  const CandidatePairs P = findCandidatePairs(_faces, _geom, _bins, nodes, dt, _dim, _axisym, gap);
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
        cp.key1(q) = F.key(f1);
        cp.key2(q) = F.key(f2);
        cp.params(q) =
            planeParams(F.params(F.surface(f1)), F.params(F.surface(f2)), F.part(f1) == F.part(f2));
        const Index o = findPair(old.key1, old.key2, old.count, F.key(f1), F.key(f2));
        if (o >= 0)
        { // (3.3) the same face pair keeps its CP and history
          cp.state(q) = old.state(o);
          return;
        }
        Real x1[kMaxFaceNodes][3], x2[kMaxFaceNodes][3];
        const bool impact = contact_kernels::usesImpactNormal(cp.params(q).option);
        const CpGeometry g = pairGeometry(F, f1, f2, x, v, half_dt, dim, axisym, x1, x2, impact);
        // (D7) at x^n, not at the half step: the step's closure increment (7) or (20) takes
        // u from the start to the end of the step, so the half-step overlap would count
        // Vn dt/2 twice (see docs/theory.md, contact runtime)
        const CpGeometry g0 = pairGeometry(F, f1, f2, x, v, 0.0, dim, axisym, x1, x2, impact);
        Real u0 = g0.u0;
        if (!g0.valid)
        {
          Real V1[3], V2[3], Vn = 0;
          contact_kernels::faceVelocity(F, f1, v, V1);
          contact_kernels::faceVelocity(F, f2, v, V2);
          for (int d = 0; d < 3; ++d)
            Vn += (V1[d] - V2[d]) * g.n[d];
          u0 = g.u0 - half_dt * Vn;
        }
        cp.state(q) = initialCpState(u0, g.n, g.Ac); // (12), (D12)
      });
  _cp = cp;
  ++_cp_generation;
  countPlanes();
}

void ContactSystem::countPlanes()
{
  const ContactFaceData F = _faces;
  const CommonPlaneData cp = _cp;
  // the CPs counted on this rank (decomposed: those of its face 1), the self-contact CPs among
  // them (slide lines, whatever the surfaces' options, 11.5) and the CPs of the velocity-
  // constraint options (slide line, sticky, sleepy; self-contact among them)
  Index owned = 0, self = 0, constraint = 0;
  Kokkos::parallel_reduce(
      "scpdyn::contact::countPlanes", Kokkos::RangePolicy<ExecSpace>(0, cp.count),
      KOKKOS_LAMBDA(const Index q, Index &n, Index &s, Index &c) {
        if (F.ghost(cp.face1(q)) != 0)
          return;
        ++n;
        s += F.part(cp.face1(q)) == F.part(cp.face2(q)) ? 1 : 0;
        c += contact_kernels::isConstraint(cp.params(q).option) ? 1 : 0;
      },
      owned, self, constraint);
  if (_comm.sum)
  {
    Real counts[3] = {Real(owned), Real(self), Real(constraint)};
    _comm.sum(counts, 3);
    owned = Index(counts[0]), self = Index(counts[1]), constraint = Index(counts[2]);
  }
  _max_count = std::max(_max_count, owned);
  _self_contact_planes = self;
  _constraint_planes = constraint;
}

Real ContactSystem::firstTimeStep(const NodeFields &nodes, const ElementFields &elements,
                                  Real dt_element)
{
  if (!_has_explicit || (_faces.count == 0 && !_comm.sum))
    return 1e300;
  const Index max_count = _max_count;
  sortIntoBins(nodes, 0.0, 0);
  detect(nodes, 0.0);
  const ContactFaceData F = _faces;
  const CommonPlaneData cp = _cp;
  auto x = nodes.x, v = nodes.v;
  auto emass = elements.mass, volume = elements.volume;
  const int dim = _dim;
  const bool axisym = _axisym;
  Real dt_min = 1e300;
  Kokkos::parallel_reduce(
      "scpdyn::contact::firstTimeStep", Kokkos::RangePolicy<ExecSpace>(0, cp.count),
      KOKKOS_LAMBDA(const Index p, Real &m) {
        const JointParams &P = cp.params(p);
        if (P.option != ContactOption::Explicit)
          return;
        const Index f1 = cp.face1(p), f2 = cp.face2(p);
        Real x1[kMaxFaceNodes][3], x2[kMaxFaceNodes][3];
        const CpGeometry g = pairGeometry(F, f1, f2, x, v, 0.0, dim, axisym, x1, x2);
        if (!cpIsActive(g)) // as in step 12: a CP without overlap does not limit
          return;
        Real V1[3], V2[3], Vn = 0;
        contact_kernels::faceVelocity(F, f1, v, V1);
        contact_kernels::faceVelocity(F, f2, v, V2);
        for (int d = 0; d < 3; ++d)
          Vn += (V1[d] - V2[d]) * g.n[d];
        const Real dt_c = contact_kernels::explicitCpTimeStep(F, P, cp.state(p), f1, f2, g.A1, g.A2,
                                                              Vn, emass, volume, dt_element);
        m = dt_c < m ? dt_c : m;
      },
      Kokkos::Min<Real>(dt_min));
  _cp = allocatePlanes(0);
  ++_cp_generation;
  _binned_cycle = -1;
  _max_count = max_count;
  return dt_min;
}

Real ContactSystem::globalSum(Real local) const
{
  if (_comm.sum)
    _comm.sum(&local, 1);
  return local;
}

void ContactSystem::setComm(const ContactComm &comm)
{
  _comm = comm;
  if (_comm.ordered_plan)
  {
    std::vector<std::uint8_t> copy(_comm.owned.size());
    for (size_t k = 0; k < copy.size(); ++k)
      copy[k] = _comm.shared_index[k] >= 0 && !_comm.owned[k] ? 1 : 0;
    _copy_node = toDevice(copy, "contact_copy_node");
  }
}

void ContactSystem::resizeNodeArrays(size_t n)
{
  if (_vstar.extent(0) == n)
    return;
  // local nodes keep their ids; only the impulse carries over (the others are per cycle)
  VectorView impulse("contact_impulse", n);
  const size_t keep = std::min(n, size_t(_impulse.extent(0)));
  Kokkos::deep_copy(Kokkos::subview(impulse, std::make_pair(size_t(0), keep), Kokkos::ALL),
                    Kokkos::subview(_impulse, std::make_pair(size_t(0), keep), Kokkos::ALL));
  _impulse = impulse;
  _vstar = VectorView("contact_vstar", n);
  _dv = VectorView("contact_dv", n);
  _fc = VectorView("contact_force", n);
}

std::vector<GhostFaceDesc> ContactSystem::ownFaces() const
{
  auto nodes = Kokkos::create_mirror_view_and_copy(HostSpace(), _own.nodes);
  auto nn = Kokkos::create_mirror_view_and_copy(HostSpace(), _own.num_nodes);
  auto surface = Kokkos::create_mirror_view_and_copy(HostSpace(), _own.surface);
  auto mass = Kokkos::create_mirror_view_and_copy(HostSpace(), _own.mass);
  auto depth = Kokkos::create_mirror_view_and_copy(HostSpace(), _own.depth);
  auto rigid = Kokkos::create_mirror_view_and_copy(HostSpace(), _own.rigid);
  auto back = Kokkos::create_mirror_view_and_copy(HostSpace(), _own.back);
  auto active = Kokkos::create_mirror_view_and_copy(HostSpace(), _own.active);
  std::vector<GhostFaceDesc> out(size_t(_own.count));
  for (Index f = 0; f < _own.count; ++f)
  {
    GhostFaceDesc &g = out[size_t(f)];
    g.key = _own_info[size_t(f)].key;
    g.part = _own_info[size_t(f)].part;
    g.surface = surface(f);
    g.num_nodes = nn(f);
    g.rigid = rigid(f);
    g.active = active(f);
    g.mass = mass(f);
    g.depth = depth(f);
    for (int a = 0; a < kMaxFaceNodes; ++a)
      g.nodes[a] = nodes(f, a);
    g.back = back(f);
  }
  return out;
}

void ContactSystem::setGhostFaces(const std::vector<GhostFaceDesc> &ghosts, Index node_count,
                                  const std::vector<Index> &shared_nodes)
{
  // merge this rank's faces and the ghosts by key: the ascending-key order of 3.5, so face 1
  // of a CP is the same face on every rank that computes it
  const std::vector<GhostFaceDesc> own = ownFaces();
  auto own_element = Kokkos::create_mirror_view_and_copy(HostSpace(), _own.element);
  const size_t n = own.size() + ghosts.size();
  ContactFaceData F;
  allocateFaces(F, n);
  F.params = _own.params;
  ContactFaceHost hf(F);
  _info.assign(n, ContactFaceInfo());
  _ghost_of_face.assign(n, -1);
  std::vector<Index> used = shared_nodes;
  size_t i = 0, j = 0;
  for (size_t f = 0; f < n; ++f)
  {
    const bool take_own = j == ghosts.size() || (i < own.size() && own[i].key < ghosts[j].key);
    const GhostFaceDesc &g = take_own ? own[i] : ghosts[j];
    hf.num_nodes(f) = g.num_nodes;
    hf.surface(f) = g.surface;
    hf.part(f) = g.part;
    hf.active(f) = g.active;
    hf.mass(f) = g.mass;
    hf.depth(f) = g.depth;
    hf.rigid(f) = g.rigid;
    hf.back(f) = g.back;
    hf.key(f) = g.key;
    hf.ghost(f) = take_own ? 0 : 1;
    for (int a = 0; a < kMaxFaceNodes; ++a)
    {
      hf.nodes(f, a) = a < g.num_nodes ? g.nodes[a] : -1;
      if (a < g.num_nodes)
        used.push_back(g.nodes[a]);
    }
    if (take_own)
    {
      hf.element(f) = own_element(Index(i));
      _info[f] = _own_info[i++];
    }
    else
    {
      hf.element(f) = Index(-2 - g.key / 8);
      _info[f] = {g.key, Index(g.key / 8), int(g.key % 8), g.part};
      _ghost_of_face[f] = Index(j++);
    }
  }
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  F.nodes_used = toDevice(used, "contact_nodes");
  hf.copyTo(F);
  _faces = F;
  resizeNodeArrays(size_t(node_count));
}

std::vector<char> ContactSystem::ghostFacesInPlanes() const
{
  size_t ghosts = 0;
  for (Index g : _ghost_of_face)
    ghosts += g >= 0 ? 1 : 0;
  std::vector<char> used(ghosts, 0);
  auto f1 = Kokkos::create_mirror_view_and_copy(HostSpace(), _cp.face1);
  auto f2 = Kokkos::create_mirror_view_and_copy(HostSpace(), _cp.face2);
  for (Index p = 0; p < _cp.count; ++p)
    for (Index f : {f1(p), f2(p)})
      if (_ghost_of_face[size_t(f)] >= 0)
        used[size_t(_ghost_of_face[size_t(f)])] = 1;
  return used;
}

std::vector<Real> ContactSystem::ownFaceDensity(const ElementFields &elements) const
{
  RealView rho("contact_own_density", size_t(_own.count));
  auto element = _own.element;
  auto mass = elements.mass, volume = elements.volume;
  Kokkos::parallel_for(
      "scpdyn::contact::ownDensity", Kokkos::RangePolicy<ExecSpace>(0, _own.count),
      KOKKOS_LAMBDA(const Index f) { rho(f) = mass(element(f)) / volume(element(f)); });
  auto h = Kokkos::create_mirror_view_and_copy(HostSpace(), rho);
  return std::vector<Real>(h.data(), h.data() + _own.count);
}

void ContactSystem::setGhostDensity(const std::vector<Real> &density)
{
  auto h = Kokkos::create_mirror_view_and_copy(HostSpace(), _faces.density);
  eachGhostFace([&](Index f, size_t g) { h(f) = density[g]; });
  Kokkos::deep_copy(_faces.density, h);
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
    if (_ghost_of_face[size_t(f1(p))] >= 0)
      continue; // the rank of face 1 reports it
    for (int d = 0; d < 3; ++d)
      h.poc.push_back(poc(p, d));
    const CpState &s = state(p);
    const bool active = status(p) != CpInactive;
    h.area.push_back(active ? area(p) : 0.0);
    h.normal_force.push_back(active ? s.Fn : 0.0);
    h.shear_force.push_back(
        active ? std::sqrt(s.Fs[0] * s.Fs[0] + s.Fs[1] * s.Fs[1] + s.Fs[2] * s.Fs[2]) : 0.0);
    h.closure.push_back(s.u);
    h.slip.push_back(s.usp * params(p).a);
    h.state.push_back(status(p));
    h.failed.push_back(params(p).option == ContactOption::Sleepy && s.failed ? 1.0 : 0.0);
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
  auto surface = Kokkos::create_mirror_view_and_copy(HostSpace(), _faces.surface);
  const size_t s1 = size_t(surface(f1(cp))), s2 = size_t(surface(f2(cp)));
  if (s1 < _surface_labels.size() && s2 < _surface_labels.size())
    os << " of contact surface"
       << (s1 == s2 ? " " + _surface_labels[s1]
                    : "s " + _surface_labels[s1] + " and " + _surface_labels[s2]);
  return os.str();
}

} // namespace scpdyn
