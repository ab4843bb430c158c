// The paper's Fig. 2 (docs/theory.md 14.1), coarse: the committed decks inputs/paper/fig2_*.yaml
// (1 cell per 1 mm block) run in-process to 40 us, and the expected outcomes (a)-(e) asserted
// on the velocity gauge at 80 mm. Reference numbers: scp-ref/bar1d.py (docs/theory.md 14.1 table).
// The jointed decks start the impactor 0.222 mm short of the target (scripts/paper/
// make_fig2_decks.py), so their impact is at 0.222 us; times below are measured from the impact.
#include "TestUtil.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

using namespace scpdyn;

namespace
{
constexpr Real kImpact = 2 * 0.5 * 1e-3 / 4500.0; // GAP / V0 of make_fig2_decks.py: 2 steps [s]
constexpr Real kThreshold = 100.0; // arrival: first v > 100 m/s (docs/theory.md 14.1)

struct Signal
{
  Real arrival = -1; // [s] after the impact
  Real peak = 0;     // [m/s]
};

Signal runCase(const std::string &name)
{
  const std::string path = std::string(SCPDYN_SOURCE_DIR) + "/inputs/paper/fig2_" + name + ".yaml";
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  Deck deck = parseDeckString(text.str(), path);
  deck.end_time = 40e-6; // past the soft joints' arrival (33.4 us), not the 60 us of the figure
  Solver s(deck);
  const Real t0 = name == "solid" ? 0.0 : kImpact;
  Signal sig;
  Real t_prev = 0, v_prev = 0;
  while (s.time() < deck.end_time)
  {
    s.cycle();
    const Real v = s.gaugeValues().at(0); // g80:vx
    const Real t = s.time() - t0;
    if (sig.arrival < 0 && v > kThreshold)
      sig.arrival = t_prev + (kThreshold - v_prev) * (t - t_prev) / (v - v_prev);
    sig.peak = std::max(sig.peak, v);
    t_prev = t;
    v_prev = v;
  }
  return sig;
}

} // namespace

// (a)-(d) of docs/theory.md 14.1 with the reference arrival shifts of bar1d.py (solid 14.78 us;
// very stiff +0.00, a = 0.01 mm +1.11, a = 0.1 mm +18.66 us; peaks 495, 496, 496, 160 m/s).
// Tolerances: two time steps (0.22 us at S = 0.5) for equal arrivals: the jointed bars' front
// trails the merged bar's by about one step here (+0.11 us; bar1d: 0), and a real delay of the
// stiff joints (a = 1e-3 mm: +0.11 us in bar1d) is of that size; the code's finite-strain elements
// shift every arrival by about -0.4 us
// against bar1d's small-strain bar, the same for all cases, so shifts are compared, within
// 0.3 us (medium) and 1.5 us (soft: a 33 us delay built up over 70 joints, bar1d's own
// explicit/implicit spread is 0.55 us); peaks within 2 % (solid-like) and 10 % (soft).
TEST(PaperFig2, JointedWaveOutcomes)
{
  const Signal solid = runCase("solid");
  const Signal stiff = runCase("a1e-7_implicit");
  const Signal slide = runCase("a1e-7_slide");
  const Signal medium = runCase("a1e-5_implicit");
  const Signal soft = runCase("a1e-4_implicit");
  ASSERT_GT(solid.arrival, 0);
  ASSERT_GT(soft.arrival, 0);
  // the solid bar itself: 70 mm at 4.5 km/s = 15.6 us for the mid-rise, 14.78 us at 100 m/s in
  // bar1d; finite strain makes the shock faster (about 14.4 us here)
  EXPECT_NEAR(solid.arrival, 14.4e-6, 0.5e-6);
  EXPECT_NEAR(solid.peak, 495.0, 10.0);
  // (a) very stiff implicit joints ~ solid
  EXPECT_NEAR(stiff.arrival, solid.arrival, 0.22e-6);
  EXPECT_NEAR(stiff.peak / solid.peak, 1.0, 0.02);
  // (b) slide line ~ solid (before tensile reflections: the gauge's first pulse)
  EXPECT_NEAR(slide.arrival, solid.arrival, 0.22e-6);
  EXPECT_NEAR(slide.peak / solid.peak, 1.0, 0.02);
  // (c) softer joints are slower
  EXPECT_NEAR(medium.arrival - solid.arrival, 1.11e-6, 0.3e-6);
  EXPECT_NEAR(soft.arrival - solid.arrival, 18.66e-6, 1.5e-6);
  // (d) softer joints reflect more: the transmitted peak falls to about a third
  EXPECT_NEAR(medium.peak, 496.0, 10.0);
  EXPECT_NEAR(soft.peak, 160.0, 16.0);
  // (e) the explicit update (limit (19), C_safe 0.5) overestimates the joint forces: a higher
  // transmitted peak (bar1d +2.5 %, here about +11 %; bounded at +25 %) and an earlier arrival
  // (bar1d -0.55 us; within 0.5 us of that)
  const Signal soft_x = runCase("a1e-4_explicit");
  ASSERT_GT(soft_x.arrival, 0);
  EXPECT_GT(soft_x.peak, soft.peak);
  EXPECT_LT(soft_x.peak, 1.25 * soft.peak);
  EXPECT_NEAR(soft_x.arrival - soft.arrival, -0.55e-6, 0.5e-6);
}
