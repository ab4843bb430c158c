#pragma once
/// \file ElementKernel.hpp
/// \brief The functor of step 6 (element/ElementLaunch.hpp launches it; a test runs its pack and
/// one-element paths side by side): the element step of one element (any type) or of a pack
/// of kElementLanes hexes, loading and storing the element state and scattering the forces.
#include "element/ElementSolver.hpp"
#include "element/ElementForces.hpp"
#include "material/Erosion.hpp"

namespace scpdyn
{
namespace element_kernel
{

/// How element forces reach the nodes: atomic adds; plain adds (one thread: the same sums in
/// the same order, without the ~7 ns lock of each of the 24 atomic adds of a hex); or, one
/// thread per chunk (NodeCorners), plain adds but corner stores for the shared nodes.
enum class Scatter
{
  Atomic,
  Plain,
  Corners
};

/// \brief Step 6 for the elements of one group: element e alone (any type), or a pack of
/// kElementLanes hexes (lane l = element first + l), with the same results bit for bit.
/// Erosion (ElementControls::erosion): skip eroded elements, test the others for erosion, and
/// run packs lane by lane. A compile-time switch, so that the kernel of a deck without erosion
/// has none of these tests in its loops: a runtime flag there, though never set, made the box
/// deck's cycle ~10 % slower (perf/results/log.md).
template <ElementType T, bool Axi, bool Erosion>
struct ElementKernel
{
  static constexpr int N = ElementTraits<T>::nodes;
  ConnView conn;
  DeviceView<std::uint8_t *> row_pack; ///< ElementFields::row_pack
  VectorView x_n, v_n;
  AtomicVectorView f_atomic;
  VectorView f_plain;
  VectorView corner_force;
  DeviceView<std::uint8_t *> shared_corners;
  IndexView corner_base;
  IndexView mat_id;
  RealView e_mass, e_volume, e_energy, e_eps, e_q, e_c, e_hg;
  SymTensorView e_stress;
  HistoryView e_hist;
  HourglassView e_hgq;
  DeviceView<std::uint8_t *> e_eroded;
  DeviceView<MaterialParams *> materials;
  ElementControls ctl;
  Scatter scatter;
  Real half_dt;

  /// Loads element e's state; its history slots only if `history` (modelUsesHistory()).
  KOKKOS_INLINE_FUNCTION void loadState(const Index e, const bool history, ElementState &s) const
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
      s.history[k] = history ? e_hist(e, k) : Real(0);
    for (int k = 0; k < kHourglassSize; ++k)
      s.hourglass[k] = k < kHourglassSlots ? e_hgq(e, k) : Real(0);
  }

  /// Hourglass resistances an element of type T has (3 a mode): 12 for the hex, 3 for the
  /// quad, none for the tet and the line: the one-element step moves only these (all 12 would
  /// cost a tet 192 B a cycle of resistances it does not have).
  static constexpr int kHourglassSlots = 3 * HourglassModes<T>::count;

  /// Stores the state (the history slots from `history` unless it is null: the model uses
  /// none), books the hourglass work and scatters the forces of element e (or flags it in
  /// local_min if its step failed).
  KOKKOS_INLINE_FUNCTION void finish(const Index e, const Real *history, const ElementState &s,
                                     const ElementResult &r, Real &local_min) const
  {
    if constexpr (Erosion)
      if (erodesInStep(e, history, s, r.stable_dt))
      {
        e_eroded(e) = kErodingNow; // its last state, and no force, no step of this cycle
        clearCornerSlots(e);
        return;
      }
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
    if (history)
      for (int k = 0; k < kHistorySize; ++k)
        e_hist(e, k) = history[k];
    for (int k = 0; k < kHourglassSlots; ++k)
      e_hgq(e, k) = s.hourglass[k];
    scatterForces(e, r.force);
    local_min = r.stable_dt < local_min ? r.stable_dt : local_min;
  }

  /// Whether element e erodes instead of finishing its step: its material erodes and its
  /// updated state s passed a limit, or it inverted (docs/theory.md 11.6). A non-finite step
  /// is left to stop the run.
  KOKKOS_INLINE_FUNCTION bool erodesInStep(const Index e, const Real *history,
                                           const ElementState &s, const Real stable_dt) const
  {
    const MaterialParams &m = materials(mat_id(e));
    if (!m.erosion.active || stable_dt != stable_dt)
      return false;
    const Real damage = history ? erosionDamage(m, history) : Real(0);
    return erosionLimitPassed(m.erosion, s.plastic_strain, damage,
                              volumetricStrain(m, s.mass, s.volume), stable_dt);
  }

