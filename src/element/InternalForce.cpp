#include "element/InternalForce.hpp"

#include "element/ElementSolver.hpp"

namespace scpdyn
{
namespace
{

/// How element forces reach the nodes: atomic adds; plain adds (one thread: the same sums in
/// the same order, without the ~7 ns lock of each of the 24 atomic adds of a hex); or
/// per-corner stores for gatherCornerForces().
enum class Scatter
{
  Atomic,
  Plain,
  Corners
};

// Kernel labels stay within std::string's 15-character small-string buffer: Kokkos turns
// each label into a std::string per launch, and a longer one is a heap allocation per cycle.

/// \brief Step 6 for the elements of one group: element e alone (any type), or a pack of
/// kElementLanes hexes (lane l = element first + l), with the same results bit for bit.
template <ElementType T, bool Axi>
struct ElementKernel
{
  static constexpr int N = ElementTraits<T>::nodes;
  ConnView conn;
  VectorView x_n, v_n;
  AtomicVectorView f_atomic;
  VectorView f_plain;
  DeviceView<Real * [kMaxElementNodes][3]> corner_force;
  IndexView mat_id;
  RealView e_mass, e_volume, e_energy, e_eps, e_q, e_c, e_hg;
  SymTensorView e_stress;
  DeviceView<Real * [kHistorySize]> e_hist;
  DeviceView<Real * [kHourglassSize]> e_hgq;
  DeviceView<MaterialParams *> materials;
  ElementControls ctl;
  Scatter scatter;
  Real half_dt;

  KOKKOS_INLINE_FUNCTION void loadState(const Index e, ElementState &s) const
  {
    for (int k = 0; k < 6; ++k)
      s.stress[k] = e_stress(e, k);
    s.energy = e_energy(e);
    s.plastic_strain = e_eps(e);
    s.volume = e_volume(e);
    s.mass = e_mass(e);
    s.sound_speed = e_c(e);
    s.q = e_q(e);
    for (int k = 0; k < kHistorySize; ++k)
      s.history[k] = e_hist(e, k);
    for (int k = 0; k < kHourglassSize; ++k)
      s.hourglass[k] = e_hgq(e, k);
  }

  /// Stores the state, books the hourglass work and scatters the forces of element e (or
  /// flags it in local_min if its step failed).
  KOKKOS_INLINE_FUNCTION void finish(const Index e, const ElementState &s, const ElementResult &r,
                                     Real &local_min) const
  {
    if (!(r.stable_dt > 0))
    {
      const Real flag = -Real(e + 1);
      local_min = flag < local_min ? flag : local_min;
      return;
    }
    for (int k = 0; k < 6; ++k)
      e_stress(e, k) = s.stress[k];
    e_energy(e) = s.energy;
    e_eps(e) = s.plastic_strain;
    e_volume(e) = s.volume;
    e_c(e) = s.sound_speed;
    e_q(e) = r.q;
    e_hg(e) += r.hourglass_power * 2 * half_dt;
    for (int k = 0; k < kHistorySize; ++k)
      e_hist(e, k) = s.history[k];
    for (int k = 0; k < kHourglassSize; ++k)
      e_hgq(e, k) = s.hourglass[k];
    if (scatter == Scatter::Corners)
    {
      for (int a = 0; a < N; ++a)
        for (int i = 0; i < 3; ++i)
          corner_force(e, a, i) = r.force[a][i];
    }
    else if (scatter == Scatter::Plain)
    {
      for (int a = 0; a < N; ++a)
      {
        const Index n = conn(e, a);
        for (int i = 0; i < ElementTraits<T>::dim; ++i)
          f_plain(n, i) += r.force[a][i];
      }
    }
    else
    {
      for (int a = 0; a < N; ++a)
      {
        const Index n = conn(e, a);
        for (int i = 0; i < ElementTraits<T>::dim; ++i)
          f_atomic(n, i) += r.force[a][i];
      }
    }
    local_min = r.stable_dt < local_min ? r.stable_dt : local_min;
  }

