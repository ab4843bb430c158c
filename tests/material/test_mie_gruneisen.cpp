// Mie-Gruneisen EOS: one update from rest to a compressed density is a Rankine-Hugoniot jump
// (the trapezoidal energy update is e1 - e0 = (p0 + p1)/2 (v0 - v1)), so it must land on the
// Us-up Hugoniot p_H = rho0 c0^2 mu (1 + mu) / (1 - (s - 1) mu)^2 exactly.
#include "MaterialTestUtil.hpp"

#include <gtest/gtest.h>

namespace scpdyn::test
{
namespace
{

MaterialParams copperMG()
{
  // Steinberg (1996) copper as in verification.md T7b
  return makeMaterialParams(makeSpec("johnson_cook", "mie_gruneisen",
                                     {{"density", 8960},
                                      {"shear_modulus", 46e9},
                                      {"A", 90e6},
                                      {"B", 292e6},
                                      {"n", 0.31},
                                      {"eos.c0", 3940},
                                      {"eos.s", 1.49},
                                      {"eos.gamma0", 1.96}}));
}

// One isotropic step from (rho0, e = 0, p = 0) to rho1 with tr D dt chosen so that
// dt tr D / rho_mid = v1 - v0 (the element kernel's volumetric kinematics to this order).
MaterialPoint shockTo(const MaterialParams &p, Real mu)
{
  MaterialPoint mp(p);
  const Real rho1 = p.density * (1 + mu);
  MaterialStep st;
  const Real rho_mid = 0.5 * (p.density + rho1);
  const Real trD_dt = rho_mid * (1 / rho1 - 1 / p.density);
  st.dt = 1e-9;
  for (int k = 0; k < 6; ++k)
    st.D[k] = k < 3 ? trD_dt / st.dt / 3 : 0;
  st.rho_old = p.density;
  st.rho_new = rho1;
  st.q = 0;
  st.time = 0;
  st.length = 1e-3;
  mp.c = updateMaterial(p, st, mp.stress, mp.e, mp.eps, mp.history);
  mp.rho = rho1;
  return mp;
}

TEST(MieGruneisen, SingleStepLandsOnHugoniot)
{
  const MaterialParams p = copperMG();
  for (Real mu : {0.01, 0.05, 0.1, 0.2, 0.3})
  {
    const MaterialPoint mp = shockTo(p, mu);
    const Real den = 1 - (p.mg_s - 1) * mu;
    const Real pH = p.density * p.mg_c0 * p.mg_c0 * mu * (1 + mu) / (den * den);
    EXPECT_LT(relErr(mp.pressure(), pH), 1e-12) << "mu = " << mu;
    // Hugoniot energy e_H = p_H (v0 - v1) / 2
    EXPECT_LT(relErr(mp.e, 0.5 * pH * (1 / p.density - 1 / mp.rho)), 1e-12);
    // Us = c0 + s up with up = sqrt(p (v0 - v1)): the same curve in Us-up form
    const Real up = std::sqrt(pH * (1 / p.density - 1 / mp.rho));
    const Real us = pH / (p.density * up);
    EXPECT_LT(relErr(us, p.mg_c0 + p.mg_s * up), 1e-12);
  }
}

TEST(MieGruneisen, ExpansionBranchAndSoundSpeed)
{
  const MaterialParams p = copperMG();
  // at rest the bulk sound speed is c0 (plus the shear term)
  const MaterialPoint rest = shockTo(p, 0.0);
  const Real cl = std::sqrt(p.mg_c0 * p.mg_c0 + 4.0 / 3.0 * p.shear / p.density);
  EXPECT_LT(relErr(rest.c, cl), 1e-12);
  // in tension the reference curve is linear: p = rho0 c0^2 mu + gamma0 rho0 e
  const MaterialPoint ten = shockTo(p, -0.01);
  const Real mu = -0.01;
  EXPECT_LT(
      relErr(ten.pressure(), p.density * p.mg_c0 * p.mg_c0 * mu + p.mg_gamma0 * p.density * ten.e),
      1e-12);
}

} // namespace
} // namespace scpdyn::test
