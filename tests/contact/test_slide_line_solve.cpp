// The slide lines' bound-constrained solve (ContactBoundSolve.cpp, docs/theory.md 10.8): a 2D
// steel punch whose corners, and every node of its lower face, sit exactly over nodes of the
// target strikes it at 100 m/s (initial velocity) or is driven into it at 50 m/s (prescribed).
// Corner-over-node contact gives redundant rows (two CPs on one node pair) on which the active
// set the solve replaced cycled: the punch gained energy 0.4 us after touch and an element
// inverted. Now a slide line only takes energy out: the model's energy never passes its start
// (plus the work of the driver), the slide lines' dissipation stays >= 0, the balance closes.
#include "TestUtil.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

using namespace scpdyn;
using namespace scpdyn::test;

namespace
{

std::string punchDeck(bool prescribed)
{
  // 20 x 10 mm target (h = 1 mm) on a fixed base; 4 x 4 mm punch (h = 1 mm) 0.1 mm above it
  std::string deck = R"(dimension: 2
geometry: plane_strain
time: {end: 10.0e-6, courant: 0.5}
materials:
  - {name: steel, model: elastic, density: 7800, youngs_modulus: 200e9, poisson_ratio: 0.3}
parts:
  - name: target
    material: steel
    mesh: {type: block, elements: [20, 10], origin: [0.0, 0.0], size: [0.02, 0.01]}
  - name: punch
    material: steel
    mesh: {type: block, elements: [4, 4], origin: [0.008, 0.0101], size: [0.004, 0.004]}
    initial_velocity: [0.0, -VELOCITY]
node_sets:
  - {name: base, box: {min: [0.0, 0.0], max: [0.02, 0.0]}}
  - {name: punch_top, box: {min: [0.008, 0.0141], max: [0.012, 0.0141]}}
boundary_conditions:
  - {type: velocity, node_set: base, component: y, value: 0.0}
DRIVER
contact:
  search_interval: 1
  surfaces:
    - {name: target, part: target, option: slide_line}
    - {name: punch, part: punch, option: slide_line}
)";
  deck.replace(deck.find("VELOCITY"), 8, prescribed ? "50.0" : "100.0");
  deck.replace(deck.find("DRIVER"), 6,
               prescribed ? "  - {type: velocity, node_set: punch_top, component: y, value: -50.0}"
                          : "");
  return deck;
}

struct PunchRun
{
  Real e0 = 0, e_max = 0, w_ext = 0, dissipation_min = 0, dissipation = 0, balance = 0;
  Real end_time = 0;
};

PunchRun runPunch(bool prescribed)
{
  Solver s(deckFromText(punchDeck(prescribed), prescribed ? "punch_driven" : "punch_free"));
  PunchRun r;
  auto total = [&]() {
    const EnergyReport &e = s.energies();
    return e.kinetic + e.internal + e.hourglass;
  };
  r.e0 = r.e_max = total();
  while (s.time() < s.deck().end_time)
  {
    s.cycle();
    const EnergyReport &e = s.energies();
    // the model's energy against its start plus the driver's work so far
    r.e_max = std::max(r.e_max, total() - e.external_work);
    r.dissipation_min = std::min(r.dissipation_min, e.contact_dissipation);
    r.balance = std::max(r.balance, std::abs(e.balance_error));
  }
  r.w_ext = s.energies().external_work;
  r.dissipation = s.energies().contact_dissipation;
  r.end_time = s.time();
  return r;
}

} // namespace

TEST(SlideLineSolve, PunchWithCornersOverNodesTakesEnergyOut)
{
  for (bool prescribed : {false, true})
  {
    SCOPED_TRACE(prescribed ? "prescribed 50 m/s" : "initial 100 m/s");
    const PunchRun r = runPunch(prescribed);
    std::printf("[punch %s] E0 %.4e J, max(E - W_ext) %.4e J, W_ext %.4e J, slide-line "
                "dissipation %.4e J (min %.3e), balance %.2e\n",
                prescribed ? "driven" : "free", r.e0, r.e_max, r.w_ext, r.dissipation,
                r.dissipation_min, r.balance);
    EXPECT_GE(r.end_time, 10.0e-6);
    // the punch strikes (0.1 mm at 100 or 50 m/s: 1 or 2 us) and the collision is plastic
    EXPECT_GT(r.dissipation, 0);
    // no energy from the contact: the leapfrog's energy wanders by its balance error only
    EXPECT_LE(r.e_max, r.e0 * (1 + 1e-2) + 1e-2 * std::abs(r.w_ext));
    EXPECT_GE(r.dissipation_min, -1e-6 * r.e0);
    EXPECT_LT(r.balance, 0.01);
  }
}
