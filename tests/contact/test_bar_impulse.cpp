// The first impulse of a slender steel bar striking a fixed, unjointed wall at an angle
// (docs/theory.md 14.6): the wall pushes on the bar's end only, along the wall's normal, so the
// bar's change of linear momentum is J n and the spin it takes about its centroid r x J n,
// whatever the bar's waves do: the part of the rigid-body relation that holds for an elastic
// bar. (The restitution form needs the bar to have left the wall; this slender bar chatters on
// it for 8 ms, so the check is taken 1 ms into the impulse, before the bar has turned.)
#include "ContactTestUtil.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace scpdyn;
using namespace scpdyn::test;

namespace
{

// The deck inputs/examples/bar_oblique_fixed_wall.yaml: a bar L = 2 m of square section
// b = 0.03 m (50 x 1 x 1 hex8), elastic steel, its axis at beta = 30 deg to the wall normal +x
// (60 deg to the wall), moving along its axis at 10 m/s, its leading edge 1 mm from the wall;
// the wall 0.1 m thick, every node held; frictionless slide lines. The end face's size bounds
// where on it the load may act: a lever-arm error of at most
// (b/2) cos(beta) / ((L/2) sin(beta)) = 2.6 %, within the 3 % the check allows.
constexpr double kL = 2.0, kB = 0.03, kBeta = 30.0 * M_PI / 180, kSpeed = 10.0;
constexpr double kMass = 7850 * kL * kB * kB; ///< the bar's mass [kg]

std::string barDeck()
{
  return readText(std::string(SCPDYN_SOURCE_DIR) + "/inputs/examples/bar_oblique_fixed_wall.yaml");
}

/// The bar's mass, momentum, centroid and angular momentum about it (host copy; the bar's
/// nodes are those that start in front of the wall, x > 0).
struct BarState
{
  double m = 0, p[3] = {0, 0, 0}, g[3] = {0, 0, 0}, h[3] = {0, 0, 0};
};

BarState barState(const Solver &s)
{
  auto x0 = Kokkos::create_mirror_view_and_copy(HostSpace(), s.nodes().x0);
  auto x = Kokkos::create_mirror_view_and_copy(HostSpace(), s.nodes().x);
  auto v = Kokkos::create_mirror_view_and_copy(HostSpace(), s.nodes().v);
  auto mass = Kokkos::create_mirror_view_and_copy(HostSpace(), s.nodes().mass);
  BarState b;
  for (Index n = 0; n < s.nodes().count; ++n)
    if (x0(n, 0) > 0)
    {
      b.m += mass(n);
      for (int d = 0; d < 3; ++d)
      {
        b.p[d] += mass(n) * v(n, d);
        b.g[d] += mass(n) * x(n, d);
      }
    }
  for (int d = 0; d < 3; ++d)
    b.g[d] /= b.m;
  for (Index n = 0; n < s.nodes().count; ++n)
    if (x0(n, 0) > 0)
    {
      const double r[3] = {x(n, 0) - b.g[0], x(n, 1) - b.g[1], x(n, 2) - b.g[2]};
      b.h[0] += mass(n) * (r[1] * v(n, 2) - r[2] * v(n, 1));
      b.h[1] += mass(n) * (r[2] * v(n, 0) - r[0] * v(n, 2));
      b.h[2] += mass(n) * (r[0] * v(n, 1) - r[1] * v(n, 0));
    }
  return b;
}

struct Impulse
{
  double jn = 0;            ///< normal impulse J (wall normal +x) [N s]
  double jt = 0;            ///< tangential impulse, |dp - J n| [N s]
  double lever = 0;         ///< |dH| / J: the measured lever arm about the centroid [m]
  double h_off_axis = 0;    ///< |dH| off the wall's z axis, over |dH|
  double ke_ratio = 0;      ///< the bar's energy (kinetic + internal) at the end over at the start
  double first_contact = 0; ///< time the bar's momentum first changed [s]
};

Impulse strike(const std::string &name)
{
  Solver s(deckFromText(barDeck(), name), MPI_COMM_SELF);
  const BarState b0 = barState(s);
  const EnergyReport e0 = s.energies();
  Impulse r;
  while (s.time() < s.deck().end_time)
  {
    s.cycle();
    if (r.first_contact == 0)
    {
      const BarState b = barState(s);
      if (std::fabs(b.p[0] - b0.p[0]) > 1e-9 * std::fabs(b0.p[0]))
        r.first_contact = s.time();
    }
  }
  const BarState b1 = barState(s);
  const EnergyReport e1 = s.energies();
  const double dp[3] = {b1.p[0] - b0.p[0], b1.p[1] - b0.p[1], b1.p[2] - b0.p[2]};
  r.jn = dp[0];
  r.jt = std::hypot(dp[1], dp[2]);
  const double dh = std::sqrt(b1.h[0] * b1.h[0] + b1.h[1] * b1.h[1] + b1.h[2] * b1.h[2]);
  r.lever = dh / r.jn;
  r.h_off_axis = std::hypot(b1.h[0], b1.h[1]) / dh;
  const double arm = 0.5 * kL * std::sin(kBeta); // (L/2) sin(beta)
  r.ke_ratio = (e1.kinetic + e1.internal) / (e0.kinetic + e0.internal);
  std::printf("[bar impulse] %s: first contact %.4e s, J %.4f N s (m v_n %.4f), tangential "
              "%.3e of J, lever arm %.5f m ((L/2) sin beta %.5f, %.3e off), dH off the z axis "
              "%.2e, energy after/before %.6f\n",
              name.c_str(), r.first_contact, r.jn, b0.m * std::fabs(b0.p[0] / b0.m), r.jt / r.jn,
              r.lever, arm, r.lever / arm - 1, r.h_off_axis, r.ke_ratio);
  return r;
}

} // namespace

TEST(BarImpulse, ASlenderBarStrikingAFixedWallAtSixtyDegreesTakesItsImpulseAlongTheWallNormal)
{
  const Impulse r = strike("bar_impulse");
  ASSERT_GT(r.first_contact, 0) << "the bar never touched the wall";
  // a real impulse: the end has stopped a good part of the bar's normal momentum
  EXPECT_GT(r.jn, 0.1 * kMass * kSpeed * std::cos(kBeta));
  // a frictionless wall pushes along its normal (the bisector of the end face's and the wall's
  // normals, 15 degrees off, gave 28 % of J along the wall)
  EXPECT_LT(r.jt / r.jn, 0.03);
  // the angular to linear momentum change is the end's lever arm (3 %: the end face's size,
  // above; the bar turns by 3 mrad in the impulse so far), about the wall's z axis
  EXPECT_NEAR(r.lever / (0.5 * kL * std::sin(kBeta)), 1.0, 0.03);
  EXPECT_LT(r.h_off_axis, 1e-6);
  // the slide line stops the end without a spring: it takes energy, never gives it
  EXPECT_LE(r.ke_ratio, 1.0 + 1e-9);
}
