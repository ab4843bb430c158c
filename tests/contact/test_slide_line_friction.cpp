// Coulomb friction of the slide lines (ContactFriction.cpp, docs/theory.md 11.1): a 0.2 x 0.1 m
// block (4 x 2 quads) on a fixed base, gravity tilted by theta so the interface is the incline.
// A rigid block slides with a = g (sin(theta) - mu cos(theta)) once tan(theta) > mu and stays
// put otherwise. The block is soft (c = 100 m/s) so 0.12 s takes 530 cycles; gravity applied at
// once sets it vibrating, which swings its centre of mass by about 1e-4 m/s.
#include "ContactTestUtil.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace scpdyn;
using namespace scpdyn::test;

namespace
{

constexpr Real kG = 9.81, kBlockMass = 1000 * 0.2 * 0.1; // [m/s^2], [kg per m]

std::string slideLineIncline(Real theta_deg, const std::string &friction, Real v0 = 0)
{
  return test::inclineDeck(theta_deg,
                           "    - {name: base, part: base, option: slide_line, " + friction +
                               "}\n    - {name: block, part: block, option: slide_line, " +
                               friction + "}\n",
                           v0);
}

struct Slide
{
  Real v_end = 0, t_end = 0; ///< the block's mean x-velocity at the end [m/s], the time [s]
  Real x = 0;                ///< its centre's displacement along the incline [m]
  Real x_half = 0;           ///< the same at half the run
};

Slide run(const std::string &deck)
{
  Solver s(deckFromText(deck, "incline"));
  Slide r;
  while (s.time() < s.deck().end_time)
  {
    const Real t0 = s.time();
    s.cycle();
    r.x += s.energies().momentum[0] / kBlockMass * (s.time() - t0);
    if (s.time() <= 0.5 * s.deck().end_time)
      r.x_half = r.x;
  }
  r.v_end = s.energies().momentum[0] / kBlockMass; // the base is held at rest
  r.t_end = s.time();
  return r;
}

} // namespace

TEST(SlideLineFriction, SlidesWithCoulombAccelerationAboveTheFrictionAngle)
{
  const Real th = 30 * M_PI / 180, mu = 0.3;
  const Slide r = run(slideLineIncline(30, "mu_static: 0.3"));
  const Real a = r.v_end / r.t_end, exact = kG * (std::sin(th) - mu * std::cos(th));
  std::printf("[incline 30 deg, mu 0.3] a = %.5f m/s^2, g(sin - mu cos) = %.5f (%+.2e)\n", a, exact,
              a / exact - 1);
  EXPECT_NEAR(a / exact, 1.0, 0.01);
}

TEST(SlideLineFriction, SticksBelowTheFrictionAngle)
{
  // tan(20 deg) = 0.364 < mu = 0.5: no slide. Frictionless it would slide g sin(theta) t^2 / 2 =
  // 24 mm. Loaded at once, the block shifts by 3e-5 m while it settles in its first cycles
  // (bound: 2e-3 of the frictionless slide), then holds: no creep over the second half (2e-4)
  const Real th = 20 * M_PI / 180;
  const Slide r = run(slideLineIncline(20, "mu_static: 0.5"));
  const Real frictionless = 0.5 * kG * std::sin(th) * r.t_end * r.t_end;
  std::printf("[incline 20 deg, mu 0.5] displacement %.3e m, %.3e m at half time (frictionless "
              "%.3e), v at the end %.2e m/s\n",
              r.x, r.x_half, frictionless, r.v_end);
  EXPECT_LT(std::abs(r.x), 2e-3 * frictionless);
  EXPECT_LT(std::abs(r.x - r.x_half), 2e-4 * frictionless);
}

TEST(SlideLineFriction, KineticCoefficientRulesOnceSliding)
{
  // mu_static 0.7 > tan(25 deg) = 0.466: at rest the block holds (the decay sees the vibration,
  // |v| ~ 1e-3 m/s: mu stays above 0.69); thrown at 1 m/s, mu = 0.3 + 0.4 exp(-10 |v|) is within
  // 2e-5 of mu_kinetic 0.3, and the block accelerates at the kinetic rate
  const Real th = 25 * M_PI / 180;
  const std::string friction = "mu_static: 0.7, mu_kinetic: 0.3, mu_decay: 10";
  const Slide rest = run(slideLineIncline(25, friction));
  const Slide thrown = run(slideLineIncline(25, friction, 1.0));
  const Real a = (thrown.v_end - 1.0) / thrown.t_end;
  const Real exact = kG * (std::sin(th) - 0.3 * std::cos(th));
  std::printf("[incline 25 deg, mu 0.7 -> 0.3] at rest: displacement %.3e m (%.3e m at half "
              "time); thrown: a = %.5f "
              "m/s^2 (kinetic %.5f, %+.2e)\n",
              rest.x, rest.x_half, a, exact, a / exact - 1);
  const Real frictionless = 0.5 * kG * std::sin(th) * rest.t_end * rest.t_end;
  EXPECT_LT(std::abs(rest.x), 2e-3 * frictionless);
  EXPECT_LT(std::abs(rest.x - rest.x_half), 2e-4 * frictionless);
  EXPECT_NEAR(a / exact, 1.0, 0.01);
}
