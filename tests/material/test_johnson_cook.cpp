// Johnson-Cook plasticity: the flow-stress function against the 1983 formula, the returned
// stress against it along a driven path (rate = the step's plastic rate), adiabatic heating,
// and the steady plastic rate of a constant-rate uniaxial-strain path.
#include "MaterialTestUtil.hpp"

#include <gtest/gtest.h>

namespace scpdyn::test
{
namespace
{

// OFHC copper, Johnson & Cook (1983), verification.md T7b
MaterialParams ofhcCopper(bool thermal)
{
  MaterialSpec s = makeSpec("johnson_cook", "mie_gruneisen",
                            {{"density", 8960},
                             {"shear_modulus", 46e9},
                             {"A", 90e6},
                             {"B", 292e6},
                             {"n", 0.31},
                             {"C", 0.025},
                             {"eos.c0", 3940},
                             {"eos.s", 1.49},
                             {"eos.gamma0", 1.96}});
  if (thermal)
  {
    s.values["m"] = 1.09;
    s.values["melt_temperature"] = 1356;
    s.values["specific_heat"] = 383;
  }
  return makeMaterialParams(s);
}

// the formula written out independently of JohnsonCook.hpp
double jcFormula(double A, double B, double n, double C, double m, double Tm, double eps,
                 double rate, double T)
{
  const double ts = (T - 294) / (Tm - 294);
  return (A + B * std::pow(eps, n)) * (1 + C * std::log(std::max(rate, 1.0))) *
         (ts <= 0 ? 1.0 : 1 - std::pow(ts, m));
}

TEST(JohnsonCook, FlowStressFormula)
{
  const MaterialParams p = ofhcCopper(true);
  for (double eps : {0.0, 0.01, 0.1, 0.5, 2.0})
    for (double rate : {0.1, 1.0, 1e3, 1e5})
      for (double T : {294.0, 500.0, 1000.0})
        EXPECT_LT(relErr(johnsonCookFlowStress(p, eps, rate, T),
                         jcFormula(90e6, 292e6, 0.31, 0.025, 1.09, 1356, eps, rate, T)),
                  1e-14);
  // no strength at or above melt
  EXPECT_EQ(johnsonCookFlowStress(p, 0.1, 1e3, 1356), 0.0);
  EXPECT_EQ(johnsonCookFlowStress(p, 0.1, 1e3, 1500), 0.0);
  // 4340 steel (JC 1983) at eps_p = 0.2, rate 1e3 /s, room temperature: by hand
  // (792 + 510 * 0.2^0.26) (1 + 0.014 ln 1000) = 1172.8... MPa
  MaterialParams st = p;
  st.model_params[kJcA] = 792e6, st.model_params[kJcB] = 510e6, st.model_params[kJcN] = 0.26;
  st.model_params[kJcC] = 0.014;
  const double by_hand = (792e6 + 510e6 * std::pow(0.2, 0.26)) * (1 + 0.014 * std::log(1e3));
  EXPECT_LT(relErr(johnsonCookFlowStress(st, 0.2, 1e3, 294), by_hand), 1e-14);
}

TEST(JohnsonCook, DrivenPathStaysOnRateDependentSurface)
{
  const MaterialParams p = ofhcCopper(true);
  MaterialPoint mp(p);
  EXPECT_EQ(mp.history[kJcHistTemperature], 294.0);
  const Real rate = 1e4, dt = 2e-8; // 2e-4 axial strain per step, 0.4 in total
  const Real D[6] = {-rate, 0.5 * rate, 0.5 * rate, 0, 0, 0}; // isochoric: steady rate 1e4
  Real heat = 0;
  for (int n = 0; n < 2000; ++n)
  {
    const Real T_old = mp.history[kJcHistTemperature], eps_old = mp.eps;
    mp.step(D, dt);
    const Real d = mp.eps - eps_old;
    if (d == 0)
      continue;
    // the returned von Mises stress is the JC stress at the new strain, the step's plastic
    // rate and the start-of-step temperature (root tolerance 1e-13 relative)
    const Real jc = jcFormula(90e6, 292e6, 0.31, 0.025, 1.09, 1356, mp.eps, d / dt, T_old);
    EXPECT_LT(relErr(mp.mises(), jc), 1e-10) << "step " << n;
    // d = eps_new - eps_old loses ~eps/d ulps (2e-4 increments on eps ~ 0.4)
    EXPECT_LT(relErr(mp.history[kJcHistRate], d / dt), 1e-11);
    heat += 0.9 * mp.mises() * d / (mp.rho * 383);
  }
  EXPECT_LT(relErr(mp.history[kJcHistTemperature] - 294, heat), 1e-12);
  // isochoric path: equivalent strain rate = |D_xx| (sqrt(2/3 D:D)); once the elastic
  // transient is over the plastic rate equals it up to the hardening-driven elastic part
  // (dq/dt / 3G ~ 1e-3 of the rate here)
  EXPECT_LT(relErr(mp.history[kJcHistRate], rate), 5e-3);
  // heating from the plastic work: rough check against chi * sigma * eps / (rho c_p)
  EXPECT_GT(mp.history[kJcHistTemperature], 294 + 0.9 * 150e6 * 0.3 / (8960 * 383));
}

TEST(JohnsonCook, IsothermalWithoutMeltTemperature)
{
  const MaterialParams p = ofhcCopper(false);
  MaterialPoint mp(p);
  const Real D[6] = {-1e3, 500, 500, 0, 0, 0};
  for (int n = 0; n < 500; ++n)
    mp.step(D, 2e-7);
  EXPECT_EQ(mp.history[kJcHistTemperature], 294.0);
  const Real jc = jcFormula(90e6, 292e6, 0.31, 0.025, 1.0, 1e9, mp.eps,
                            mp.history[kJcHistRate], 294);
  EXPECT_LT(relErr(mp.mises(), jc), 1e-10);
}

} // namespace
} // namespace scpdyn::test
