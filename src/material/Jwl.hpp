#pragma once
/// \file Jwl.hpp
/// \brief High explosive: JWL detonation-products EOS with programmed burn (the scheme of
/// LS-DYNA *MAT_HIGH_EXPLOSIVE_BURN), no strength.
///
///   p_JWL = A (1 - w/(R1 V)) e^{-R1 V} + B (1 - w/(R2 V)) e^{-R2 V} + w rho e,   V = rho0/rho,
///   p     = F p_JWL,   F = burn fraction (0 -> 1, never decreasing).
///
/// w rho e = w E/V with E = rho0 e the energy per unit initial volume (E0 at the start).
/// The element is lit at t_l = t_0 + |x_c - x_ig| / D (x_c the centroid, distance to the
/// ignition point, or to the ignition line when an axis is given) and F = (t - t_l) D /
/// (w_b L) ramps to 1 while the front crosses w_b element lengths (w_b = 1.5 is LS-DYNA's
/// 2/3 A_max/v factor). Optionally F = max(F, (1 - V)/(1 - V_CJ)) (LS-DYNA's beta burn).
/// See docs/theory_materials.md.
#include "material/MaterialMath.hpp"
#include "material/MaterialParams.hpp"
#include "material/TensorOps.hpp"

namespace scpdyn
{

// model_params layout
constexpr int kJwlA = 0;         ///< A [Pa]
constexpr int kJwlB = 1;         ///< B [Pa]
constexpr int kJwlR1 = 2;        ///< R1 [-]
constexpr int kJwlR2 = 3;        ///< R2 [-]
constexpr int kJwlOmega = 4;     ///< omega (Gruneisen coefficient of the products) [-]
constexpr int kJwlE0 = 5;        ///< detonation energy per unit initial volume E0 [Pa = J/m^3]
constexpr int kHeD = 6;          ///< detonation velocity D of the programmed burn [m/s]
constexpr int kHePcj = 7;        ///< Chapman-Jouguet pressure (given or the model's) [Pa]
constexpr int kHeIgnX = 8;       ///< ignition point x [m]
constexpr int kHeIgnY = 9;       ///< ignition point y [m]
constexpr int kHeIgnZ = 10;      ///< ignition point z [m]
constexpr int kHeAxis = 11;      ///< -1: point ignition; 0|1|2: line through the point along x|y|z
constexpr int kHeT0 = 12;        ///< initiation time [s]
constexpr int kHeBurnWidth = 13; ///< burn ramp width in element lengths [-]
constexpr int kHeBetaBurn = 14;  ///< 1: also burn on compression (1 - V)/(1 - V_CJ)
constexpr int kHeVcj = 15;       ///< relative volume at the model's CJ state [-] (derived)

// history layout
constexpr int kHeHistLightTime = 0; ///< lighting time t_l [s]
constexpr int kHeHistBurn = 1;      ///< burn fraction F [-]

/// \brief Energy-independent part of the JWL pressure, Aj(V), and dAj/dV.
KOKKOS_INLINE_FUNCTION void jwlColdPart(const Real jwl[], Real V, Real &Aj, Real &dAj)
{
  const Real A = jwl[kJwlA], B = jwl[kJwlB], R1 = jwl[kJwlR1], R2 = jwl[kJwlR2];
  const Real w = jwl[kJwlOmega];
  const Real e1 = kmath::exp(-R1 * V), e2 = kmath::exp(-R2 * V);
  Aj = A * (1 - w / (R1 * V)) * e1 + B * (1 - w / (R2 * V)) * e2;
  dAj = A * e1 * (w / (R1 * V * V) - R1 + w / V) + B * e2 * (w / (R2 * V * V) - R2 + w / V);
}

/// \brief Full JWL pressure [Pa] at relative volume V and energy per initial volume E [Pa].
KOKKOS_INLINE_FUNCTION Real jwlPressure(const Real jwl[], Real V, Real E)
{
  Real Aj, dAj;
  jwlColdPart(jwl, V, Aj, dAj);
  return Aj + jwl[kJwlOmega] * E / V;
}

/// \brief Products Hugoniot centred on the unreacted state (V = 1, E = E0, p = 0):
/// E = E0 + p (1 - V)/2 substituted into the JWL form. Defined for V > w/(2 + w);
/// returns a negative value where the denominator is not positive.
KOKKOS_INLINE_FUNCTION Real jwlHugoniotPressure(const Real jwl[], Real V)
{
  const Real w = jwl[kJwlOmega];
  Real Aj, dAj;
  jwlColdPart(jwl, V, Aj, dAj);
  const Real den = 1 - w * (1 - V) / (2 * V);
  return den > 0 ? (Aj + w * jwl[kJwlE0] / V) / den : Real(-1);
}

/// \brief The model's Chapman-Jouguet state (all SI; E per initial volume).
struct JwlCjState
{
  bool ok = false;
  Real V = 0, D = 0, p = 0, u = 0, rho = 0, E = 0, c = 0;
};

/// \brief CJ state of the JWL constants for unreacted density rho0: the point of the products
/// Hugoniot where the Rayleigh line D^2 = p / (rho0 (1 - V)) is tangent, i.e. the minimum of
/// D over V. A coarse scan brackets the minimum (D^2 -> inf at both ends of the Hugoniot's
/// domain when p_H > 0 there), golden-section search refines it. ok = false when p_H is not
/// positive around the minimum or the minimum is not interior (no CJ state).
KOKKOS_INLINE_FUNCTION JwlCjState jwlChapmanJouguet(const Real jwl[], Real rho0)
{
  JwlCjState cj;
  const Real w = jwl[kJwlOmega];
  const Real vmin = w / (2 + w);
  auto d2 = [&](Real V) {
    const Real ph = jwlHugoniotPressure(jwl, V);
    return ph > 0 ? ph / (rho0 * (1 - V)) : Real(-1);
  };
  constexpr int n = 2000;
  int best = -1;
  Real best_d2 = 0;
  for (int i = 1; i < n; ++i)
  {
    const Real V = vmin + (1 - vmin) * i / n;
    const Real v = d2(V);
    if (v > 0 && (best < 0 || v < best_d2))
    {
      best = i;
      best_d2 = v;
    }
  }
  if (best <= 1 || best >= n - 1)
    return cj;
  Real a = vmin + (1 - vmin) * (best - 1) / n, b = vmin + (1 - vmin) * (best + 1) / n;
  if (!(d2(a) > 0 && d2(b) > 0))
    return cj;
  const Real g = 0.5 * (kmath::sqrt(5.0) - 1);
  Real x1 = b - g * (b - a), x2 = a + g * (b - a), f1 = d2(x1), f2 = d2(x2);
  for (int it = 0; it < 100 && b - a > 1e-14; ++it)
  {
    if (f1 < f2)
    {
      b = x2;
      x2 = x1;
      f2 = f1;
      x1 = b - g * (b - a);
      f1 = d2(x1);
    }
    else
    {
      a = x1;
      x1 = x2;
      f1 = f2;
      x2 = a + g * (b - a);
      f2 = d2(x2);
    }
  }
  cj.V = 0.5 * (a + b);
  cj.p = jwlHugoniotPressure(jwl, cj.V);
  cj.D = kmath::sqrt(cj.p / (rho0 * (1 - cj.V)));
  cj.u = cj.D * (1 - cj.V);
  cj.c = cj.D - cj.u;
  cj.rho = rho0 / cj.V;
  cj.E = jwl[kJwlE0] + 0.5 * cj.p * (1 - cj.V);
  cj.ok = cj.p > 0;
  return cj;
}

/// \brief Lighting time [s] of an element with this centroid [m]: initiation time plus the
/// straight-line distance to the ignition point (or line) over D. In 2D plane strain an
/// ignition point acts as a line along z, in 2D axisymmetric a point on the axis as a point.
KOKKOS_INLINE_FUNCTION Real lightingTime(const MaterialParams &p, const Real centroid[3])
{
  const Real *m = p.model_params;
  const int axis = static_cast<int>(m[kHeAxis]);
  Real d2 = 0;
  for (int k = 0; k < 3; ++k)
    if (k != axis)
    {
      const Real dx = centroid[k] - m[kHeIgnX + k];
      d2 += dx * dx;
    }
  return m[kHeT0] + kmath::sqrt(d2) / m[kHeD];
}

/// \brief Burn fraction at half-step time t for an element of length L [m] lit at t_l, at
/// relative volume V, never below the previous value F_old.
KOKKOS_INLINE_FUNCTION Real burnFraction(const MaterialParams &p, Real t, Real t_l, Real L, Real V,
                                         Real F_old)
{
  const Real *m = p.model_params;
  Real F = material_math::clamp((t - t_l) * m[kHeD] / (m[kHeBurnWidth] * L), 0, 1);
  if (m[kHeBetaBurn] > 0)
    F = material_math::max(F, material_math::clamp((1 - V) / (1 - m[kHeVcj]), 0, 1));
  return material_math::max(F, F_old);
}

/// \brief High-explosive step: burn fraction, then p_new and e_new solved together (p is
/// linear in e) with the trapezoidal energy update of updateMaterial(). The stress is
/// hydrostatic. Returns the products' sound speed at the new state (as if F = 1, so the
/// time step is already sized for the burn when an element lights).
KOKKOS_INLINE_FUNCTION Real highExplosiveUpdate(const MaterialParams &p, const MaterialStep &st,
                                                Real stress[6], Real &e, Real history[kHistorySize])
{
  const Real *m = p.model_params;
  const Real V = p.density / st.rho_new;
  const Real F =
      burnFraction(p, st.time, history[kHeHistLightTime], st.length, V, history[kHeHistBurn]);
  history[kHeHistBurn] = F;

  const Real rho_mid = 0.5 * (st.rho_old + st.rho_new);
  const Real trD = trace(st.D);
  const Real p_old = -trace(stress) / 3;
  const Real h = st.dt / rho_mid;
  const Real e_star = e - h * (0.5 * p_old + st.q) * trD;
  Real Aj, dAj;
  jwlColdPart(m, V, Aj, dAj);
  const Real w = m[kJwlOmega];
  const Real hh = 0.5 * h * trD;
  e = (e_star - hh * F * Aj) / (1 + hh * F * w * st.rho_new);
  const Real p_full = Aj + w * st.rho_new * e;
  const Real p_new = F * p_full;
  for (int k = 0; k < 3; ++k)
  {
    stress[k] = -p_new;
    stress[k + 3] = 0;
  }
  const Real c2 = -dAj * V / st.rho_new + w * e + w * p_full / st.rho_new;
  const Real c2_floor = soundSpeedSquaredFloor(p); // the products carry no shear: 1e-6 K / rho0
  return kmath::sqrt(c2 > c2_floor ? c2 : c2_floor);
}

} // namespace scpdyn
