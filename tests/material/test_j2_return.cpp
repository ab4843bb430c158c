// J2 radial return with linear hardening (model elastic_plastic): the returned stress lies on
// the yield surface, the plastic flow is normal to it, the uniaxial-strain path has the closed
// form eps_p = (2 G eps - sigma_y) / (3 G + H), and the energy receives the trapezoidal work.
#include "MaterialTestUtil.hpp"

#include <gtest/gtest.h>

namespace scpdyn::test
{
namespace
{

MaterialParams steelJ2()
{
  return makeMaterialParams(makeSpec("elastic_plastic", "linear",
                                     {{"density", 7850},
                                      {"youngs_modulus", 200e9},
                                      {"poisson_ratio", 0.3},
                                      {"yield_stress", 400e6},
                                      {"hardening_modulus", 2e9}}));
}

TEST(J2Return, UniaxialStrainMatchesClosedForm)
{
  const MaterialParams p = steelJ2();
  MaterialPoint mp(p);
  const Real rate = 100, dt = 1e-7; // 1e-5 strain per step
  const Real D[6] = {-rate, 0, 0, 0, 0, 0};
  Real strain = 0;
  for (int n = 0; n < 1000; ++n)
  {
    mp.step(D, dt);
    strain += rate * dt;
    // Along a straight deviatoric path the radial return is exact for linear hardening:
    // q_trial - 3 G eps_p = sigma_y0 + H eps_p with q_trial = 2 G strain.
    const Real eps_exact = std::max(0.0, (2 * p.shear * strain - p.yield_stress) /
                                             (3 * p.shear + p.hardening_modulus));
    EXPECT_NEAR(mp.eps, eps_exact, 1e-12 + 1e-10 * eps_exact) << "step " << n;
    // pressure of the linear EOS: K times the volumetric strain; axial stress -(p + 2/3 q)
    const Real q =
        eps_exact > 0 ? p.yield_stress + p.hardening_modulus * eps_exact : 2 * p.shear * strain;
    const Real sxx = -(p.bulk * strain + 2.0 / 3.0 * q);
    EXPECT_LT(relErr(mp.stress[0], sxx), 1e-10) << "step " << n;
  }
  EXPECT_GT(mp.eps, 0.004); // the path went well into the plastic range
}

TEST(J2Return, ReturnedStressOnYieldSurfaceAndNormal)
{
  const MaterialParams p = steelJ2();
  MaterialPoint mp(p);
  const Real dt = 2e-7;
  // non-proportional path: shear, then tension-compression, then mixed
  const Real paths[3][6] = {
      {0, 0, 0, 300, 0, 0}, {200, -100, -100, 0, 0, 0}, {-150, 50, 20, 100, -80, 60}};
  int plastic_steps = 0;
  for (const auto &D : paths)
    for (int n = 0; n < 300; ++n)
    {
      // trial deviator computed independently
      Real s_trial[6];
      for (int k = 0; k < 6; ++k)
        s_trial[k] = mp.stress[k];
      makeDeviatoric(s_trial);
      const Real trD = D[0] + D[1] + D[2];
      for (int k = 0; k < 6; ++k)
        s_trial[k] += 2 * p.shear * dt * (D[k] - (k < 3 ? trD / 3 : 0));
      const Real eps_old = mp.eps;
      mp.step(D, dt);
      if (mp.eps == eps_old)
        continue;
      ++plastic_steps;
      Real s[6];
      for (int k = 0; k < 6; ++k)
        s[k] = mp.stress[k];
      makeDeviatoric(s);
      // on the yield surface (the return is closed-form: round-off only)
      EXPECT_LT(relErr(vonMises(s), p.yield_stress + p.hardening_modulus * mp.eps), 1e-12);
      // normality: plastic strain increment (s_trial - s)/(2G) parallel to s, and its
      // equivalent sqrt(2/3 de:de) is the equivalent plastic strain increment
      const Real lambda = contract(s, s_trial) / contract(s_trial, s_trial);
      Real de[6], off = 0;
      for (int k = 0; k < 6; ++k)
      {
        off = std::max(off, std::fabs(s[k] - lambda * s_trial[k]));
        de[k] = (s_trial[k] - s[k]) / (2 * p.shear);
      }
      EXPECT_LT(off, 1e-12 * vonMises(s));
      EXPECT_GT(lambda, 0);
      EXPECT_LT(lambda, 1);
      EXPECT_LT(relErr(std::sqrt(2.0 / 3.0 * contract(de, de)), mp.eps - eps_old), 1e-9);
    }
  EXPECT_GT(plastic_steps, 300);
}

TEST(J2Return, EnergyIsTrapezoidalStressWork)
{
  const MaterialParams p = steelJ2();
  MaterialPoint mp(p);
  const Real D[6] = {-150, 80, 20, 60, -30, 10};
  Real work = 0;
  for (int n = 0; n < 800; ++n)
  {
    mp.step(D, 1e-7, n % 3 == 0 ? 1e6 : 0.0); // with some viscous q work as well
    work += mp.last_work;
  }
  // de = dt/rho_mid (sigma_mid : D - q tr D), term by term: equal to round-off
  EXPECT_LT(relErr(mp.e, work), 1e-12);
  EXPECT_GT(mp.eps, 0);
}

} // namespace
} // namespace scpdyn::test