  KOKKOS_INLINE_FUNCTION void one(const Index e, Real &local_min) const
  {
    Real x[N][3], v[N][3];
    for (int a = 0; a < N; ++a)
    {
      const Index n = conn(e, a);
      for (int i = 0; i < 3; ++i)
      {
        v[a][i] = v_n(n, i);
        x[a][i] = x_n(n, i) + half_dt * v[a][i];
      }
    }
    ElementState s;
    loadState(e, s);
    ElementResult r;
    elementStep<T, Axi>(x, v, materials(mat_id(e)), ctl, s, r);
    finish(e, s, r, local_min);
  }

#ifdef SCPDYN_ELEMENT_LANES
  /// Elements first .. first + count - 1 (count <= kElementLanes) as one pack; the lanes past
  /// count repeat the last element and are dropped. Material updates run lane by lane.
  KOKKOS_INLINE_FUNCTION void pack(const Index first, const int count, Real &local_min) const
  {
    constexpr int W = kElementLanes;
    using P = LanePack;
    Index el[W];
    for (int l = 0; l < W; ++l)
      el[l] = first + (l < count ? l : count - 1);
    P x[N][3], v[N][3];
    for (int a = 0; a < N; ++a)
      for (int l = 0; l < W; ++l)
      {
        const Index n = conn(el[l], a);
        for (int i = 0; i < 3; ++i)
        {
          const Real vi = v_n(n, i);
          v[a][i][l] = vi;
          x[a][i][l] = x_n(n, i) + half_dt * vi;
        }
      }
    ElementKinematicsOf<T, P> k;
    elementGeometry<T, Axi>(x, k);
    bool valid = true;
    for (int l = 0; l < W; ++l)
      valid = valid && k.V[l] > 0 && k.measure[l] > 0;
    if (!valid) // an inverted element: the scalar path reports it (and stops the run)
    {
      for (int l = 0; l < count; ++l)
        one(el[l], local_min);
      return;
    }
    ElementStateOf<P> s;
    for (int l = 0; l < W; ++l)
    {
      const Index e = el[l];
      for (int j = 0; j < 6; ++j)
        s.stress[j][l] = e_stress(e, j);
      s.energy[l] = e_energy(e);
      s.plastic_strain[l] = e_eps(e);
      s.volume[l] = e_volume(e);
      s.mass[l] = e_mass(e);
      s.sound_speed[l] = e_c(e);
      s.q[l] = e_q(e);
      for (int j = 0; j < kHourglassSize; ++j)
        s.hourglass[j][l] = e_hgq(e, j);
    }
    elementRates<T, Axi>(v, ctl, s, k);
    // the material update, one lane at a time (it reads the history slots directly)
    P c;
    Real hist[W][kHistorySize];
    for (int l = 0; l < W; ++l)
    {
      const Index e = el[l];
      MaterialStep st;
      for (int j = 0; j < 6; ++j)
        st.D[j] = k.D[j][l];
      st.dt = ctl.dt;
      st.rho_old = k.rho_old[l];
      st.rho_new = k.rho_new[l];
      st.q = k.q_mean[l];
      st.time = ctl.half_time;
      st.length = k.length[l];
      Real stress[6];
      for (int j = 0; j < 6; ++j)
        stress[j] = s.stress[j][l];
      for (int j = 0; j < kHistorySize; ++j)
        hist[l][j] = e_hist(e, j);
      Real energy = s.energy[l], eps = s.plastic_strain[l];
      c[l] = updateMaterial(materials(mat_id(e)), st, stress, energy, eps, hist[l]);
      for (int j = 0; j < 6; ++j)
        s.stress[j][l] = stress[j];
      s.energy[l] = energy;
      s.plastic_strain[l] = eps;
    }
    ElementResultOf<P> r;
    elementForces<T, Axi>(x, v, ctl, k, c, s, r);
    for (int l = 0; l < count; ++l)
    {
      ElementState sl;
      ElementResult rl;
      for (int j = 0; j < 6; ++j)
        sl.stress[j] = s.stress[j][l];
      sl.energy = s.energy[l];
      sl.plastic_strain = s.plastic_strain[l];
      sl.volume = s.volume[l];
      sl.sound_speed = s.sound_speed[l];
      for (int j = 0; j < kHistorySize; ++j)
        sl.history[j] = hist[l][j];
      for (int j = 0; j < kHourglassSize; ++j)
        sl.hourglass[j] = s.hourglass[j][l];
      for (int a = 0; a < N; ++a)
        for (int i = 0; i < 3; ++i)
          rl.force[a][i] = r.force[a][i][l];
      rl.q = r.q[l];
      rl.hourglass_power = r.hourglass_power[l];
      rl.stable_dt = r.stable_dt[l];
      finish(el[l], sl, rl, local_min);
    }
  }
#endif
};

template <ElementType T, bool Axi>
Real launchGroup(const ElementGroup &g, const ElementControls &ctl, Scatter scatter,
                 const NodeFields &nodes, const ElementFields &el,
                 const DeviceView<MaterialParams *> &materials, const NodeCorners &corners)
{
  ElementKernel<T, Axi> k;
  k.conn = el.conn;
  k.x_n = nodes.x;
  k.v_n = nodes.v;
  k.f_atomic = nodes.f_int;
  k.f_plain = nodes.f_int;
  k.corner_force = corners.corner_force;
  k.mat_id = el.material;
  k.e_mass = el.mass;
  k.e_volume = el.volume;
  k.e_energy = el.energy;
  k.e_eps = el.plastic_strain;
  k.e_q = el.q;
  k.e_c = el.sound_speed;
  k.e_hg = el.hourglass_energy;
  k.e_stress = el.stress;
  k.e_hist = el.history;
  k.e_hgq = el.hourglass;
  k.materials = materials;
  k.ctl = ctl;
  k.scatter = scatter;
  k.half_dt = 0.5 * ctl.dt;

  Real dt_min = 0;
#ifdef SCPDYN_ELEMENT_LANES
  if constexpr (T == ElementType::Hex8 && !Axi)
  {
    constexpr Index W = kElementLanes;
    const Index begin = g.begin, end = g.end;
    Kokkos::parallel_reduce(
        "hex8Forces", Kokkos::RangePolicy<ExecSpace>(0, (end - begin + W - 1) / W),
        KOKKOS_LAMBDA(const Index p, Real &local_min) {
          const Index first = begin + p * W;
          k.pack(first, int(end - first < W ? end - first : W), local_min);
        },
        Kokkos::Min<Real>(dt_min));
    return dt_min;
  }
#endif
  Kokkos::parallel_reduce(
      "elementForces", Kokkos::RangePolicy<ExecSpace>(g.begin, g.end),
      KOKKOS_LAMBDA(const Index e, Real &local_min) { k.one(e, local_min); },
      Kokkos::Min<Real>(dt_min));
  return dt_min;
}

template <bool Axi>
Real launchAny(const ElementGroup &g, const ElementControls &ctl, Scatter s,
               const NodeFields &nodes, const ElementFields &el,
               const DeviceView<MaterialParams *> &materials, const NodeCorners &corners)
{
  switch (g.type)
  {
  case ElementType::Line2:
    return launchGroup<ElementType::Line2, false>(g, ctl, s, nodes, el, materials, corners);
  case ElementType::Quad4:
    return launchGroup<ElementType::Quad4, Axi>(g, ctl, s, nodes, el, materials, corners);
  case ElementType::Hex8:
    return launchGroup<ElementType::Hex8, false>(g, ctl, s, nodes, el, materials, corners);
  case ElementType::Tet4:
    return launchGroup<ElementType::Tet4, false>(g, ctl, s, nodes, el, materials, corners);
  }
  return 0;
}

template <ElementType T, bool Axi>
Real initialGroup(const ElementGroup &g, const NodeFields &nodes, const ElementFields &el,
                  const DeviceView<MaterialParams *> &materials)
{
  constexpr int N = ElementTraits<T>::nodes;
  auto conn = el.conn;
  auto x_n = nodes.x;
  auto mat_id = el.material;
  auto e_volume = el.volume, e_c = el.sound_speed;
  Real dt_min = 0;
  Kokkos::parallel_reduce(
      "initialDt", Kokkos::RangePolicy<ExecSpace>(g.begin, g.end),
      KOKKOS_LAMBDA(const Index e, Real &local_min) {
        Real x[N][3], B[N][3];
        for (int a = 0; a < N; ++a)
          for (int i = 0; i < 3; ++i)
            x[a][i] = x_n(conn(e, a), i);
        const Real measure = elementGradients<T>(x, B);
        Real V = measure;
        if constexpr (Axi)
          V = quad4RadialVolume(x);
        const MaterialParams &m = materials(mat_id(e));
        const Real c = kmath::sqrt((m.bulk + 4.0 / 3.0 * m.shear) / m.density);
        e_c(e) = c;
        e_volume(e) = V;
        const Real h = characteristicLength<T>(x, measure);
        const Real dt = (V > 0 && measure > 0) ? h / c : -Real(e + 1);
        local_min = dt < local_min ? dt : local_min;
      },
      Kokkos::Min<Real>(dt_min));
  return dt_min;
}

} // namespace

Real computeElementForces(const std::vector<ElementGroup> &groups, const ElementControls &ctl,
                          const NodeFields &nodes, const ElementFields &elems,
                          const DeviceView<MaterialParams *> &materials, const NodeCorners &corners)
{
  const Scatter s = ctl.gather                       ? Scatter::Corners
                    : ExecSpace().concurrency() == 1 ? Scatter::Plain
                                                     : Scatter::Atomic;
  Real dt_min = Kokkos::reduction_identity<Real>::min();
  for (const auto &g : groups)
  {
    const Real d = ctl.geometry == Geometry2D::Axisymmetric
                       ? launchAny<true>(g, ctl, s, nodes, elems, materials, corners)
                       : launchAny<false>(g, ctl, s, nodes, elems, materials, corners);
    dt_min = d < dt_min ? d : dt_min;
  }
  return dt_min;
}

void gatherCornerForces(const NodeFields &nodes, const NodeCorners &corners)
{
  auto offsets = corners.offsets;
  auto list = corners.corners;
  auto cf = corners.corner_force;
  auto f = nodes.f_int;
  Kokkos::parallel_for(
      "gatherCorners", Kokkos::RangePolicy<ExecSpace>(0, nodes.count),
      KOKKOS_LAMBDA(const Index n) {
        // corner e * 8 + a is the 3 reals at 3 * corner of the (LayoutRight) corner array
        const Real *cf0 = cf.data();
        Real s[3] = {0, 0, 0};
        for (Index k = offsets(n); k < offsets(n + 1); ++k)
        {
          const Real *c = cf0 + 3 * size_t(list(k));
          for (int i = 0; i < 3; ++i)
            s[i] += c[i];
        }
        for (int i = 0; i < 3; ++i)
          f(n, i) = s[i];
      });
}

Real initialElementTimeStep(const std::vector<ElementGroup> &groups, Geometry2D geometry,
                            const NodeFields &nodes, const ElementFields &elems,
                            const DeviceView<MaterialParams *> &materials)
{
  Real dt_min = Kokkos::reduction_identity<Real>::min();
  const bool axi = geometry == Geometry2D::Axisymmetric;
  for (const auto &g : groups)
  {
    Real d = 0;
    switch (g.type)
    {
    case ElementType::Line2:
      d = initialGroup<ElementType::Line2, false>(g, nodes, elems, materials);
      break;
    case ElementType::Quad4:
      d = axi ? initialGroup<ElementType::Quad4, true>(g, nodes, elems, materials)
              : initialGroup<ElementType::Quad4, false>(g, nodes, elems, materials);
      break;
    case ElementType::Hex8:
      d = initialGroup<ElementType::Hex8, false>(g, nodes, elems, materials);
      break;
    case ElementType::Tet4:
      d = initialGroup<ElementType::Tet4, false>(g, nodes, elems, materials);
      break;
    }
    dt_min = d < dt_min ? d : dt_min;
  }
  return dt_min;
}

} // namespace scpdyn
