// Normal joint law, energy, implicit update and explicit time step (docs/theory.md 6.1, 6.2, 6.5,
// 6.6, 6.7, 7, 9, 10). Reference numbers come from the Python prototypes in
// shared/docs/scp-ref (run with /usr/bin/python3); each test names the script and arguments.
#include "contact/JointConstraints.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace scpdyn;

namespace
{
const Real kInf = std::numeric_limits<Real>::infinity();
const Real kZ[3] = {0, 0, 1};

JointParams normalParams(Real a, Real E0, Real C = 0, Real phi0_deg = 40)
{
  JointParams p;
  p.a = a, p.E0 = E0, p.C = C, p.phi0 = phi0_deg * M_PI / 180, p.psi0 = 0;
  return resolveParams(p);
}
CpKinematics kin(Real Vn, Real Ac, Real dt, Real mstar = kInf, Real Fint_n = 0)
{
  CpKinematics k;
  for (int d = 0; d < 3; ++d)
    k.n[d] = kZ[d], k.Vs[d] = 0, k.Fint_s[d] = 0;
  k.Vn = Vn, k.Ac = Ac, k.dt = dt, k.mstar = mstar, k.Fint_n = Fint_n;
  return k;
}
// closed CP on the virgin curve at closure u
CpState onCurve(const JointParams &p, Real u, Real Ac)
{
  CpState s = initialCpState(u, kZ, Ac);
  s.Fn = jointLoadingStress(p, u) * Ac;
  return s;
}
Real rel(Real a, Real b) { return std::fabs(a - b) / std::fabs(b); }
} // namespace

// 6.1/6.2 table (worked_examples.py, no arguments): sigma(0.05 mm) = 50 MPa, E = 0.2 GPa;
// sigma(0.09 mm) = 450 MPa, E = 5 GPa; E = Emax = 500 GPa from u_cap = 0.99 a. 1e-12: closed forms.
TEST(JointNormal, LoadingCurveAndModulus)
{
  const JointParams p = resolveParams(JointParams{});
  EXPECT_DOUBLE_EQ(p.Emax, 5e11);
  EXPECT_NEAR(p.sigma_t, 1191753.59259421, 1e-6); // worked_examples.py: T = C/tan(phi0)
  EXPECT_NEAR(jointCapClosure(p), 0.99e-4, 1e-18);
  EXPECT_DOUBLE_EQ(jointModulus(p, 0, 0), 5e7);
  EXPECT_LT(rel(jointLoadingStress(p, 0.5e-4), 5e7), 1e-12);
  EXPECT_LT(rel(jointModulus(p, 0.5e-4, 0.5e-4), 2e8), 1e-12);
  EXPECT_LT(rel(jointLoadingStress(p, 0.9e-4), 450000000.00000006), 1e-12);
  EXPECT_LT(rel(jointModulus(p, 0.9e-4, 0.9e-4), 5000000000.000003), 1e-12);
  EXPECT_LT(rel(jointModulus(p, 0.099e-3, 0), 5e11),
            1e-12); // cap reached (prototype: 499999999999.988)
  // unloading keeps the tangent at umax (tangent unloading)
  EXPECT_LT(rel(jointModulus(p, 0.1e-4, 0.5e-4), 2e8), 1e-12);
}

// Section 7 overestimation example (worked_examples.py): u = umax = 0.05 mm, Fn = 5 kN on
// 1 cm^2, Vn = 10 m/s, dt = 10 ns: explicit dF = 20.08024064160385 N > exact 20.040080160321295 N.
TEST(JointNormal, ExplicitStepOverestimates)
{
  const JointParams p = normalParams(1e-4, 5e7);
  CpState s = onCurve(p, 0.5e-4, 1e-4);
  const CpStepResult r = updateExplicit(p, s, kin(10, 1e-4, 1e-8));
  EXPECT_LT(rel(r.Fn - 5000, 20.08024064160385), 1e-9); // 5000 + 20: 1e-13 of Fn lost in -5000
  EXPECT_GT(r.Fn - 5000, 20.040080160321295);
  // energy (6.7): an explicit loading step dissipates exactly 0.5 Fn^2 (1/K - 1/K')
  const Real K = 2e8 * 1e-4 / 1e-4, K1 = jointModulus(p, s.u, s.umax) * 1e-4 / 1e-4;
  EXPECT_LT(rel(r.dD, 0.5 * 5000.0 * 5000.0 * (1 / K - 1 / K1)),
            1e-6); // dD = dW - dPsi: cancellation
  EXPECT_NEAR(r.dW, r.dPsi + r.dD, 1e-12 * r.dW);
}

