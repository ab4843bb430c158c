#pragma once
/// \file MaterialUpdate.hpp
/// \brief The device-side stress update of every material model: one switch on the model.
#include "material/Geomaterial.hpp"
#include "material/JohnsonCook.hpp"
#include "material/Jwl.hpp"
#include "material/MaterialParams.hpp"
#include "material/MetalUpdate.hpp"
#include "material/TensorOps.hpp"

namespace scpdyn
{

/// \brief Set-up of an element's history slots before the first cycle from the element
/// centroid [m]: the lighting time of a programmed burn, the room temperature of a
/// Johnson-Cook material, the intact tensile strength of a geomaterial; all else zero.
KOKKOS_INLINE_FUNCTION void initializeMaterialHistory(const MaterialParams &p,
                                                      const Real centroid[3],
                                                      Real history[kHistorySize])
{
  for (int k = 0; k < kHistorySize; ++k)
    history[k] = 0;
  switch (p.model)
  {
  case MaterialModel::JohnsonCook:
    history[kJcHistTemperature] = p.model_params[kJcTroom];
    break;
  case MaterialModel::Geomaterial:
    history[kGeoHistTensile] = p.model_params[kGeoT0];
    break;
  case MaterialModel::HighExplosive:
    history[kHeHistLightTime] = lightingTime(p, centroid);
    break;
  default:
    break;
  }
}

/// \brief Mie-Gruneisen reference pressure A(mu) and Gruneisen factor B(mu) with
/// p = A(mu) + B(mu) * rho0 * e (LS-DYNA *EOS_GRUNEISEN form, e specific internal energy).
/// Also returns dA/dmu for the sound speed.
KOKKOS_INLINE_FUNCTION void mieGruneisenParts(const MaterialParams &p, Real mu, Real &A, Real &dA,
                                              Real &B)
{
  const Real rc2 = p.density * p.mg_c0 * p.mg_c0;
  if (mu > 0)
  {
    const Real k = 1 - 0.5 * p.mg_gamma0;
    const Real den = 1 - (p.mg_s - 1) * mu;
    const Real num = mu * (1 + k * mu);
    A = rc2 * num / (den * den);
    dA = rc2 * ((1 + 2 * k * mu) * den + 2 * (p.mg_s - 1) * num) / (den * den * den);
  }
  else
  {
    A = rc2 * mu;
    dA = rc2;
  }
  B = p.mg_gamma0 + p.mg_a * mu;
}

/// \brief J2 radial return with linear isotropic hardening on the deviator s (in place).
/// Returns the plastic strain increment.
KOKKOS_INLINE_FUNCTION Real radialReturn(const MaterialParams &p, Real s[6], Real eps)
{
  const Real q_trial = vonMises(s);
  const Real sy = p.yield_stress + p.hardening_modulus * eps;
  if (q_trial <= sy)
    return 0;
  const Real deps = (q_trial - sy) / (3 * p.shear + p.hardening_modulus);
  const Real scale = 1 - 3 * p.shear * deps / q_trial;
  for (int k = 0; k < 6; ++k)
    s[k] *= scale;
  return deps;
}

/// \brief Update stress (already rotated to the current configuration), specific internal
/// energy e [J/kg] and history for one step; returns the sound speed [m/s].
///
/// Energy: de = dt/rho_mid (sigma_mid : D - q tr D) (trapezoidal in stress), so the internal
/// energy of the element (m e) receives exactly the work of the stress and viscosity forces
/// to second order. For the Mie-Gruneisen and JWL EOS the pressure is linear in e, so p_new
/// and e_new are solved together without iteration. The geomaterial and the high explosive
/// own their whole update (Geomaterial.hpp, Jwl.hpp); the metals share the EOS switch below.
KOKKOS_INLINE_FUNCTION Real updateMaterial(const MaterialParams &p, const MaterialStep &st,
                                           Real stress[6], Real &e, Real &eps,
                                           Real history[kHistorySize])
{
  if (p.model == MaterialModel::Geomaterial)
    return geomaterialUpdate(p, st, stress, e, eps, history);
  if (p.model == MaterialModel::HighExplosive)
    return highExplosiveUpdate(p, st, stress, e, history);

  // the stages live in MetalUpdate.hpp, templated, so the element lanes run the same text
  Real s_old[6], s[6], p_old, trD;
  metalTrial(p, st.D, st.dt, stress, s_old, s, p_old, trD);
  if (p.model == MaterialModel::ElasticPlastic)
    eps += radialReturn(p, s, eps);
  else if (p.model == MaterialModel::JohnsonCook)
    johnsonCookDeviatoric(p, st, s, eps, history);

  Real h;
  const Real e_star =
      metalEnergyStar(s_old, s, st.D, trD, p_old, st.q, st.dt, st.rho_old, st.rho_new, e, h);

  Real p_new = 0, c2 = 0;
  switch (p.eos)
  {
  case EosModel::Linear:
    c2 = linearEos(p, p_old, trD, st.dt, h, e_star, st.rho_new, p_new, e);
    break;
  case EosModel::MieGruneisen:
  {
    const Real mu = st.rho_new / p.density - 1;
    Real A, dA, B;
    mieGruneisenParts(p, mu, A, dA, B);
    const Real hh = 0.5 * h * trD;
    e = (e_star - hh * A) / (1 + hh * B * p.density);
    p_new = A + B * p.density * e;
    // c^2 = dp/drho|_e + p/rho^2 dp/de|_rho, plus the shear contribution
    const Real dp_drho = (dA + p.mg_a * p.density * e) / p.density;
    c2 = dp_drho + p_new / (st.rho_new * st.rho_new) * B * p.density +
         4.0 / 3.0 * p.shear / st.rho_new;
    break;
  }
  case EosModel::Jwl: // only with HighExplosive, dispatched above
    break;
  }
  metalStress(s, p_new, stress);
  const Real c2_floor = soundSpeedSquaredFloor(p);
  return kmath::sqrt(c2 > c2_floor ? c2 : c2_floor);
}

/// \brief Whether updateMaterial() reads or writes the history slots for this model: the
/// elastic and J2 models (any EOS) do not, so the element kernel skips their 8 slots (load
/// and store: they keep the zeros initializeMaterialHistory() gave them). Johnson-Cook
/// (temperature), the geomaterial and the high explosive do.
KOKKOS_INLINE_FUNCTION constexpr bool modelUsesHistory(MaterialModel m)
{
  return !(m == MaterialModel::Elastic || m == MaterialModel::ElasticPlastic);
}

} // namespace scpdyn
