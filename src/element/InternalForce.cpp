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

template <ElementType T, bool Axi>
Real launchGroup(const ElementGroup &g, const ElementControls &ctl, Scatter scatter,
                 const NodeFields &nodes, const ElementFields &el,
                 const DeviceView<MaterialParams *> &materials, const NodeCorners &corners)
{
  constexpr int N = ElementTraits<T>::nodes;
  auto conn = el.conn;
  auto x_n = nodes.x;
  auto v_n = nodes.v;
  AtomicVectorView f_atomic = nodes.f_int;
  VectorView f_plain = nodes.f_int;
  auto corner_force = corners.corner_force;
  auto mat_id = el.material;
  auto e_mass = el.mass, e_volume = el.volume, e_energy = el.energy, e_eps = el.plastic_strain;
  auto e_q = el.q, e_c = el.sound_speed, e_hg = el.hourglass_energy;
  auto e_stress = el.stress;
  auto e_hist = el.history;
  auto e_hgq = el.hourglass;
  const Real half_dt = 0.5 * ctl.dt;

  Real dt_min = 0;
  Kokkos::parallel_reduce(
      "elementForces", Kokkos::RangePolicy<ExecSpace>(g.begin, g.end),
      KOKKOS_LAMBDA(const Index e, Real &local_min) {
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

        ElementResult r;
        elementStep<T, Axi>(x, v, materials(mat_id(e)), ctl, s, r);
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
      },
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
