// rcforc.csv, spcforc.csv and matsum.csv (driver/RunHistories.hpp) against the physics they
// report: the parts add up to history.csv, momentum balances of the contact forces and of the
// constraint reactions, and the reaction of a column settled under gravity.
#include "TestUtil.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

using namespace scpdyn;

namespace
{
namespace fs = std::filesystem;
using Columns = std::map<std::string, std::vector<double>>;

/// Runs `yaml` in-process into a fresh directory; returns the directory.
std::string runDeck(const std::string &yaml, const std::string &name)
{
  const std::string dir = std::string(SCPDYN_TEST_WORKDIR) + "/run_histories/" + name;
  fs::remove_all(dir);
  Solver s(test::deckFromText(yaml, name));
  s.run(dir);
  return dir;
}

double maxAbs(const std::vector<double> &v)
{
  double m = 0;
  for (double x : v)
    m = std::max(m, std::abs(x));
  return m;
}

/// sum over rows of dt * column: with a row every cycle, the impulse of a force that acted
/// over each row's step (the leapfrog applies the step's force for its whole dt, v^{n+1} = v^n
/// + dt F / m, so the momentum change is exactly this rectangle sum)
double impulse(const Columns &history, const std::vector<double> &force)
{
  const std::vector<double> &dt = history.at("dt");
  double sum = 0;
  for (size_t k = 0; k < force.size(); ++k)
    sum += dt[k] * force[k];
  return sum;
}

// Two elastic blocks, each with its own contact surface, the first at 20 m/s into the second at
// rest: no other force, so each block's momentum changes only by its contact force.
const char *kImpactDeck = R"(dimension: 2
time: {end: 2.0e-5}
materials:
  - {name: rock, density: 2600, youngs_modulus: 5.0e10, poisson_ratio: 0.25}
parts:
  - {name: a, material: rock, mesh: {elements: [4, 4], size: [0.02, 0.02]}, initial_velocity: [20, 1]}
  - {name: b, material: rock, mesh: {elements: [5, 5], origin: [0.0201, -0.003], size: [0.02, 0.02]}}
contact:
  search_gap: 0.002
  surfaces:
    - {name: sa, part: a, option: implicit}
    - {name: sb, part: b, option: implicit}
)";

// The projectile of kImpactDeck against a wall block held along its far side (vx = 0): the only
// external force is the constraint's reaction.
const char *kWallDeck = R"(dimension: 2
time: {end: 3.0e-5}
materials:
  - {name: rock, density: 2600, youngs_modulus: 5.0e10, poisson_ratio: 0.25}
parts:
  - {name: a, material: rock, mesh: {elements: [4, 4], size: [0.02, 0.02]}, initial_velocity: [20, 1]}
  - {name: wall, material: rock, mesh: {elements: [3, 6], origin: [0.0201, -0.01], size: [0.015, 0.04]}}
node_sets:
  - {name: back, box: {min: [0.0351, -1], max: [0.0351, 1]}}
boundary_conditions:
  - {type: velocity, node_set: back, component: x, value: 0}
contact:
  search_gap: 0.002
  surfaces:
    - {name: joint, part: "*", option: explicit}
)";
} // namespace

TEST(RunHistories, PartsAddUpToTheHistoryTotals)
{
  // two parts merged into one body (merge_nodes: the shared row of nodes counts in part `low`
  // only) hit at different speeds, plus the wall deck's contact and constraint: kinetic,
  // internal and hourglass energy and momentum of the parts add up to history.csv's columns,
  // which sum the same terms in another order (round-off: 1e-12 of the column's largest value)
  const std::string merged = R"(dimension: 2
time: {end: 2.0e-5}
materials:
  - {name: rock, density: 2600, youngs_modulus: 5.0e10, poisson_ratio: 0.25}
parts:
  - {name: low, material: rock, merge_nodes: true, mesh: {elements: [4, 2], size: [0.02, 0.01]}, initial_velocity: [5, 0]}
  - {name: high, material: rock, merge_nodes: true, mesh: {elements: [4, 2], origin: [0, 0.01], size: [0.02, 0.01]}, initial_velocity: [-5, 3]}
)";
  for (const auto &[name, yaml] : {std::make_pair("matsum_merged", merged),
                                   std::make_pair("matsum_wall", std::string(kWallDeck))})
  {
    const std::string dir = runDeck(yaml, name);
    const Columns h = test::readCsv(dir + "/history.csv"), m = test::readCsv(dir + "/matsum.csv");
    ASSERT_EQ(m.at("time").size(), h.at("time").size()) << name;
    const std::vector<std::string> parts = std::string(name) == "matsum_merged"
                                               ? std::vector<std::string>{"low", "high"}
                                               : std::vector<std::string>{"a", "wall"};
    for (const char *q :
         {"kinetic", "internal", "hourglass", "momentum_x", "momentum_y", "momentum_z"})
    {
      // the scale of the terms: the parts' momenta may cancel in the total
      double scale = std::max(maxAbs(h.at(q)), 1e-300);
      for (const auto &p : parts)
        scale = std::max(scale, maxAbs(m.at(p + ":" + q)));
      double worst = 0;
      for (size_t k = 0; k < h.at(q).size(); ++k)
      {
        double sum = 0;
        for (const auto &p : parts)
          sum += m.at(p + ":" + q)[k];
        worst = std::max(worst, std::abs(sum - h.at(q)[k]) / scale);
      }
      std::printf("[matsum] %s %-10s parts - history: %.3e of %.3e\n", name, q, worst, scale);
      EXPECT_LT(worst, 1e-12) << name << " " << q;
    }
  }
}