// checks_normal.py (no arguments), part 1: 9000 explicit steps of du = 1e-8 m (Vn = 10 m/s,
// dt = 1 ns, Ac = 1 m^2) reach u/a = 0.9 with F = 450247583.24977386 N (+5.5e-4 above (2)).
// Same arithmetic as the prototype, so agreement to 1e-12 after 9000 additions.
TEST(JointNormal, ExplicitLoadingConvergesToLaw)
{
  const JointParams p = normalParams(1e-4, 5e7);
  CpState s = initialCpState(0, kZ, 1.0);
  for (int i = 0; i < 9000; ++i)
    updateExplicit(p, s, kin(10, 1.0, 1e-9));
  EXPECT_LT(rel(s.u, 8.999999999999219e-05), 1e-12);
  EXPECT_LT(rel(s.Fn, 450247583.24977386), 1e-12);
  EXPECT_LT(rel(s.Fn, 4.5e8), 6e-4);
  EXPECT_GT(s.Fn, 4.5e8);
}

// checks_normal.py part 2: the implicit update with m* -> infinity (c = 0) follows (2) to
// round-off at every step (each increment is an exact secant), and unloading reaches zero
// force at umax^2/a (8.1e-5 m) - the prototype prints 8.100000e-05.
TEST(JointNormal, ImplicitInfiniteMassIsTheLaw)
{
  const JointParams p = normalParams(1e-4, 5e7);
  CpState s = initialCpState(0, kZ, 1.0);
  Real worst = 0;
  for (int i = 0; i < 9000; ++i)
  {
    const CpStepResult r = updateImplicit(p, s, kin(10, 1.0, 1e-9));
    worst = std::max(worst, rel(r.Fn, jointLoadingStress(p, s.u)));
  }
  EXPECT_LT(worst, 1e-12);
  EXPECT_LT(rel(s.u / p.a, 0.9), 1e-12);
  EXPECT_LT(rel(s.Fn, 4.5e8), 1e-12);
  const Real umax = s.umax;
  int steps = 0;
  while (!s.open && steps < 20000)
    updateImplicit(p, s, kin(-10, 1.0, 1e-9)), ++steps;
  ASSERT_TRUE(s.open);
  EXPECT_LT(rel(s.u_z, umax * umax / p.a), 1e-10);
  std::printf("[ measured ] implicit c=0: max |F/F_law - 1| = %.2e over 9000 steps; u_z/(umax^2/a) "
              "- 1 = %.2e\n",
              worst, s.u_z / (umax * umax / p.a) - 1);
}

// T9/T11c hysteresis: load to sigma_max, unload to zero force; the dissipated energy per m^2 is
// a E0 [-ln(1 - s_m) - s_m - s_m^2/2] (verification.md T9: 0.0128 / 8.83 / 1049 / 8193 J/m^2 for
// 1 / 10 / 100 / 1000 MPa; exact values from that formula: python3 -c with math.log). Implicit
// c = 0 with 4000 loading steps: trapezoid error O(N^-2), measured <= 1.3e-6, 1e-5 allowed;
// explicit with 20000 steps: Riemann-sum error O(1/N), measured 6.6e-5, 5e-4 allowed
// (verification tolerance 2 %).
TEST(JointNormal, HysteresisEnergy)
{
  const JointParams p = normalParams(1e-4, 5e7); // C = 0: sigma_t = 0
  const Real sig[4] = {1e6, 1e7, 1e8, 1e9};
  for (int implicit = 1; implicit >= 0; --implicit)
    for (int c = 0; c < 4; ++c)
    {
      if (!implicit && c != 1)
        continue;
      const Real sm = sig[c] / (p.E0 + sig[c]);
      const Real exact = p.a * p.E0 * (-std::log(1 - sm) - sm - 0.5 * sm * sm);
      const int N = implicit ? 4000 : 20000;
      const Real dt = 1e-9, V = sm * p.a / N / dt;
      CpState s = initialCpState(0, kZ, 1.0);
      Real D = 0, W = 0;
      auto step = [&](Real Vn) {
        const CpStepResult r = implicit ? updateImplicit(p, s, kin(Vn, 1.0, dt))
                                        : updateExplicit(p, s, kin(Vn, 1.0, dt));
        D += r.dD, W += r.dW;
      };
      for (int i = 0; i < N; ++i)
        step(V);
      const Real umax = s.umax;
      int n = 0;
      while (!s.open && n < 4 * N)
        step(-V), ++n;
      ASSERT_TRUE(s.open);
      EXPECT_NEAR(W, D, 1e-9 * std::fabs(D)); // nothing stored once open
      EXPECT_LT(rel(D, exact), implicit ? 1e-5 : 5e-4) << sig[c];
      if (implicit)
      {
        EXPECT_LT(rel(s.u_z, umax * umax / p.a), 1e-9);
      }
      std::printf("[ measured ] %s hysteresis to %g MPa: D = %.6g J/m^2 (exact %.6g, rel %.1e), "
                  "residual closure %.4g um\n",
                  implicit ? "implicit" : "explicit", sig[c] / 1e6, D, exact, D / exact - 1,
                  s.u_z * 1e6);
    }
}

