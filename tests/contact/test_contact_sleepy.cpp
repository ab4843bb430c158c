// Sleepy contact (docs/theory.md 11.4, ContactSleepy.cpp): tied while the elements behind a CP's
// faces are intact, a frictional slide line once the deck's failure measure of either (or both)
// reaches its threshold, or at a prescribed time; irreversible.
#include "ContactTestUtil.hpp"

#include "contact/ContactSystem.hpp"
#include "contact/JointConstraints.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <string>

using namespace scpdyn;
using namespace scpdyn::test;

namespace
{

// The wall of tests/parallel/decks/sleepy_wall_2d.yaml: 4 x 3 bricks (20 x 10 mm, 4 x 2 quads
// each, every other course shifted) of an elastic-plastic brick (yield 40 MPa), struck on its top
// by a steel block at 60 m/s across a slide line: the stress under the striker, rho c v ~ 200
// MPa, yields the bricks there; its joints are `joint`.
std::string wallDeck(const std::string &joint)
{
  const std::string deck =
      readText(std::string(SCPDYN_SOURCE_DIR) + "/tests/parallel/decks/sleepy_wall_2d.yaml");
  return replaced(deck, "option: sleepy, failure_measure: plastic_strain, failure_threshold: 0.03",
                  joint);
}

template <class V>
auto host(const V &v)
{
  return Kokkos::create_mirror_view_and_copy(HostSpace(), v);
}

/// The largest difference of two node fields relative to the largest magnitude of the first.
Real relativeDifference(const VectorView &a, const VectorView &b, Index n)
{
  auto ha = host(a), hb = host(b);
  Real diff = 0, scale = 0;
  for (Index i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d)
    {
      diff = std::max(diff, std::abs(ha(i, d) - hb(i, d)));
      scale = std::max(scale, std::abs(ha(i, d)));
    }
  return scale > 0 ? diff / scale : diff;
}

} // namespace

TEST(Sleepy, SwitchRule)
{
  JointParams p;
  p.option = ContactOption::Sleepy;
  EXPECT_FALSE(sleepyFails(p, 1e30, 1e30, 1e30)) << "no measure: never";
  p.failure_measure = FailureMeasure::PlasticStrain;
  p.failure_threshold = 0.01;
  EXPECT_FALSE(sleepyFails(p, 0.0099, 0.005, 1.0));
  EXPECT_TRUE(sleepyFails(p, 0.0, 0.01, 0.0)) << "either element, at the threshold";
  p.failure_both = true;
  EXPECT_FALSE(sleepyFails(p, 0.0, 0.02, 0.0)) << "both: one is not enough";
  EXPECT_TRUE(sleepyFails(p, 0.01, 0.02, 0.0));
  p.failure_measure = FailureMeasure::Time;
  p.failure_threshold = 2e-3;
  EXPECT_FALSE(sleepyFails(p, 1.0, 1.0, 1.9e-3));
  EXPECT_TRUE(sleepyFails(p, 0.0, 0.0, 2e-3));

  CpState s;
  EXPECT_TRUE(isTie(p, s));
  EXPECT_FALSE(isSlide(p, s));
  s.failed = 1;
  EXPECT_FALSE(isTie(p, s));
  EXPECT_TRUE(isSlide(p, s));
}