  /// An element that scatters nothing (eroded): its corner slots, which the gather sums every
  /// cycle, must not keep its last forces.
  KOKKOS_INLINE_FUNCTION void clearCornerSlots(const Index e) const
  {
    if (scatter != Scatter::Corners)
      return;
    const Real zero[N][3] = {};
    scatterForces(e, zero);
  }

  /// Element e's nodal forces to f_int (atomic or plain adds) or to its corner slots.
  KOKKOS_INLINE_FUNCTION void scatterForces(const Index e, const Real force[][3]) const
  {
    if (scatter == Scatter::Atomic)
    {
      for (int a = 0; a < N; ++a)
      {
        const Index n = conn(e, a);
        for (int i = 0; i < ElementTraits<T>::dim; ++i)
          f_atomic(n, i) += force[a][i];
      }
      return;
    }
    // plain adds, but the corners of shared nodes (chunked assembly) to their slots
    const unsigned shared = scatter == Scatter::Corners ? unsigned(shared_corners(e)) : 0u;
    Index slot = shared != 0 ? corner_base(e) : 0;
    for (int a = 0; a < N; ++a)
      if (shared >> a & 1u)
      {
        for (int i = 0; i < 3; ++i)
          corner_force(slot, i) = force[a][i];
        ++slot;
      }
      else
      {
        const Index n = conn(e, a);
        for (int i = 0; i < ElementTraits<T>::dim; ++i)
          f_plain(n, i) += force[a][i];
      }
  }

  KOKKOS_INLINE_FUNCTION void one(const Index e, Real &local_min) const
  {
    if constexpr (Erosion)
      if (e_eroded(e) != 0)
      {
        clearCornerSlots(e);
        return;
      }
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
    const MaterialParams &mat = materials(mat_id(e));
    const bool history = modelUsesHistory(mat.model);
    ElementState s;
    loadState(e, history, s);
    ElementResult r;
    elementStep<T, Axi>(x, v, mat, ctl, s, r);
    finish(e, history ? s.history : nullptr, s, r, local_min);
  }

  /// Elements begin .. end - 1 in order, on the calling thread: packs of kElementLanes hexes,
  /// else one element at a time.
  KOKKOS_INLINE_FUNCTION void range(const Index begin, const Index end, Real &local_min) const
  {
#ifdef SCPDYN_ELEMENT_LANES
    if constexpr (T == ElementType::Hex8 && !Axi)
    {
      for (Index first = begin; first < end; first += kElementLanes)
        pack(first, int(end - first < kElementLanes ? end - first : kElementLanes), local_min);
      return;
    }
#endif
    for (Index e = begin; e < end; ++e)
      one(e, local_min);
  }

#ifdef SCPDYN_ELEMENT_LANES
  // A pack of W consecutive elements reads and writes its state with vector loads and stores:
  // every state View is 1-D or component-major (ElementComponentView), so component j of
  // elements first .. first + W - 1 is one contiguous run from &view(first, j).
  static_assert(std::is_same<SymTensorView::array_layout, Kokkos::LayoutLeft>::value &&
                    std::is_same<HourglassView::array_layout, Kokkos::LayoutLeft>::value,
                "the pack's vector loads need component-major element state");

  /// The pack's state (not the history slots): lanes el[0..W-1].
  KOKKOS_INLINE_FUNCTION void loadPackState(const Index first, const int count, const Index el[],
                                            ElementStateOf<LanePack> &s) const
  {
    constexpr int W = kElementLanes;
    if (count == W)
    {
      s.energy = loadPack(e_energy.data() + first);
      s.plastic_strain = loadPack(e_eps.data() + first);
      s.volume = loadPack(e_volume.data() + first);
      s.mass = loadPack(e_mass.data() + first);
      s.sound_speed = loadPack(e_c.data() + first);
      s.q = loadPack(e_q.data() + first);
      for (int j = 0; j < 6; ++j)
        s.stress[j] = loadPack(&e_stress(first, j));
      for (int j = 0; j < kHourglassSize; ++j)
        s.hourglass[j] = loadPack(&e_hgq(first, j));
      return;
    }
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
  }