// Section 10.4 worked example (worked_examples.py): m* = 6.5e-5 kg, dt = 0.1 us, Vn = 10 m/s,
// u = umax = 0.05 mm, Fn = 5 kN on 1 cm^2: Fn' = 5044.971446983377 N, du = 2.2385054661794e-07 m.
// Slide-line limit (24): 6500 N.
TEST(JointNormal, ImplicitWorkedExample)
{
  const JointParams p = normalParams(1e-4, 5e7);
  CpState s = onCurve(p, 0.5e-4, 1e-4);
  const CpStepResult r = updateImplicit(p, s, kin(10, 1e-4, 1e-7, 6.5e-5));
  EXPECT_LT(rel(r.Fn, 5044.971446983377), 1e-12);
  EXPECT_LT(rel(s.u - 0.5e-4, 2.2385054661794225e-07), 1e-9); // difference of 5e-5 and u
  CpState t = onCurve(p, 0.5e-4, 1e-4);
  EXPECT_LT(rel(updateSlideLine(t, kin(10, 1e-4, 1e-7, 6.5e-5)).Fn, 6500.0), 1e-12);
}

// Section 10.5 stiff-limit check (checks_normal.py part 3): a = 1 nm, E0 = 5 GPa, no cap,
// m* = 2 kg, Vn = 100 m/s, dt = 0.1 us, Fint_n = 1 kN, fresh CP: quadratic 1999943858.2886162 N,
// slide line m* Vn/dt + Fint = 2.000001e9 N.
TEST(JointNormal, StiffLimitIsSlideLine)
{
  JointParams p = normalParams(1e-9, 5e9);
  p.Emax = 1e40;
  CpState s = initialCpState(0, kZ, 1.0);
  const CpStepResult r = updateImplicit(p, s, kin(100, 1.0, 1e-7, 2.0, 1e3));
  EXPECT_LT(rel(r.Fn, 1999943858.2886162), 1e-10);
  EXPECT_LT(s.u, p.a); // (22): the implicit closure never reaches the aperture
  CpState t = initialCpState(0, kZ, 1.0);
  const Real Fstop = updateSlideLine(t, kin(100, 1.0, 1e-7, 2.0, 1e3)).Fn;
  EXPECT_LT(rel(Fstop, 2.000001e9), 1e-12);
  EXPECT_LT(rel(r.Fn, Fstop), 3e-5);
}