// Until its first switch a sleepy wall is the sticky wall: the same tie rows, the same solve,
// bit for bit with one thread. With more, the contact forces are added atomically in any order,
// and the tie solve, which stops at 1e-10 of its initial residual, may take one iteration more
// or less on either run: to 1e-9. The switch then comes (the struck bricks yield), the runs part.
TEST(Sleepy, IntactIsStickyToRoundOffThenSwitches)
{
  Solver sticky(deckFromText(wallDeck("option: sticky"), "wall_sticky"));
  Solver sleepy(deckFromText(
      wallDeck("option: sleepy, failure_measure: plastic_strain, failure_threshold: 3.0e-2"),
      "wall_sleepy"));
  const Index n = sticky.nodes().count;
  long equal_cycles = 0, first_switch = -1;
  Real worst = 0;
  while (sleepy.time() < sleepy.deck().end_time)
  {
    sticky.cycle();
    sleepy.cycle();
    const Index failed = sleepy.contact()->failedCount();
    if (failed > 0 && first_switch < 0)
      first_switch = sleepy.cycles();
    if (failed > 0)
      continue;
    worst = std::max({worst, relativeDifference(sticky.nodes().x, sleepy.nodes().x, n),
                      relativeDifference(sticky.nodes().v, sleepy.nodes().v, n)});
    ++equal_cycles;
  }
  const Real after = relativeDifference(sticky.nodes().v, sleepy.nodes().v, n);
  std::printf("[sleepy wall] %ld cycles before the first switch (cycle %ld), x and v within "
              "%.1e of the sticky wall; at the end %ld of %ld CPs failed, v differs by %.2e\n",
              equal_cycles, first_switch, worst, long(sleepy.contact()->failedCount()),
              long(sleepy.contact()->count()), after);
  if (ExecSpace().concurrency() == 1)
    EXPECT_EQ(worst, 0.0) << "tied, a sleepy wall is the sticky wall, bit for bit";
  else
    EXPECT_LE(worst, 1e-9) << "tied, a sleepy wall is the sticky wall";
  EXPECT_GT(equal_cycles, 10) << "the wall is tied for a while before the bricks yield";
  EXPECT_GT(first_switch, 0) << "the struck bricks yield and their joints fail";
  EXPECT_GT(after, 1e-3) << "a switch changes the run";
}

// The CPs that have switched are exactly those with an element at or past the threshold (with
// `both`: both elements), as the plastic strain never decreases: either rule, checked per CP
// on the measures of the last cycle. With residual friction: the released joints slide and
// the energy check (which books a failing CP's last impulse as a tie's, no work) stays quiet.
TEST(Sleepy, TheCpsOfFailedElementsSwitchAndNoOthers)
{
  for (const char *sides : {"either", "both"})
  {
    const Real threshold = 2.0e-3;
    Solver s(deckFromText(wallDeck("option: sleepy, failure_measure: plastic_strain, "
                                   "failure_threshold: 2.0e-3, mu_static: 0.4, failure_sides: " +
                                   std::string(sides)),
                          "wall_sleepy_sides"));
    while (s.time() < s.deck().end_time)
      s.cycle();
    const ContactFaceData &F = s.contact()->faces();
    const CommonPlaneData &cp = s.contact()->planes();
    auto state = host(cp.state);
    auto params = host(cp.params);
    auto f1 = host(cp.face1), f2 = host(cp.face2);
    auto element = host(F.element);
    auto eps = host(s.elements().plastic_strain);
    int sleepy = 0, failed = 0, wrong = 0;
    for (Index p = 0; p < cp.count; ++p)
    {
      if (params(p).option != ContactOption::Sleepy)
        continue;
      ++sleepy;
      const Real e1 = eps(element(f1(p))), e2 = eps(element(f2(p)));
      const bool expect = std::string(sides) == "both" ? std::min(e1, e2) >= threshold
                                                       : std::max(e1, e2) >= threshold;
      failed += state(p).failed;
      wrong += (state(p).failed != 0) != expect ? 1 : 0;
    }
    std::printf("[sleepy %s] %d of %d sleepy CPs failed\n", sides, failed, sleepy);
    EXPECT_EQ(wrong, 0) << sides;
    EXPECT_GT(failed, 0) << sides;
    EXPECT_LT(failed, sleepy) << sides << ": the far joints stay tied";
  }
}

