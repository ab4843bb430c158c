#pragma once
/// \file JohnsonCook.hpp
/// \brief J2 plasticity with the Johnson-Cook (1983) flow stress
///   sigma_y = (A + B eps_p^n) (1 + C ln(epsdot_p / epsdot_0)) (1 - T*^m),
///   T* = (T - T_room) / (T_melt - T_room),
/// and adiabatic heating dT = chi sigma_y d eps_p / (rho c_p). The pressure comes from the
/// material's EOS (linear or Mie-Gruneisen) in updateMaterial(). See docs/theory_materials.md.
#include "material/MaterialParams.hpp"
#include "material/MaterialMath.hpp"
#include "material/TensorOps.hpp"

namespace scpdyn
{

// model_params layout
constexpr int kJcA = 0;     ///< A: initial yield stress [Pa]
constexpr int kJcB = 1;     ///< B: hardening modulus [Pa]
constexpr int kJcN = 2;     ///< n: hardening exponent [-]
constexpr int kJcC = 3;     ///< C: strain-rate coefficient [-]
constexpr int kJcM = 4;     ///< m: thermal-softening exponent [-]
constexpr int kJcTmelt = 5; ///< melt temperature [K]; 0 = no thermal softening
constexpr int kJcTroom = 6; ///< room (reference and initial) temperature [K]
constexpr int kJcRate0 = 7; ///< reference strain rate epsdot_0 [1/s]
constexpr int kJcCp = 8;    ///< specific heat c_p [J/(kg K)]; 0 = isothermal
constexpr int kJcChi = 9;   ///< Taylor-Quinney fraction of plastic work turned to heat

// history layout
constexpr int kJcHistTemperature = 0; ///< temperature [K]
constexpr int kJcHistRate = 1;        ///< equivalent plastic strain rate of the last step [1/s]

/// \brief Johnson-Cook flow stress [Pa] at equivalent plastic strain eps, equivalent plastic
/// strain rate `rate` [1/s] and temperature T [K]. The rate factor is 1 below epsdot_0 (no
/// softening below the reference rate, as LS-DYNA and Radioss do); the thermal factor is 1
/// below room temperature and 0 at or above melt.
KOKKOS_INLINE_FUNCTION Real johnsonCookFlowStress(const MaterialParams &p, Real eps, Real rate,
                                                  Real T)
{
  const Real *m = p.model_params;
  const Real hard = m[kJcA] + (eps > 0 ? m[kJcB] * kmath::pow(eps, m[kJcN]) : Real(0));
  const Real rr = rate / m[kJcRate0];
  const Real rate_factor = rr > 1 ? 1 + m[kJcC] * kmath::log(rr) : Real(1);
  Real thermal = 1;
  if (m[kJcTmelt] > 0)
  {
    const Real ts = (T - m[kJcTroom]) / (m[kJcTmelt] - m[kJcTroom]);
    thermal = ts <= 0 ? Real(1) : ts >= 1 ? Real(0) : 1 - kmath::pow(ts, m[kJcM]);
  }
  return hard * rate_factor * thermal;
}

/// \brief Residual of the viscoplastic consistency condition for a plastic increment d:
/// q_trial - 3 G d - sigma_y(eps + d, d/dt, T). Strictly decreasing in d.
struct JohnsonCookResidual
{
  const MaterialParams *p;
  Real q_trial, eps, dt, T;
  KOKKOS_INLINE_FUNCTION Real operator()(Real d) const
  {
    const Real rate = dt > 0 ? d / dt : Real(0);
    return q_trial - 3 * p->shear * d - johnsonCookFlowStress(*p, eps + d, rate, T);
  }
};

/// \brief Radial return on the deviator s (in place) with the Johnson-Cook flow stress; the
/// plastic strain rate of the rate term is the increment's own (d eps_p / dt), so the
/// returned stress lies exactly on the rate-dependent yield surface. Temperature is held at
/// its start-of-step value (heating is applied after the return). Returns d eps_p.
KOKKOS_INLINE_FUNCTION Real johnsonCookReturn(const MaterialParams &p, Real s[6], Real eps, Real dt,
                                              Real T)
{
  const Real q_trial = vonMises(s);
  JohnsonCookResidual g{&p, q_trial, eps, dt, T};
  const Real g0 = q_trial - johnsonCookFlowStress(p, eps, 0, T);
  if (g0 <= 0)
    return 0;
  const Real hi = q_trial / (3 * p.shear);
  const Real d = bracketedRoot(g, Real(0), g0, hi, g(hi), 1e-15 * hi, 1e-13 * q_trial);
  const Real scale = 1 - 3 * p.shear * d / q_trial;
  for (int k = 0; k < 6; ++k)
    s[k] *= scale;
  return d;
}

/// \brief Johnson-Cook deviatoric step: return mapping, plastic strain, rate and adiabatic
/// temperature rise (chi q d eps_p / (rho c_p), q the returned von Mises stress).
KOKKOS_INLINE_FUNCTION void johnsonCookDeviatoric(const MaterialParams &p, const MaterialStep &st,
                                                  Real s[6], Real &eps, Real history[kHistorySize])
{
  const Real d = johnsonCookReturn(p, s, eps, st.dt, history[kJcHistTemperature]);
  eps += d;
  history[kJcHistRate] = st.dt > 0 ? d / st.dt : Real(0);
  const Real cp = p.model_params[kJcCp];
  if (cp > 0 && d > 0)
    history[kJcHistTemperature] += p.model_params[kJcChi] * vonMises(s) * d / (st.rho_new * cp);
}

} // namespace scpdyn