// 10.6: corrected velocities v* with Fint = 0 equal v^n with Fint from (21) (same B and
// Fs_stick up to the rounding of Vn + dt Fint/m*): 1e-12 on a loading and slipping step.
TEST(JointNormal, VelocityCorrectionEqualsInternalForce)
{
  JointParams p = normalParams(1e-4, 5e7, 1e5, 30);
  p.psi0 = 5 * M_PI / 180;
  const Real m = 1e-3, dt = 1e-7, Ac = 1e-4;
  CpState a = onCurve(p, 0.3e-4, Ac), b = a;
  a.Fs[0] = b.Fs[0] = 1240; // cap C Ac + Fn tan 30 = 1247 N: the trial slips
  CpKinematics ka = kin(3.0, Ac, dt, m, 20.0), kb = kin(3.0 + dt * 20.0 / m, Ac, dt, m, 0);
  ka.Vs[0] = 5, ka.Fint_s[0] = -30;
  kb.Vs[0] = 5 + dt * (-30) / m;
  const CpStepResult ra = updateImplicit(p, a, ka), rb = updateImplicit(p, b, kb);
  EXPECT_EQ(ra.slipped, 1);
  EXPECT_LT(rel(ra.Fn, rb.Fn), 1e-12);
  EXPECT_LT(rel(ra.Fs[0], rb.Fs[0]), 1e-12);
  EXPECT_LT(rel(a.u, b.u), 1e-12);
}

// (19) numbers of section 9 (worked_examples.py): rho = 2600, h = 1 mm so mu* = 0.65 kg/m^2;
// C_safe = 1: 2.280350850198276 us (E0), 1.140175425099138 us (0.2 GPa), 0.22803508501982754 us
// (5 GPa); paper form a sqrt(rho/E0) = 0.7211102550927979 us. E_pred at u + Vn dt_el
// (python3 -c: u = 0.06 mm, E = 3.125e8 Pa): 0.9121403400793106 us.
TEST(JointNormal, ExplicitTimeStep)
{
  JointParams p = normalParams(1e-4, 5e7);
  p.C_safe = 1;
  const Real mu = arealReducedMass(1.3e-4, 1e-4, false, 1.3e-4, 1e-4, false);
  EXPECT_LT(rel(mu, 0.65), 1e-15);
  const Real us[3] = {0, 0.5e-4, 0.9e-4};
  const Real ref[3] = {2.280350850198276e-06, 1.140175425099138e-06, 2.2803508501982754e-07};
  for (int i = 0; i < 3; ++i)
  {
    CpState s = initialCpState(us[i], kZ, 1e-4);
    EXPECT_LT(rel(contactTimeStep(p, s, 0, 1e-7, mu, 2600), ref[i]), 1e-12);
  }
  CpState s = initialCpState(0.5e-4, kZ, 1e-4);
  EXPECT_LT(rel(contactTimeStep(p, s, 100, 1e-7, mu, 2600), 9.121403400793106e-07), 1e-12);
  EXPECT_LT(rel(contactTimeStep(p, s, -100, 1e-7, mu, 2600), 1.140175425099138e-06), 1e-12);
  p.dt_form = DtContactForm::Paper;
  CpState s0 = initialCpState(0, kZ, 1e-4);
  EXPECT_LT(rel(contactTimeStep(p, s0, 0, 1e-7, mu, 2600), 7.211102550927979e-07), 1e-12);
  p.C_safe = kInf;
  EXPECT_GE(contactTimeStep(p, s0, 0, 1e-7, mu, 2600), 1e300);
  // a rigid face: mu* = mu of the other face
  EXPECT_LT(rel(arealReducedMass(1.3e-4, 1e-4, false, 1.0, 1e-4, true), 1.3), 1e-15);
}