  /// finish()'s stores for a full pack (elements first .. first + W - 1) whose steps all
  /// succeeded, as vector stores; false (nothing stored) if one did not.
  KOKKOS_INLINE_FUNCTION bool storePackState(const Index first, const ElementStateOf<LanePack> &s,
                                             const ElementResultOf<LanePack> &r,
                                             const bool uses_history[],
                                             const Real hist[][kHistorySize]) const
  {
    constexpr int W = kElementLanes;
    for (int l = 0; l < W; ++l)
      if (!(r.stable_dt[l] > 0))
        return false;
    storePack(e_energy.data() + first, s.energy);
    storePack(e_eps.data() + first, s.plastic_strain);
    storePack(e_volume.data() + first, s.volume);
    storePack(e_c.data() + first, s.sound_speed);
    storePack(e_q.data() + first, r.q);
    Real *hge = e_hg.data() + first;
    storePack(hge, loadPack(hge) + r.hourglass_power * Real(2) * half_dt);
    for (int j = 0; j < 6; ++j)
      storePack(&e_stress(first, j), s.stress[j]);
    for (int j = 0; j < kHourglassSize; ++j)
      storePack(&e_hgq(first, j), s.hourglass[j]);
    for (int l = 0; l < W; ++l)
      if (uses_history[l])
        for (int j = 0; j < kHistorySize; ++j)
          e_hist(first + l, j) = hist[l][j];
    return true;
  }

