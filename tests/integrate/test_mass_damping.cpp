// The settling stage's damped kick (integrate/MassDamping.hpp, docs/theory.md 2.4): its
// impulse is what it takes off the undamped kick, coefficient 0 is the undamped kick bit for
// bit, a free oscillator decays as exp(-alpha t / 2) whatever its frequency, and every step is
// stable however large alpha dt.
#include "integrate/MassDamping.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace scpdyn
{
namespace
{

TEST(MassDamping, TheImpulseIsWhatTheDampingTakesOffTheKick)
{
  const Real m = 2.5, dt = 1e-3, force = 40, v_old = 3;
  for (const Real alpha : {0.0, 10.0, 1e3, 1e6})
  {
    const MassDamping d = massDamping(alpha, dt);
    const Real v_new = d.velocity(v_old, dt * force / m);
    EXPECT_NEAR(m * (v_new - v_old) - dt * force, d.impulse(m, v_old, v_new),
                1e-12 * (m * std::fabs(v_old) + dt * force))
        << "alpha " << alpha;
    EXPECT_LE(std::fabs(d.keep), 1) << "alpha " << alpha;
  }
  const MassDamping none = massDamping(0, dt);
  EXPECT_EQ(none.velocity(v_old, 0.37), v_old + 0.37);
  EXPECT_EQ(none.impulse(m, v_old, 4), 0);
}

TEST(MassDamping, AnOscillatorDecaysAtHalfTheCoefficientWhateverItsFrequency)
{
  // x'' = -w^2 x - alpha x', leapfrog with the damped kick: Q = v^2 + alpha x v + w^2 x^2
  // decays exactly as exp(-alpha t) in the ODE, so sqrt(Q) / w, the amplitude, as
  // exp(-alpha t / 2), here to O((w dt)^2)
  const Real alpha = 20, T = 0.5;
  for (const Real w : {200.0, 2000.0})
  {
    const Real dt = 0.01 / w;
    const MassDamping d = massDamping(alpha, dt);
    Real x = 1, v = 0;
    const long steps = long(T / dt);
    for (long n = 0; n < steps; ++n)
    {
      const Real xh = x + 0.5 * dt * v;
      const Real v_new = d.velocity(v, -w * w * xh * dt);
      x += 0.5 * dt * (v + v_new);
      v = v_new;
    }
    const Real amplitude = std::sqrt(v * v + alpha * x * v + w * w * x * x) / w;
    EXPECT_NEAR(amplitude / std::exp(-alpha * steps * dt / 2), 1, 2e-3) << "w " << w;
  }
}

} // namespace
} // namespace scpdyn