namespace
{

// The incline of tests/contact/test_slide_line_friction.cpp (a soft 0.2 x 0.1 m block of 4 x
// 2 quads on a fixed base, gravity tilted by 30 degrees) with sleepy joints that fail at 0.03 s.
constexpr Real kG = 9.81, kBlockMass = 1000 * 0.2 * 0.1, kRelease = 0.03;

std::string sleepyIncline(const std::string &friction)
{
  return test::inclineDeck(30, "    - {name: glue, part: \"*\", option: sleepy, failure_measure: "
                               "time, failure_threshold: 0.03, " +
                                   friction + "}\n");
}

} // namespace

// Tied, the block holds on the 30 degree incline; released at 0.03 s it slides as the frictional
// slide line does, a = g (sin - mu cos), measured from 0.06 s (when it slides at 0.1 m/s, far
// above the 8e-3 m/s the release sets the soft block vibrating with) to the end.
TEST(Sleepy, ReleasedBlockSlidesDownTheInclineWithCoulombAcceleration)
{
  const Real th = 30 * M_PI / 180, mu = 0.3;
  Solver s(deckFromText(sleepyIncline("mu_static: 0.3"), "incline_sleepy"));
  Real x_tied = 0, x = 0, v_from = 0, t_from = -1;
  while (s.time() < s.deck().end_time)
  {
    const Real t0 = s.time();
    s.cycle();
    const Real v = s.energies().momentum[0] / kBlockMass; // the base is held at rest
    x += v * (s.time() - t0);
    if (s.time() < kRelease)
      x_tied = std::max(x_tied, std::abs(x));
    if (t_from < 0 && s.time() >= 0.06)
      t_from = s.time(), v_from = v;
  }
  const Real v_end = s.energies().momentum[0] / kBlockMass;
  const Real a = (v_end - v_from) / (s.time() - t_from);
  const Real exact = kG * (std::sin(th) - mu * std::cos(th));
  // tied, the block shears elastically under its weight: its top by tau h / G, tau = rho g h
  // sin(theta), its centre by half of that; loaded at once, it overshoots to twice the static
  const Real G = 1.0e7 / 2.5, h = 0.1;
  const Real tied_bound = 2 * 1000 * kG * h * std::sin(th) / G * h;
  const Real frictionless = 0.5 * kG * std::sin(th) * kRelease * kRelease;
  std::printf("[sleepy incline] tied: |x| <= %.2e m (bound %.2e m; frictionless it would slide "
              "%.2e m); released: a = %.5f m/s^2, g(sin - mu cos) = %.5f (%+.2e); %ld failed "
              "CPs\n",
              x_tied, tied_bound, frictionless, a, exact, a / exact - 1,
              long(s.contact()->failedCount()));
  EXPECT_LT(x_tied, tied_bound) << "tied until the switch";
  EXPECT_NEAR(a / exact, 1.0, 0.01);
  EXPECT_GT(s.contact()->failedCount(), 0);
}

namespace
{

// Verification T11g: two 0.1 m bars (50 line2 cells each) joined at x = 0.1 m, their far ends
// pulled apart at 1 m/s each. The tension waves meet at the joint at L/c and leave it under
// sigma = 2 Z v; the sleepy joint is forced to fail at t_s = 1.5 L/c, while in tension.
constexpr Real kRho = 2000, kE = 2.0e10, kL = 0.1, kV = 1.0;

std::string barsDeck(const std::string &joint, bool monolithic)
{
  std::string deck = R"(dimension: 1
time: {end: END, courant: 0.5}
materials:
  - {name: m, model: elastic, density: 2000, youngs_modulus: 2.0e10, poisson_ratio: 0.0}
parts:
PARTS
node_sets:
  - {name: left_end, box: {min: [0.0], max: [0.0]}}
  - {name: right_end, box: {min: [0.2], max: [0.2]}}
boundary_conditions:
  - {type: velocity, node_set: left_end, component: x, value: -1.0}
  - {type: velocity, node_set: right_end, component: x, value: 1.0}
gauges:
  - {name: left, kind: node, point: [0.08], quantities: [vx]}
  - {name: right, kind: node, point: [0.12], quantities: [vx]}
  - {name: sl, kind: element, point: [0.081], quantities: [sxx]}
)";
  const std::string parts =
      monolithic ? "  - {name: bar, material: m, mesh: {elements: [100], size: [0.2]}}\n"
                 : "  - {name: a, material: m, mesh: {elements: [50], size: [0.1]}}\n"
                   "  - {name: b, material: m, mesh: {elements: [50], origin: [0.1], size: "
                   "[0.1]}}\n";
  deck = replaced(deck, "PARTS", parts);
  const Real c = std::sqrt(kE / kRho);
  deck = replaced(deck, "END", std::to_string(2.0 * kL / c));
  if (!monolithic)
    deck += "contact:\n  surfaces:\n    - {name: joint, part: \"*\", " + joint + "}\n";
  return deck;
}

} // namespace