  /// Elements first .. first + count - 1 (count <= kElementLanes) as one pack; the lanes past
  /// count repeat the last element and are dropped. The material update runs on the pack when
  /// all lanes share an elastic + linear EOS material (elasticLinearUpdate, updateMaterial's
  /// own stages), else lane by lane.
  KOKKOS_INLINE_FUNCTION void pack(const Index first, const int count, Real &local_min) const
  {
    constexpr int W = kElementLanes;
    using P = LanePack;
    if constexpr (Erosion) // eroded lanes and eroding ones: the scalar path skips and flags them
    {
      for (Index e = first; e < first + count; ++e)
        one(e, local_min);
      return;
    }
    Index el[W];
    for (int l = 0; l < W; ++l)
      el[l] = first + (l < count ? l : count - 1);
    static_assert(std::is_same<VectorView::array_layout, Kokkos::LayoutRight>::value,
                  "loadTriples and addTriples read node n's vector at data() + 3 n");
    // a row pack (markRowPacks): the rows' first nodes, and each row read once
    const bool row = count == W && row_pack(first) != 0;
    Index row_base[4], node[N][W];
    P x[N][3], v[N][3];
    if (row)
      for (int r = 0; r < 4; ++r)
      {
        row_base[r] = conn(first, kHexRowMinus[r]);
        loadRowTriples(v_n.data(), row_base[r], v[kHexRowMinus[r]], v[kHexRowPlus[r]]);
        loadRowTriples(x_n.data(), row_base[r], x[kHexRowMinus[r]], x[kHexRowPlus[r]]);
      }
    else
      for (int a = 0; a < N; ++a)
      {
        for (int l = 0; l < W; ++l)
          node[a][l] = conn(el[l], a);
        loadTriples(v_n.data(), node[a], v[a]);
        loadTriples(x_n.data(), node[a], x[a]);
      }
    for (int a = 0; a < N; ++a)
      for (int i = 0; i < 3; ++i)
        x[a][i] += half_dt * v[a][i];
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
    loadPackState(first, count, el, s);
    elementRates<T, Axi>(v, ctl, s, k);
    P c;
    Real hist[W][kHistorySize];
    bool uses_history[W] = {}; // the elastic and J2 models leave their slots alone
    const Index m0 = mat_id(el[0]);
    bool one_material = true;
    for (int l = 1; l < W; ++l)
      one_material = one_material && mat_id(el[l]) == m0;
    // The elastic update runs on the pack (updateMaterial's own stages, MetalUpdate.hpp), once
    // for each elastic + linear EOS material among the lanes, each lane keeping its own
    // material's result: an element gets the same bits whichever elements share its pack,
    // which depends on the thread chunks and on where the partition cuts. The other models run
    // one lane at a time (they read the history slots directly).
    bool done[W] = {};
    if (one_material && isElasticLinear(materials(m0)))
    {
      const MaterialParams &mp = materials(m0);
      const P c2 =
          elasticLinearUpdate(mp, k.D, ctl.dt, k.rho_old, k.rho_new, k.q_mean, s.stress, s.energy);
      c = LaneOps<P>::sqrt(LaneOps<P>::max(c2, LaneOps<P>::broadcast(soundSpeedSquaredFloor(mp))));
      for (int l = 0; l < W; ++l)
        done[l] = true;
    }
    else
      for (int l = 0; l < W; ++l)
      {
        const Index m = mat_id(el[l]);
        if (done[l] || !isElasticLinear(materials(m)))
          continue;
        const MaterialParams &mp = materials(m);
        P stress[6], energy = s.energy;
        for (int j = 0; j < 6; ++j)
          stress[j] = s.stress[j];
        const P c2 =
            elasticLinearUpdate(mp, k.D, ctl.dt, k.rho_old, k.rho_new, k.q_mean, stress, energy);
        const P cm = LaneOps<P>::sqrt(
            LaneOps<P>::max(c2, LaneOps<P>::broadcast(soundSpeedSquaredFloor(mp))));
        for (int j = l; j < W; ++j)
          if (!done[j] && mat_id(el[j]) == m)
          {
            for (int i = 0; i < 6; ++i)
              s.stress[i][j] = stress[i][j];
            s.energy[j] = energy[j];
            c[j] = cm[j];
            done[j] = true;
          }
      }
    for (int l = 0; l < W; ++l)
      if (!done[l])
      {
        const Index e = el[l];
        const MaterialParams &mat = materials(mat_id(e));
        uses_history[l] = modelUsesHistory(mat.model);
        const MaterialStep st = materialStep<T>(k, ctl, l);
        Real stress[6];
        for (int j = 0; j < 6; ++j)
          stress[j] = s.stress[j][l];
        for (int j = 0; j < kHistorySize; ++j)
          hist[l][j] = uses_history[l] ? e_hist(e, j) : Real(0);
        Real energy = s.energy[l], eps = s.plastic_strain[l];
        c[l] = updateMaterial(mat, st, stress, energy, eps, hist[l]);
        for (int j = 0; j < 6; ++j)
          s.stress[j][l] = stress[j];
        s.energy[l] = energy;
        s.plastic_strain[l] = eps;
      }
    ElementResultOf<P> r;
    elementForces<T, Axi>(x, v, ctl, k, c, s, r);
    if (count == W && storePackState(first, s, r, uses_history, hist))
    {
      unsigned shared = 0; // does the pack touch a shared node (chunked assembly)?
      if (scatter == Scatter::Corners)
        for (int l = 0; l < W; ++l)
          shared |= shared_corners(first + l);
      if (scatter != Scatter::Atomic && shared == 0 && row)
        for (int r4 = 0; r4 < 4; ++r4)
          addRowTriples(f_plain.data(), row_base[r4], r.force[kHexRowMinus[r4]],
                        r.force[kHexRowPlus[r4]]);
      else if (scatter != Scatter::Atomic && shared == 0)
        addTriples<N>(f_plain.data(), node, r.force);
      else
        for (int l = 0; l < W; ++l)
        {
          Real force[N][3];
          for (int a = 0; a < N; ++a)
            for (int i = 0; i < 3; ++i)
              force[a][i] = r.force[a][i][l];
          scatterForces(el[l], force);
        }
      for (int l = 0; l < W; ++l)
        local_min = r.stable_dt[l] < local_min ? r.stable_dt[l] : local_min;
      return;
    }
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
      for (int j = 0; j < kHourglassSize; ++j)
        sl.hourglass[j] = s.hourglass[j][l];
      for (int a = 0; a < N; ++a)
        for (int i = 0; i < 3; ++i)
          rl.force[a][i] = r.force[a][i][l];
      rl.q = r.q[l];
      rl.hourglass_power = r.hourglass_power[l];
      rl.stable_dt = r.stable_dt[l];
      finish(el[l], uses_history[l] ? hist[l] : nullptr, sl, rl, local_min);
    }
  }
#endif
};

/// \brief The kernel of step 6 for elements of type T on these fields (Erosion: as
/// ctl.erosion).
template <ElementType T, bool Axi, bool Erosion>
ElementKernel<T, Axi, Erosion> makeElementKernel(const ElementControls &ctl, Scatter scatter,
                                                 const NodeFields &nodes, const ElementFields &el,
                                                 const DeviceView<MaterialParams *> &materials,
                                                 const NodeCorners &corners)
{
  ElementKernel<T, Axi, Erosion> k;
  k.conn = el.conn;
  k.row_pack = el.row_pack;
  k.x_n = nodes.x;
  k.v_n = nodes.v;
  k.f_atomic = nodes.f_int;
  k.f_plain = nodes.f_int;
  k.corner_force = corners.corner_force;
  k.shared_corners = corners.shared_corners;
  k.corner_base = corners.corner_base;
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
  k.e_eroded = el.eroded;
  k.materials = materials;
  k.ctl = ctl;
  k.scatter = scatter;
  k.half_dt = 0.5 * ctl.dt;
  return k;
}

} // namespace element_kernel
} // namespace scpdyn