TEST(RunHistories, AFreeBlockKeepsItsMomentumPerPart)
{
  // two blocks far apart, translating: each part's momentum stays its mass (rho x area per
  // metre) times its velocity. Not bit for bit: x + dt v rounds, which leaves strains of 1e-16
  // and internal energies of 1e-31 J whose forces add up to zero over a part to round-off; over
  // 20 cycles that is a few ulps of the momentum (measured: 2), allowed 1e-14 of it
  const std::string dir = runDeck(R"(dimension: 2
time: {end: 2.0e-5}
materials:
  - {name: rock, density: 2600, youngs_modulus: 5.0e10, poisson_ratio: 0.25}
parts:
  - {name: a, material: rock, mesh: {elements: [4, 2], size: [0.04, 0.02]}, initial_velocity: [3, -2]}
  - {name: b, material: rock, mesh: {elements: [3, 3], origin: [1, 0], size: [0.03, 0.03]}, initial_velocity: [-1, 4]}
)",
                                  "matsum_free");
  const Columns m = test::readCsv(dir + "/matsum.csv");
  ASSERT_GT(m.at("time").size(), 10u);
  const struct
  {
    const char *part;
    double mass, vx, vy;
  } blocks[] = {{"a", 2600 * 0.04 * 0.02, 3, -2}, {"b", 2600 * 0.03 * 0.03, -1, 4}};
  for (const auto &b : blocks)
  {
    const std::string p = b.part;
    for (const char *q : {":momentum_x", ":momentum_y"})
    {
      double drift = 0;
      for (double v : m.at(p + q))
        drift = std::max(drift, std::abs(v - m.at(p + q).front()));
      std::printf("[matsum] free block %s%s: %.17g N s, largest change %.3e\n", p.c_str(), q,
                  m.at(p + q).front(), drift);
      EXPECT_LE(drift, 1e-14 * std::abs(m.at(p + q).front())) << p << q;
    }
    // the nodal masses add up the element masses in another order: round-off
    EXPECT_NEAR(m.at(p + ":momentum_x").front(), b.mass * b.vx, 1e-14 * b.mass * 4) << p;
    EXPECT_NEAR(m.at(p + ":momentum_y").front(), b.mass * b.vy, 1e-14 * b.mass * 4) << p;
  }
}

TEST(RunHistories, ContactForcesAreOppositeAndGiveEachBlockItsMomentum)
{
  const std::string dir = runDeck(kImpactDeck, "rcforc_impact");
  const Columns h = test::readCsv(dir + "/history.csv"), m = test::readCsv(dir + "/matsum.csv"),
                c = test::readCsv(dir + "/rcforc.csv");
  ASSERT_EQ(c.at("time").size(), h.at("time").size());
  ASSERT_TRUE(c.count("sa-sb:fx1") && c.count("sa-sa:fx1") && c.count("sb-sb:fz2"));
  for (const char *q : {"x", "y"})
  {
    const std::vector<double> &f1 = c.at(std::string("sa-sb:f") + q + "1"),
                              &f2 = c.at(std::string("sa-sb:f") + q + "2");
    const double scale = maxAbs(f2);
    for (size_t k = 0; k < f1.size(); ++k)
      EXPECT_LE(std::abs(f1[k] + f2[k]), 1e-15 * scale) << q << " row " << k;
    // the blocks touch only each other: a surface on itself carries nothing
    EXPECT_EQ(maxAbs(c.at(std::string("sa-sa:f") + q + "1")), 0.0);
    EXPECT_EQ(maxAbs(c.at(std::string("sb-sb:f") + q + "2")), 0.0);
    // each block is free, its internal forces add up to zero (round-off of the element forces,
    // ~1e-16 of the contact force per step): its momentum change is the impulse of its
    // contact force
    for (const auto &[part, f] : {std::make_pair("a", &f1), std::make_pair("b", &f2)})
    {
      const std::vector<double> &p = m.at(std::string(part) + ":momentum_" + q);
      const double change = p.back() - p.front(), given = impulse(h, *f);
      const double ref = std::abs(impulse(h, c.at("sa-sb:fx2")));
      std::printf("[rcforc] block %s %s: momentum change %.9e N s, contact impulse %.9e N s "
                  "(%.2e of %.3e)\n",
                  part, q, change, given, std::abs(change - given) / ref, ref);
      EXPECT_GT(ref, 0.1 * 2600 * 0.02 * 0.02 * 20) << "the blocks must collide";
      EXPECT_NEAR(change, given, 1e-6 * ref) << part << " " << q;
    }
  }
}

