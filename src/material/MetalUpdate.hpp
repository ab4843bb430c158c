#pragma once
/// \file MetalUpdate.hpp
/// \brief The stages of the metals' stress update (elastic, J2, Johnson-Cook: deviatoric trial,
/// trapezoidal energy, linear EOS, final stress) templated on the value type R: R = Real is
/// what updateMaterial() runs, R = a GCC vector of doubles (element/Lanes.hpp's LanePack) runs
/// W elements of one material at once. Every stage does the scalar arithmetic in the scalar
/// order, so a lane gives the bits of the scalar call (IEEE +, -, *, / are correctly rounded
/// in vector registers too). Only +, -, *, / and literals of type Real appear here: no branch,
/// no library call, so the same text compiles for both R.
#include "material/MaterialParams.hpp"

namespace scpdyn
{

/// \brief Deviatoric trial of the metals: trD = tr D, s_old = dev(stress), p_old = -tr/3 of
/// the old stress [Pa], s = s_old + 2 G dt dev(D) [Pa].
template <class R>
KOKKOS_INLINE_FUNCTION void metalTrial(const MaterialParams &p, const R D[6], Real dt,
                                       const R stress[6], R s_old[6], R s[6], R &p_old, R &trD)
{
  trD = D[0] + D[1] + D[2];
  for (int k = 0; k < 6; ++k)
    s_old[k] = stress[k];
  // products with 1/3 rather than divisions by 3: a vector division costs ~8 multiplications
  const R m = (s_old[0] + s_old[1] + s_old[2]) * Real(1.0 / 3.0);
  s_old[0] -= m;
  s_old[1] -= m;
  s_old[2] -= m;
  p_old = -m;
  const Real two_G_dt = Real(2) * p.shear * dt;
  for (int k = 0; k < 6; ++k)
    s[k] = s_old[k] + two_G_dt * D[k];
  const R volumetric = two_G_dt * Real(1.0 / 3.0) * trD;
  s[0] -= volumetric;
  s[1] -= volumetric;
  s[2] -= volumetric;
}

/// \brief Trapezoidal specific energy before the EOS work: returns e* = e + h (s_mid : D -
/// p_old trD / 2 - q trD) [J/kg] and h = dt / rho_mid [m^3 s/kg].
template <class R>
KOKKOS_INLINE_FUNCTION R metalEnergyStar(const R s_old[6], const R s[6], const R D[6], const R &trD,
                                         const R &p_old, const R &q, Real dt, const R &rho_old,
                                         const R &rho_new, const R &e, R &h)
{
  const R rho_mid = Real(0.5) * (rho_old + rho_new);
  R m[6];
  for (int k = 0; k < 6; ++k)
    m[k] = Real(0.5) * (s_old[k] + s[k]);
  h = dt / rho_mid;
  const R sD =
      m[0] * D[0] + m[1] * D[1] + m[2] * D[2] + Real(2) * (m[3] * D[3] + m[4] * D[4] + m[5] * D[5]);
  return e + h * (sD - Real(0.5) * p_old * trD - q * trD);
}

/// \brief Linear (hypoelastic) EOS: p_new = p_old - K dt trD [Pa], e = e* - h p_new trD / 2;
/// returns c^2 = (K + 4G/3) / rho_new [m^2/s^2].
template <class R>
KOKKOS_INLINE_FUNCTION R linearEos(const MaterialParams &p, const R &p_old, const R &trD, Real dt,
                                   const R &h, const R &e_star, const R &rho_new, R &p_new, R &e)
{
  p_new = p_old - p.bulk * dt * trD;
  e = e_star - Real(0.5) * h * p_new * trD;
  return pWaveModulus(p.bulk, p.shear) / rho_new;
}

/// \brief stress = s - p_new I [Pa].
template <class R>
KOKKOS_INLINE_FUNCTION void metalStress(const R s[6], const R &p_new, R stress[6])
{
  for (int k = 0; k < 6; ++k)
    stress[k] = s[k];
  stress[0] -= p_new;
  stress[1] -= p_new;
  stress[2] -= p_new;
}

/// \brief The whole update of the `elastic` model with the linear EOS (what updateMaterial()
/// runs for it): stress [Pa] and specific energy e [J/kg] in place; returns c^2 [m^2/s^2]
/// before the floor (the caller takes max(c^2, soundSpeedSquaredFloor) and its square root).
/// D [1/s], q the step's mean viscosity pressure [Pa], densities [kg/m^3].
template <class R>
KOKKOS_INLINE_FUNCTION R elasticLinearUpdate(const MaterialParams &p, const R D[6], Real dt,
                                             const R &rho_old, const R &rho_new, const R &q,
                                             R stress[6], R &e)
{
  R s_old[6], s[6], p_old, trD, h, p_new;
  metalTrial(p, D, dt, stress, s_old, s, p_old, trD);
  const R e_star = metalEnergyStar(s_old, s, D, trD, p_old, q, dt, rho_old, rho_new, e, h);
  const R c2 = linearEos(p, p_old, trD, dt, h, e_star, rho_new, p_new, e);
  metalStress(s, p_new, stress);
  return c2;
}

/// \brief Whether updateMaterial() of this material is elasticLinearUpdate() (so the element
/// kernel may run it on a pack of elements).
KOKKOS_INLINE_FUNCTION constexpr bool isElasticLinear(const MaterialParams &p)
{
  return p.model == MaterialModel::Elastic && p.eos == EosModel::Linear;
}

} // namespace scpdyn
