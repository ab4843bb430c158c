// Geomaterial (pseudo-cap): uniaxial-strain compaction along the crush curve, triaxial
// strength points on the yield surface, brittle softening by dilatancy to the damaged surface,
// tensile softening to zero, crack closure, and the trapezoidal energy identity. Reference
// formulas are written out here independently of Geomaterial.hpp.
#include "MaterialTestUtil.hpp"

#include <gtest/gtest.h>

#include <functional>

namespace scpdyn::test
{
namespace
{

// Parameter sets of docs/theory.md (limestone: MaterialTestUtil.hpp; concrete: HJC 48 MPa)
MaterialSpec concrete()
{
  return makeSpec("geomaterial", "linear",
                  {{"density", 2440},
                   {"bulk_modulus", 16e9},
                   {"shear_modulus", 14.86e9},
                   {"porosity", 0.0823},
                   {"crush_pressure", 16e6},
                   {"lock_pressure", 800e6},
                   {"solid_bulk_modulus", 85e9},
                   {"intact_strength", 12e6},
                   {"intact_friction", 2.53},
                   {"max_strength", 336e6},
                   {"damaged_friction", 1.05},
                   {"tensile_strength", 4e6},
                   {"damage_strain", 0.002},
                   {"dilatancy", 0.2},
                   {"dilatancy_pressure", 100e6},
                   {"compaction_hardening", 0.3}});
}

MaterialParams without(MaterialSpec s, std::initializer_list<const char *> keys)
{
  for (const char *k : keys)
    s.values.erase(k);
  return makeMaterialParams(s);
}

// independent yield surface (docs/theory_materials.md)
double yieldSurface(const MaterialParams &p, double P, double D, double theta_p)
{
  const double *m = p.model_params;
  const double y0 = m[kGeoY0], ym = m[kGeoYmax], mi = m[kGeoMuI];
  const double yi =
      P >= 0 ? y0 + mi * P / (1 + mi * P / (ym - y0)) : y0 * std::max(0.0, 1 + P / m[kGeoT0]);
  const double yd = std::min(m[kGeoMuD] * std::max(P, 0.0), ym);
  const double tl = m[kGeoThetaLock];
  const double h = tl > 0 ? 1 + m[kGeoHc] * std::min(std::max(theta_p / tl, 0.0), 1.0) : 1.0;
  return h * ((1 - D) * yi + D * yd);
}

// loading crush curve in the (theta, p) plane: elastic, then the parametric curve
// theta = x + p_c(x) / K(x), then the locked solid
double crushCurve(const MaterialParams &p, double theta, double *theta_p)
{
  const double *m = p.model_params;
  const double tl = m[kGeoThetaLock], pe = m[kGeoPcrush], pl = m[kGeoPlock], ks = m[kGeoKs];
  auto K = [&](double x) { return p.bulk + (ks - p.bulk) * x / tl; };
  auto pc = [&](double x) { return pe + (pl - pe) * x / tl; };
  *theta_p = 0;
  if (theta <= pe / p.bulk)
    return p.bulk * theta;
  if (theta >= tl + pl / ks)
  {
    *theta_p = tl;
    return ks * (theta - tl);
  }
  double lo = 0, hi = tl;
  for (int i = 0; i < 200; ++i)
  {
    const double x = 0.5 * (lo + hi);
    (x + pc(x) / K(x) < theta ? lo : hi) = x;
  }
  *theta_p = 0.5 * (lo + hi);
  return pc(*theta_p);
}

TEST(Geomaterial, UniaxialStrainCompactionFollowsCrushCurve)
{
  MaterialSpec s = concrete();
  s.values["dilatancy"] = 0; // pure compaction: the shear flow leaves the pressure alone
  const MaterialParams p = makeMaterialParams(s);
  MaterialPoint mp(p);
  const Real dt = 1e-7, rate = 1e3; // 1e-4 per step, to theta = 0.12 (beyond lock at 0.0953)
  const Real load[6] = {-rate, 0, 0, 0, 0, 0}, unload[6] = {rate, 0, 0, 0, 0, 0};
  double theta_p_max = 0;
  int plastic = 0;
  for (int n = 0; n < 1400; ++n)
  {
    const bool loading = n < 1200;
    mp.step(loading ? load : unload, dt);
    const double theta = std::log(mp.rho / p.density);
    double tp;
    if (loading)
    {
      const double pc = crushCurve(p, theta, &tp);
      theta_p_max = tp;
      // 1e-9: the crush root is solved to 1e-13 p_l; theta accumulates round-off per step
      EXPECT_LT(relErr(mp.pressure(), pc, 1e6), 1e-9) << "step " << n;
      EXPECT_NEAR(mp.history[kGeoHistThetaP], tp, 1e-11) << "step " << n;
    }
    else
    {
      // elastic unloading with the stiffened modulus, from the plastic strain reached
      const double K = theta_p_max >= p.model_params[kGeoThetaLock] ? p.model_params[kGeoKs] : 0;
      EXPECT_EQ(K, p.model_params[kGeoKs]); // the path went past lock
      EXPECT_LT(relErr(mp.pressure(), K * (theta - theta_p_max), 1e6), 1e-9) << "step " << n;
    }
    // the deviator sits on the yield surface whenever it yields (compaction hardening h)
    const double y = yieldSurface(p, mp.pressure(), 0, mp.history[kGeoHistThetaP]);
    EXPECT_LE(mp.mises(), y * (1 + 1e-10));
    if (mp.mises() > y * (1 - 1e-6))
      ++plastic;
  }
  EXPECT_GT(plastic, 100);
  EXPECT_EQ(mp.history[kGeoHistDamage], 0.0); // no dilatancy, no damage
  // sound speed of the locked solid: sqrt((Ks + 4G/3)/rho)
  EXPECT_LT(relErr(mp.c, std::sqrt((85e9 + 4.0 / 3.0 * 14.86e9) / mp.rho)), 1e-12);
}

// Triaxial compression: hydrostatic to sigma_c, then axial strain with the lateral stress held
// at -sigma_c by solving for the lateral strain rate each step (secant on copies). Calls
// `check` after every step; returns the final point.
MaterialPoint triaxial(const MaterialParams &p, double sigma_c, int steps,
                       const std::function<void(const MaterialPoint &)> &check)
{
  MaterialPoint mp(p);
  const double dt = 1e-7;
  const int nh = 20;
  const double th = sigma_c / (3 * p.bulk) / nh / dt;
  const Real hyd[6] = {-th, -th, -th, 0, 0, 0};
  for (int n = 0; n < nh; ++n)
    mp.step(hyd, dt);
  const double a = 2e-5 / dt; // axial strain 2e-5 per step
  // elastic lateral-stress sensitivity d sigma_yy / dx = (2 lambda + 2 G) dt seeds the secant
  const double lambda = p.bulk - 2.0 / 3.0 * p.shear, slope = (2 * lambda + 2 * p.shear) * dt;
  double x_prev = 0.25 * a; // Poisson ratio of the limestone
  for (int n = 0; n < steps; ++n)
  {
    auto lateral = [&](double x) {
      MaterialPoint t = mp;
      const Real D[6] = {-a, x, x, 0, 0, 0};
      t.step(D, dt);
      return std::make_pair(t.stress[1] + sigma_c, t);
    };
    double x0 = x_prev;
    auto r0 = lateral(x0);
    double x1 = x0 - r0.first / slope;
    auto r1 = lateral(x1);
    for (int it = 0; it < 60 && std::fabs(r1.first) > 1e-6 * (sigma_c + 1e6); ++it)
    {
      const double x2 = x1 - r1.first * (x1 - x0) / (r1.first - r0.first);
      x0 = x1, r0 = r1, x1 = x2, r1 = lateral(x1);
    }
    mp = r1.second;
    x_prev = x1;
    check(mp);
  }
  return mp;
}

TEST(Geomaterial, TriaxialStrengthPointsOnYieldSurface)
{
  MaterialSpec s = limestone();
  s.values["dilatancy"] = 0; // no damage: perfectly plastic on the intact surface
  const MaterialParams p =
      without(s, {"porosity", "crush_pressure", "lock_pressure", "solid_bulk_modulus"});
  for (double sc : {0.0, 10e6, 50e6, 150e6})
  {
    // the strength point: q = Y(sigma_c + q/3) (triaxial compression, p = sigma_c + q/3)
    double lo = 0, hi = 2e9;
    for (int i = 0; i < 200; ++i)
    {
      const double q = 0.5 * (lo + hi);
      (q < yieldSurface(p, sc + q / 3, 0, 0) ? lo : hi) = q;
    }
    const double q_star = 0.5 * (lo + hi);
    const MaterialPoint end = triaxial(p, sc, 1000, [&](const MaterialPoint &mp) {
      EXPECT_LE(mp.mises(), yieldSurface(p, mp.pressure(), 0, 0) * (1 + 1e-10));
    });
    // lateral stress is held to 1e-6 (sigma_c + 1 MPa), which bounds the error in p
    EXPECT_LT(relErr(end.mises(), q_star), 1e-5) << "sigma_c = " << sc;
    EXPECT_LT(relErr(end.pressure(), sc + q_star / 3), 1e-5) << "sigma_c = " << sc;
  }
}

TEST(Geomaterial, BrittleSofteningByDilatancyToDamagedSurface)
{
  const MaterialParams p =
      without(limestone(), {"porosity", "crush_pressure", "lock_pressure", "solid_bulk_modulus"});
  const double sc = 20e6;
  double q_peak = 0, d_prev = 0;
  bool monotone = true;
  const MaterialPoint end = triaxial(p, sc, 12000, [&](const MaterialPoint &mp) {
    q_peak = std::max(q_peak, mp.mises());
    const double D = mp.history[kGeoHistDamage];
    monotone = monotone && D >= d_prev;
    d_prev = D;
    EXPECT_LE(mp.mises(),
              yieldSurface(p, mp.pressure(), D, mp.history[kGeoHistThetaP]) * (1 + 1e-10));
    EXPECT_DOUBLE_EQ(mp.history[kGeoHistTensile], 8e6 * (1 - D));
  });
  double lo = 0, hi = 2e9;
  for (int i = 0; i < 200; ++i)
  {
    const double q = 0.5 * (lo + hi);
    (q < yieldSurface(p, sc + q / 3, 0, 0) ? lo : hi) = q;
  }
  // the peak is the intact strength point (one step of softening later at most)
  EXPECT_LT(relErr(q_peak, 0.5 * (lo + hi)), 1e-3);
  EXPECT_TRUE(monotone);
  EXPECT_EQ(end.history[kGeoHistDamage], 1.0);
  EXPECT_EQ(end.history[kGeoHistTensile], 0.0);
  // residual: the damaged (rubble) surface q = mu_d (sigma_c + q/3)
  const double q_res = 1.2 * sc / (1 - 1.2 / 3);
  EXPECT_LT(relErr(end.mises(), q_res), 1e-5);
  EXPECT_LT(end.mises(), 0.5 * q_peak);
}

TEST(Geomaterial, TensileSofteningToZeroAndCrackClosure)
{
  const MaterialParams p =
      without(limestone(), {"porosity", "crush_pressure", "lock_pressure", "solid_bulk_modulus"});
  const double K = p.bulk, t0 = 8e6, ed = 0.01;
  MaterialPoint mp(p);
  EXPECT_EQ(mp.history[kGeoHistTensile], t0);
  const Real dt = 1e-7, r = 1e2; // isotropic: no deviator, the cut-off acts alone
  const Real expand[6] = {r, r, r, 0, 0, 0}, squeeze[6] = {-r, -r, -r, 0, 0, 0};
  double theta_min = 0;
  for (int n = 0; n < 500; ++n) // theta to -0.015
  {
    mp.step(expand, dt);
    const double theta = std::log(mp.rho / p.density);
    theta_min = theta;
    double P, D;
    if (theta >= -t0 / K)
      P = K * theta, D = 0;
    else
    {
      // -T0 (1 - td/ed) = K (theta + td)  =>  td = (-T0 - K theta) / (K - T0/ed)
      const double td = (-t0 - K * theta) / (K - t0 / ed);
      D = std::min(1.0, td / ed);
      P = -t0 * (1 - D);
    }
    EXPECT_NEAR(mp.pressure(), P, 1e-9 * t0) << "step " << n;
    EXPECT_NEAR(mp.history[kGeoHistDamage], D, 1e-9) << "step " << n;
    EXPECT_NEAR(mp.history[kGeoHistTensile], t0 * (1 - D), 1e-9 * t0);
  }
  EXPECT_EQ(mp.history[kGeoHistDamage], 1.0);
  EXPECT_EQ(mp.history[kGeoHistTensile], 0.0);
  EXPECT_EQ(mp.pressure(), 0.0);
  // recompression: the cracks close at no pressure until the original volume is back, then
  // the rock is elastic again (with no tensile strength left)
  for (int n = 0; n < 700; ++n)
  {
    mp.step(squeeze, dt);
    const double theta = std::log(mp.rho / p.density);
    EXPECT_NEAR(mp.pressure(), theta <= 0 ? 0.0 : K * theta, 1e-9 * t0) << "step " << n;
  }
  EXPECT_GT(std::log(mp.rho / p.density), 0.003);
  EXPECT_LT(theta_min, -0.0149);
}

TEST(Geomaterial, CrackBandDissipatesTheFractureEnergyAtAnyElementLength)
{
  // isotropic opening to full damage: the work per unit volume is the softening triangle,
  // T0 eps_t / 2 = G_f / L, so W L = G_f for every L; the damage is the opening over eps_t
  MaterialSpec spec = limestone();
  for (const char *k : {"porosity", "crush_pressure", "lock_pressure", "solid_bulk_modulus"})
    spec.values.erase(k);
  const double gf = 100.0;
  spec.values["fracture_energy"] = gf;
  const MaterialParams p = makeMaterialParams(spec);
  const double K = p.bulk, t0 = 8e6;
  const Real dt = 1e-7, r = 1e2, expand[6] = {r, r, r, 0, 0, 0};
  for (const double L : {1e-3, 4e-3})
  {
    const double eps_t = 2 * gf / (t0 * L);
    MaterialPoint mp(p);
    mp.length = L;
    double work = 0; // per unit current volume (the log strain's measure): rho times it per mass
    int n = 0;
    while (mp.history[kGeoHistDamage] < 1 && n < 100000)
    {
      const double rho_old = mp.rho;
      mp.step(expand, dt);
      work += 0.5 * (rho_old + mp.rho) * mp.last_work;
      ++n;
      const double strain = -std::log(mp.rho / p.density);
      if (strain > t0 / K && mp.history[kGeoHistDamage] < 1)
      {
        const double opening = (strain - t0 / K) / (1 - t0 / (K * eps_t));
        EXPECT_NEAR(mp.history[kGeoHistDamage], opening / eps_t, 1e-9) << "L " << L;
      }
    }
    ASSERT_EQ(mp.history[kGeoHistDamage], 1.0) << "L " << L;
    EXPECT_EQ(mp.pressure(), 0.0);
    // the last step overshoots full damage by at most one strain increment 3 r dt at T -> 0,
    // and the trapezoidal work errs by T0 (3 r dt) / 2 at the peak: 1e-3 of G_f / L here
    EXPECT_NEAR(work * L, gf, 2e-3 * gf) << "L " << L << ", " << n << " steps";
  }
}

TEST(Geomaterial, EnergyIsTrapezoidalStressWork)
{
  const MaterialParams p = makeMaterialParams(concrete());
  MaterialPoint mp(p);
  Real work = 0;
  for (int n = 0; n < 1500; ++n)
  {
    const Real r = n < 600 ? -800.0 : 600.0; // crush and shear, then open to full damage
    const Real D[6] = {r, 0.2 * r, -0.1 * r, 0.3 * r, 0, 0.1 * r};
    mp.step(D, 1e-7, n % 4 == 0 ? 2e5 : 0.0);
    work += mp.last_work;
  }
  EXPECT_GT(mp.history[kGeoHistThetaC], 0.0);
  EXPECT_EQ(mp.history[kGeoHistDamage], 1.0);
  EXPECT_LT(relErr(mp.e, work), 1e-10);
}

} // namespace
} // namespace scpdyn::test