// T11g (law level) against the prototype: python3 -c "import sys; sys.path.insert(0,
// 'shared/docs/scp-ref'); from joint import *" driving P(a=1e-4, E0=5e7, C=C, phi0=40.0), S(),
// Ac = 1, dt = 1 ns: 100 steps Vn = +10, 200 steps Vn = -10, 200 steps Vn = +10, with
// explicit_normal / implicit_normal(m* = 1e30). Results (C = 0 | C = 1e5, sigma_t = 119175 Pa):
//   explicit: F(100) = 505101.2677278687, F(150) = 250025.25507609796, opens at step 200 | 223
//             with u_z = 9.90049499983306e-09, re-closes at 401 with F = 50.762677363025745,
//             F(500) = 505101.26772786875;
//   implicit: F(100) = 505050.505050505, F(150) = 249974.49239873426, opens at 199 | 223 with
//             u_z = 1.0000000000001388e-08, re-closes at 402 with F = 5101.520253034728,
//             F(500) = 505050.50505050505.
// Opening at 199/200 for C = 0 is the round-off of F crossing zero exactly at u = u_z, so either
// is accepted there. Forces: 1e-9 relative (a few hundred incremental additions).
TEST(JointNormal, TensionCutoffAndReclosing)
{
  for (int implicit = 0; implicit < 2; ++implicit)
    for (int withC = 0; withC < 2; ++withC)
    {
      const JointParams p = normalParams(1e-4, 5e7, withC ? 1e5 : 0.0, 40);
      const Real T = p.sigma_t;
      CpState s = initialCpState(0, kZ, 1.0);
      int step = 0, open_step = -1, close_step = -1;
      Real F100 = 0, F150 = 0, F500 = 0, Fclose = 0, Fmin = 0, uz = 0;
      const Real V[3] = {10, -10, 10};
      const int n[3] = {100, 200, 200};
      for (int ph = 0; ph < 3; ++ph)
        for (int i = 0; i < n[ph]; ++i)
        {
          const int was_open = s.open;
          const CpStepResult r = implicit ? updateImplicit(p, s, kin(V[ph], 1.0, 1e-9, 1e30))
                                          : updateExplicit(p, s, kin(V[ph], 1.0, 1e-9));
          ++step;
          Fmin = std::min(Fmin, r.Fn);
          if (!was_open && s.open)
            open_step = step, uz = s.u_z;
          if (was_open && !s.open)
            close_step = step, Fclose = r.Fn;
          if (step == 100)
            F100 = r.Fn;
          if (step == 150)
            F150 = r.Fn;
          if (step == 500)
            F500 = r.Fn;
        }
      EXPECT_GE(Fmin, -T * (1 + 1e-12)); // never beyond the tensile strength
      if (!withC)
      {
        EXPECT_GE(Fmin, 0.0); // C = 0: no tension at all
      }
      if (!implicit)
      {
        EXPECT_LT(rel(F100, 505101.2677278687), 1e-9);
        EXPECT_LT(rel(F150, 250025.25507609796), 1e-9);
        EXPECT_LT(rel(uz, 9.90049499983306e-09), 1e-6);
        EXPECT_EQ(close_step, 401);
        EXPECT_LT(rel(Fclose, 50.762677363025745), 1e-6); // K*(u - u_z) on a 1e-10 m difference
        EXPECT_LT(rel(F500, 505101.26772786875), 1e-9);
      }
      else
      {
        EXPECT_LT(rel(F100, 505050.505050505), 1e-9);
        EXPECT_LT(rel(F150, 249974.49239873426), 1e-9);
        EXPECT_LT(rel(uz, 1.0000000000001388e-08), 1e-9);
        EXPECT_EQ(close_step, 402);
        EXPECT_LT(rel(Fclose, 5101.520253034728), 1e-6);
        EXPECT_LT(rel(F500, 505050.50505050505), 1e-9);
      }
      if (withC)
        EXPECT_EQ(open_step, 223);
      else
        EXPECT_TRUE(open_step == 199 || open_step == 200) << open_step;
    }
}

// D12 new CPs and 6.6 traction history. A gap starts open and takes force only after closing
// past u_z = 0; an overlap is forgiven (zero force at u0). Halving Ac halves the stored forces
// and books -Psi/2 as dW_area.
TEST(JointNormal, NewCpAndTractionHistory)
{
  const JointParams p = normalParams(1e-4, 5e7);
  CpState s = initialCpState(-1e-6, kZ, 1.0);
  EXPECT_TRUE(s.open);
  for (int i = 0; i < 99; ++i)
    EXPECT_EQ(updateExplicit(p, s, kin(10, 1.0, 1e-9)).Fn, 0.0); // u = -1e-8 after 99 steps
  updateExplicit(p, s, kin(10, 1.0, 1e-9));
  updateExplicit(p, s, kin(10, 1.0, 1e-9));
  EXPECT_FALSE(s.open);
  EXPECT_NEAR(s.Fn, 5e11 * 1e-8 / (1 - 1e-4) / (1 - 1e-4), 1e-3); // K(u'=1e-8)*(u' - 0)
  CpState t = initialCpState(2e-6, kZ, 1.0);
  EXPECT_FALSE(t.open);
  EXPECT_EQ(t.umax, 2e-6);
  EXPECT_EQ(updateExplicit(p, t, kin(0, 1.0, 1e-9)).Fn, 0.0);

  CpState a = onCurve(p, 0.5e-4, 1.0), b = a;
  const Real Psi = storedEnergy(p, a.Fn, a.Fs, a.umax, 1.0);
  const CpStepResult ra = updateExplicit(p, a, kin(0, 0.5, 1e-9));
  EXPECT_LT(rel(ra.Fn, 0.5 * 5e7), 1e-12);
  EXPECT_LT(rel(ra.dW_area, -0.5 * Psi), 1e-12);
  JointParams q = p;
  q.traction_history = false;
  EXPECT_LT(rel(updateExplicit(q, b, kin(0, 0.5, 1e-9)).Fn, 5e7), 1e-12);
}

