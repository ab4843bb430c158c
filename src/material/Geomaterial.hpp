#pragma once
/// \file Geomaterial.hpp
/// \brief Rock and concrete ("pseudo-cap" model): pressure-dependent shear strength, porous
/// compaction through a crush curve in the EOS, hardening by compaction, softening by
/// dilatancy, and a tensile strength that damage drives to zero.
///
/// One volumetric internal variable carries the porosity: theta_p, the plastic volumetric
/// (log) strain, positive in compaction. Crushing raises it (the hydrostatic "cap" of the
/// EOS: p <= p_c(theta_p)); shear dilatancy and tensile cracking lower it. Pressure is elastic
/// in the rest: p = K(theta_c) (theta - theta_p), theta = ln(rho/rho0), theta_c = max theta_p.
///   crush curve      p_c(x) = p_e + (p_l - p_e) x / theta_L  (0 <= x < theta_L; locked at
///                    theta_L); open cracks (x < 0) close at p = 0 before any crushing
///   bulk modulus     K(x) = K0 + (Ks - K0) min(x / theta_L, 1)   (unloading stiffens)
///   intact strength  Y_i(p) = Y0 + mu_i p / (1 + mu_i p / (Ym - Y0))   (p >= 0, Lundborg)
///                    Y_i(p) = Y0 max(0, 1 + p / T0)                     (p < 0)
///   damaged          Y_d(p) = min(mu_d max(p, 0), Ym)
///   strength         Y = (1 + h_c clamp(theta_p / theta_L, 0, 1)) ((1 - D) Y_i + D Y_d)
///   dilatancy        d theta_d = beta d eps_p,  beta = beta0 max(0, 1 - p / p_bd)
///   damage           D = min(1, theta_d / eps_d),  theta_d = accumulated dilatant strain
///   tension cut-off  p >= -T,  T = T0 (1 - D)  (opening beyond it is dilatant strain too)
///   crack band       with G_f: an opening strain eps_t = 2 G_f / (T0 L) takes T to zero
///                    in an element of length L, so a crack costs G_f whatever the mesh
/// See docs/theory_materials.md for the derivation and the parameter sets.
#include "material/MaterialMath.hpp"
#include "material/MaterialParams.hpp"
#include "material/TensorOps.hpp"