TEST(RunHistories, ConstraintReactionsBalanceTheMomentum)
{
  // the projectile bounces off the held wall: no external force but the reaction, so the
  // model's momentum changes by the reactions' impulse (each step's reaction acts over its dt:
  // m (v^{n+1} - v^n) = dt (f_int + f_contact + R) node by node, and f_int and f_contact add up
  // to zero over the model)
  const std::string dir = runDeck(kWallDeck, "spcforc_wall");
  const Columns h = test::readCsv(dir + "/history.csv"), r = test::readCsv(dir + "/spcforc.csv");
  ASSERT_EQ(r.at("time").size(), h.at("time").size());
  ASSERT_EQ(r.size(), 2u) << "time and back:x";
  const double change = h.at("momentum_x").back() - h.at("momentum_x").front();
  const double given = impulse(h, r.at("back:x"));
  std::printf("[spcforc] momentum change %.12e N s, reaction impulse %.12e N s (%.2e)\n", change,
              given, std::abs(change - given) / std::abs(given));
  EXPECT_GT(std::abs(given), 0.1 * std::abs(h.at("momentum_x").front())) << "the wall must hold";
  EXPECT_NEAR(change, given, 1e-6 * std::abs(given));
}

TEST(RunHistories, AColumnSettledUnderGravityRestsOnItsBase)
{
  // a 0.1 x 0.4 m column on a held base, gravity ramped over 10 periods T of its first axial
  // mode (T = 4 L / c = 1.6 / 4529 m/s = 0.35 ms, plane-strain bar speed) and then held for 5:
  // a ramp of duration t_r leaves an oscillation of at most T / (pi t_r) = 3.2 % of the static
  // load, whose mean over the 5 held periods is off by at most 1 / (5 pi) of that, 0.2 %; so the
  // mean reaction is m g within 0.5 %
  const double T = 0.35e-3, ramp = 10 * T, end = 15 * T;
  char yaml[2048];
  std::snprintf(yaml, sizeof yaml, R"(dimension: 2
time: {end: %.9g}
functions:
  - {name: ramp, points: [[0, 0], [%.9g, 1], [1, 1]]}
gravity: {value: [0, -9.81], function: ramp}
materials:
  - {name: rock, density: 2600, youngs_modulus: 5.0e10, poisson_ratio: 0.25}
parts:
  - {name: column, material: rock, mesh: {elements: [2, 8], size: [0.1, 0.4]}}
node_sets:
  - {name: base, box: {min: [-1, 0], max: [1, 0]}}
boundary_conditions:
  - {type: velocity, node_set: base, component: x, value: 0}
  - {type: velocity, node_set: base, component: y, value: 0}
)",
                end, ramp);
  const std::string dir = runDeck(yaml, "spcforc_column");
  const Columns h = test::readCsv(dir + "/history.csv"), r = test::readCsv(dir + "/spcforc.csv");
  const double mg = 2600 * 0.1 * 0.4 * 9.81;
  double sum = 0, span = 0;
  for (size_t k = 0; k < r.at("time").size(); ++k)
    if (r.at("time")[k] > ramp)
    {
      sum += h.at("dt")[k] * r.at("base:y")[k];
      span += h.at("dt")[k];
    }
  ASSERT_GT(span, 4 * T);
  std::printf("[spcforc] column: mean reaction %.6e N over %.3e s, m g %.6e N (%.2e), last %.6e, "
              "x %.3e\n",
              sum / span, span, mg, sum / span / mg - 1, r.at("base:y").back(),
              maxAbs(r.at("base:x")));
  EXPECT_NEAR(sum / span, mg, 5e-3 * mg);
  // the base holds the column symmetrically: no net horizontal reaction beyond round-off
  EXPECT_LT(maxAbs(r.at("base:x")), 1e-9 * mg);
}