// 6.7 on an opening step with tension: the joint returns its elastic energy down to the
// strength and the drop dissipates exactly T^2/(2 K_line); dD >= 0 even for one huge step.
TEST(JointNormal, OpeningEnergy)
{
  const JointParams p = normalParams(1e-4, 5e7, 1e5, 40);
  for (int implicit = 0; implicit < 2; ++implicit)
  {
    CpState s = onCurve(p, 1e-6, 1.0);
    const Real K = lineStiffness(p, s.umax, 1.0), T = p.sigma_t;
    const CpStepResult r = implicit ? updateImplicit(p, s, kin(-1e3, 1.0, 1e-8, 1e30))
                                    : updateExplicit(p, s, kin(-1e3, 1.0, 1e-8));
    EXPECT_EQ(r.opened, 1);
    EXPECT_EQ(r.Fn, 0.0);
    EXPECT_LT(rel(r.dD, 0.5 * T * T / K), 1e-9);
  }
}

// (20) on every branch of 10.4: the end-of-step force and closure satisfy du = B - c Fn' (the
// equation of relative motion) to round-off, and a CP that starts on the virgin curve ends on it
// when it loads (line, hyperbola (22)-(23), capped line beyond u_cap, re-closing from open).
// 1e-12 relative to the step sizes: a handful of operations on O(B) numbers.
TEST(JointNormal, ImplicitSatisfiesEquationOfMotion)
{
  const JointParams p = normalParams(1e-4, 5e7);
  const Real Ac = 1e-4, dt = 1e-7, ucap = jointCapClosure(p);
  const Real masses[3] = {1e-5, 1e-3, 1e30};
  const Real speeds[5] = {-5, 1, 10, 100, 1000};
  int branches_cap = 0, branches_reclose = 0;
  for (Real m : masses)
    for (Real V : speeds)
      for (int start = 0; start < 4; ++start)
      {
        // 0: on the curve at a/2; 1: just below u_cap; 2: unloaded below umax; 3: open
        CpState s = onCurve(p, start == 1 ? 0.985e-4 : 0.5e-4, Ac);
        if (start == 2)
          s.u -= 1e-6, s.Fn -= lineStiffness(p, s.umax, Ac) * 1e-6;
        if (start == 3)
          s.open = 1, s.u_z = 1e-5, s.u = 0.95e-5, s.Fn = 0;
        const Real u0 = s.u, c = dt * dt / m, B = V * dt;
        const bool was_open = s.open;
        const CpStepResult r = updateImplicit(p, s, kin(V, Ac, dt, m));
        if (r.opened || s.open)
          continue;
        const Real du = s.u - u0;
        EXPECT_NEAR(du, B - c * r.Fn, 1e-12 * std::max(std::fabs(B), 1e-9))
            << m << " " << V << " " << start;
        if (s.u > ucap)
          ++branches_cap;
        if (was_open)
          ++branches_reclose;
        if (start < 2 && du > 0)
        {
          EXPECT_LT(rel(r.Fn, jointLoadingStress(p, s.u) * Ac), 1e-9)
              << m << " " << V << " " << start;
        }
      }
  EXPECT_GT(branches_cap, 0);
  EXPECT_GT(branches_reclose, 0);

  // 3.4 inactive CP: only u and n_old move
  CpState s = onCurve(p, 0.5e-4, Ac);
  const Real n[3] = {0, 1, 0};
  updateInactiveCp(s, n, -2.0, 1e-7);
  EXPECT_NEAR(s.u, 0.5e-4 - 2e-7, 1e-20);
  EXPECT_EQ(s.n_old[1], 1.0);
  EXPECT_EQ(s.Fn, 5e7 * Ac);
}