TEST(Sleepy, ForcedSwitchInTensionSendsTheReleaseWaveT11g)
{
  const Real c = std::sqrt(kE / kRho), Z = kRho * c, ts = 1.5 * kL / c;
  const Real sigma = 2 * Z * kV; // the interface tension at t_s
  Solver mono(deckFromText(barsDeck("", true), "bars_mono"));
  Solver sleepy(deckFromText(
      barsDeck("option: sleepy, failure_measure: time, failure_threshold: " + std::to_string(ts),
               false),
      "bars_sleepy"));
  Real worst_before = 0, tension = 0, v_left = 0, v_right = 0, s_left = 0, fn_after = -1;
  // the release front (2 cm away) past the gauges, until the end (the first waves' reflections
  // from the far ends arrive after it)
  const Real t_read = ts + (0.02 + 0.01) / c;
  Real window = 0;
  while (sleepy.time() < sleepy.deck().end_time)
  {
    mono.cycle();
    sleepy.cycle();
    const std::vector<Real> a = mono.gaugeValues(), b = sleepy.gaugeValues();
    if (sleepy.contact()->failedCount() == 0)
    {
      ASSERT_NEAR(mono.dt(), sleepy.dt(), 1e-12 * mono.dt()); // the cells' lengths to round-off
      for (size_t k = 0; k < a.size(); ++k)
        worst_before = std::max(worst_before, std::abs(a[k] - b[k]) / (k < 2 ? kV : sigma));
      tension = b[2];
    }
    else if (fn_after < 0)
    { // the cycle of the switch: the CP carries nothing
      auto state = host(sleepy.contact()->planes().state);
      fn_after = 0;
      for (Index p = 0; p < sleepy.contact()->count(); ++p)
        fn_after = std::max(fn_after, std::abs(state(p).Fn));
    }
    if (sleepy.time() >= t_read) // the front rings (no viscosity in expansion): the mean
    {
      v_left += b[0] * sleepy.dt(), v_right += b[1] * sleepy.dt(), s_left += b[2] * sleepy.dt();
      window += sleepy.dt();
    }
  }
  v_left /= window, v_right /= window, s_left /= window;
  std::printf("[T11g] before t_s: worst difference to the monolithic bar %.2e; tension %.4e Pa "
              "(2 Z v = %.4e); after the release (mean from 1.8 L/c to the end): v = %.4f / %.4f "
              "m/s (exact -/+ %.4f), sxx = %.3e Pa\n",
              worst_before, tension, sigma, v_left, v_right, sigma / Z, s_left);
  EXPECT_LT(worst_before, 1e-9) << "tied, the jointed bar is the monolithic bar";
  EXPECT_GE(fn_after, 0.0) << "the joint fails";
  EXPECT_LT(fn_after, 1e-9 * sigma) << "normal force in the cycle of the switch [N]";
  EXPECT_NEAR(tension / sigma, 1.0, 0.02) << "the interface is in tension when it fails";
  EXPECT_NEAR(v_left, -sigma / Z, 0.02 * sigma / Z);
  EXPECT_NEAR(v_right, sigma / Z, 0.02 * sigma / Z);
  EXPECT_LT(std::abs(s_left), 0.02 * sigma) << "the release wave leaves the bar unloaded";
}