namespace scpdyn
{

// model_params layout (K0 = MaterialParams::bulk, G = MaterialParams::shear)
constexpr int kGeoKs = 0;        ///< fully compacted bulk modulus Ks [Pa]
constexpr int kGeoPcrush = 1;    ///< crush pressure p_e (onset of pore collapse) [Pa]
constexpr int kGeoPlock = 2;     ///< lock pressure p_l (porosity closed) [Pa]
constexpr int kGeoThetaLock = 3; ///< plastic volumetric strain at lock, -ln(1 - phi0); 0 = no crush
constexpr int kGeoY0 = 4;        ///< intact von Mises strength at p = 0 [Pa]
constexpr int kGeoMuI = 5;       ///< intact dY/dp at p = 0 [-]
constexpr int kGeoYmax = 6;      ///< limit strength Ym [Pa]
constexpr int kGeoMuD = 7;       ///< damaged (rubble) friction slope dY/dp [-]
constexpr int kGeoT0 = 8;        ///< intact tensile strength (pressure cut-off) [Pa]
constexpr int kGeoBeta = 9;      ///< dilatancy ratio beta0 = d theta_d / d eps_p at p = 0 [-]
constexpr int kGeoPbd = 10;      ///< pressure at which dilatancy vanishes [Pa]
constexpr int kGeoEpsD = 11;     ///< dilatant volumetric strain at full damage [-]
constexpr int kGeoHc = 12;       ///< compaction hardening: strength factor 1 + h_c at lock [-]
constexpr int kGeoGf = 13;       ///< fracture energy G_f of the tensile softening [J/m^2]; 0 = off

// history layout
constexpr int kGeoHistDamage = 0;  ///< D [-]
constexpr int kGeoHistTensile = 1; ///< remaining tensile strength T [Pa]
constexpr int kGeoHistThetaP = 2;  ///< theta_p, plastic volumetric strain (compaction > 0)
constexpr int kGeoHistThetaC = 3;  ///< theta_c, largest theta_p reached (sets the modulus)
constexpr int kGeoHistThetaD = 4;  ///< theta_d, accumulated dilatant strain (sets D)

/// \brief Bulk modulus after compaction x (x = theta_c).
KOKKOS_INLINE_FUNCTION Real geoBulk(const MaterialParams &p, Real x)
{
  const Real tl = p.model_params[kGeoThetaLock];
  if (tl <= 0)
    return p.bulk;
  return p.bulk + (p.model_params[kGeoKs] - p.bulk) * material_math::clamp(x / tl, 0, 1);
}

/// \brief Crush pressure [Pa] at plastic volumetric strain 0 <= x < theta_L.
KOKKOS_INLINE_FUNCTION Real geoCrushPressure(const MaterialParams &p, Real x)
{
  const Real *m = p.model_params;
  return m[kGeoPcrush] + (m[kGeoPlock] - m[kGeoPcrush]) * x / m[kGeoThetaLock];
}

/// \brief Shear strength (von Mises) [Pa] at pressure P, damage D and compaction theta_p.
KOKKOS_INLINE_FUNCTION Real geoStrength(const MaterialParams &p, Real P, Real D, Real theta_p)
{
  const Real *m = p.model_params;
  const Real y0 = m[kGeoY0], ym = m[kGeoYmax];
  const Real yi = P >= 0 ? y0 + m[kGeoMuI] * P / (1 + m[kGeoMuI] * P / (ym - y0))
                         : y0 * material_math::max(0, 1 + P / m[kGeoT0]);
  const Real yd = material_math::min(m[kGeoMuD] * material_math::max(P, 0), ym);
  const Real tl = m[kGeoThetaLock];
  const Real h = tl > 0 ? 1 + m[kGeoHc] * material_math::clamp(theta_p / tl, 0, 1) : Real(1);
  return h * ((1 - D) * yi + D * yd);
}

/// \brief Damage from the accumulated dilatant strain.
KOKKOS_INLINE_FUNCTION Real geoDamage(const MaterialParams &p, Real theta_d)
{
  return material_math::clamp(theta_d / p.model_params[kGeoEpsD], 0, 1);
}

/// \brief Dilatancy ratio beta(P): plastic volume increase per unit eq. plastic shear strain.
KOKKOS_INLINE_FUNCTION Real geoDilatancy(const MaterialParams &p, Real P)
{
  const Real *m = p.model_params;
  return m[kGeoBeta] * material_math::max(0, 1 - P / m[kGeoPbd]);
}

/// \brief Volumetric state of one element during its update.
struct GeoState
{
  Real theta; ///< total volumetric strain measured from theta_p's origin
  Real P;     ///< pressure [Pa]
  Real theta_p, theta_c, theta_d, D;
};

/// \brief Crush residual K(max(theta_c, x)) (theta - x) - p_c(x); decreasing in x where the
/// compaction stiffening is slower than the loss of elastic strain (all physical sets).
struct GeoCrushResidual
{
  const MaterialParams *p;
  Real theta, theta_c;
  KOKKOS_INLINE_FUNCTION Real operator()(Real x) const
  {
    return geoBulk(*p, material_math::max(theta_c, x)) * (theta - x) - geoCrushPressure(*p, x);
  }
};

/// \brief Compaction under positive pressure. Open cracks (theta_p < 0, volume gained by
/// dilatancy or tension) close first, at no pressure; then porosity collapses where P exceeds
/// the crush curve.
KOKKOS_INLINE_FUNCTION void geoCrush(const MaterialParams &p, GeoState &g)
{
  if (g.P <= 0)
    return;
  if (g.theta_p < 0)
  {
    g.theta_p = material_math::min(g.theta, 0);
    g.P = geoBulk(p, g.theta_c) * (g.theta - g.theta_p);
  }
  const Real tl = p.model_params[kGeoThetaLock];
  if (tl <= 0 || g.theta_p >= tl || g.P <= geoCrushPressure(p, g.theta_p))
    return;
  GeoCrushResidual f{&p, g.theta, g.theta_c};
  const Real f_lock = p.model_params[kGeoKs] * (g.theta - tl) - p.model_params[kGeoPlock];
  if (f_lock >= 0)
    g.theta_p = tl; // all crushable porosity closed
  else
    g.theta_p = bracketedRoot(f, g.theta_p, f(g.theta_p), tl, f_lock, 1e-15,
                              1e-13 * p.model_params[kGeoPlock]);
  g.theta_c = material_math::max(g.theta_c, g.theta_p);
  g.P = geoBulk(p, g.theta_c) * (g.theta - g.theta_p);
}

/// \brief Opening strain eps_t [-] that takes the tensile strength from T0 to zero in an
/// element of characteristic length L [m]: the crack band 2 G_f / (T0 L) with a fracture
/// energy (the softening line then dissipates T0 eps_t / 2 = G_f / L per unit volume), else
/// eps_d (softening per unit volume, whatever the element's size).
KOKKOS_INLINE_FUNCTION Real geoTensileOpening(const MaterialParams &p, Real L)
{
  const Real *m = p.model_params;
  return m[kGeoGf] > 0 ? 2 * m[kGeoGf] / (m[kGeoT0] * L) : m[kGeoEpsD];
}

/// \brief Tension cut-off with softening: opening beyond p = -T0 (1 - D) is dilatant strain,
/// which raises D by (eps_d / eps_t) per unit opening (eps_t: geoTensileOpening).
/// K (theta - x) = -T0 (1 - (theta_d + (theta_p - x) eps_d / eps_t)/eps_d) is linear in the
/// new theta_p = x; full damage leaves p = 0. An element too large for its crack band
/// (eps_t <= T0 / K: the softening would snap back) breaks at once.
KOKKOS_INLINE_FUNCTION void geoTension(const MaterialParams &p, Real eps_t, GeoState &g)
{
  const Real t0 = p.model_params[kGeoT0], ed = p.model_params[kGeoEpsD];
  if (g.P >= -t0 * (1 - g.D))
    return;
  const Real K = geoBulk(p, g.theta_c);
  const Real gain = ed / eps_t; // exactly 1 without a fracture energy
  const Real den = t0 / eps_t - K;
  Real x = den < 0 ? (-t0 + t0 * (g.theta_d + g.theta_p * gain) / ed - K * g.theta) / den : g.theta;
  Real td = g.theta_d + (g.theta_p - x) * gain;
  if (den >= 0 || td >= ed)
  {
    x = g.theta; // fully damaged: no tension left
    td = g.theta_d + (g.theta_p - x) * gain;
  }
  g.theta_d = td;
  g.theta_p = x;
  g.D = geoDamage(p, td);
  g.P = K * (g.theta - x);
}

/// \brief Consistency residual of the shear return with dilatancy for a plastic increment d:
/// q_trial - 3 G d - Y(P + K beta d, D(theta_d + beta d), theta_p - beta d).
struct GeoShearResidual
{
  const MaterialParams *p;
  Real q_trial, K, beta;
  GeoState g;
  KOKKOS_INLINE_FUNCTION Real operator()(Real d) const
  {
    const Real bd = beta * d;
    return q_trial - 3 * p->shear * d -
           geoStrength(*p, g.P + K * bd, geoDamage(*p, g.theta_d + bd), g.theta_p - bd);
  }
};

/// \brief Geomaterial step. The volumetric part goes first (crush, tension), then the shear
/// return, whose dilatancy can only raise P and D; the tension cut-off is checked again for
/// the reduced T. Energy as in updateMaterial(): trapezoidal in stress.
KOKKOS_INLINE_FUNCTION Real geomaterialUpdate(const MaterialParams &p, const MaterialStep &st,
                                              Real stress[6], Real &e, Real &eps,
                                              Real history[kHistorySize])
{
  const Real trD = trace(st.D);
  Real s_old[6];
  for (int k = 0; k < 6; ++k)
    s_old[k] = stress[k];
  const Real p_old = -makeDeviatoric(s_old);

  GeoState g;
  g.theta_p = history[kGeoHistThetaP];
  g.theta_c = history[kGeoHistThetaC];
  g.theta_d = history[kGeoHistThetaD];
  g.D = history[kGeoHistDamage];
  // incremental (log) volumetric strain keeps any initial pressure consistent
  const Real K_old = geoBulk(p, g.theta_c);
  g.theta = g.theta_p + p_old / K_old + kmath::log(st.rho_new / st.rho_old);
  g.P = K_old * (g.theta - g.theta_p);
  geoCrush(p, g);
  const Real eps_t = geoTensileOpening(p, st.length);
  geoTension(p, eps_t, g);

  Real s[6];
  for (int k = 0; k < 6; ++k)
    s[k] = s_old[k] + 2 * p.shear * st.dt * st.D[k];
  for (int k = 0; k < 3; ++k)
    s[k] -= 2 * p.shear * st.dt * trD / 3;
  const Real q_trial = vonMises(s);
  const Real y = geoStrength(p, g.P, g.D, g.theta_p);
  if (q_trial > y)
  {
    const Real K = geoBulk(p, g.theta_c);
    GeoShearResidual f{&p, q_trial, K, geoDilatancy(p, g.P), g};
    const Real hi = q_trial / (3 * p.shear);
    const Real d = bracketedRoot(f, Real(0), q_trial - y, hi, f(hi), 1e-15 * hi, 1e-13 * q_trial);
    const Real scale = 1 - 3 * p.shear * d / q_trial;
    for (int k = 0; k < 6; ++k)
      s[k] *= scale;
    eps += d;
    const Real bd = f.beta * d;
    g.P += K * bd;
    g.theta_p -= bd;
    g.theta_d += bd;
    g.D = geoDamage(p, g.theta_d);
    geoTension(p, eps_t, g);
  }

  history[kGeoHistDamage] = g.D;
  history[kGeoHistTensile] = p.model_params[kGeoT0] * (1 - g.D);
  history[kGeoHistThetaP] = g.theta_p;
  history[kGeoHistThetaC] = g.theta_c;
  history[kGeoHistThetaD] = g.theta_d;

  const Real rho_mid = 0.5 * (st.rho_old + st.rho_new);
  Real s_mid[6];
  for (int k = 0; k < 6; ++k)
    s_mid[k] = 0.5 * (s_old[k] + s[k]);
  e += st.dt / rho_mid * (contract(s_mid, st.D) - (0.5 * (p_old + g.P) + st.q) * trD);
  for (int k = 0; k < 6; ++k)
    stress[k] = s[k];
  for (int k = 0; k < 3; ++k)
    stress[k] -= g.P;
  return kmath::sqrt(pWaveModulus(geoBulk(p, g.theta_c), p.shear) / st.rho_new);
}

} // namespace scpdyn
