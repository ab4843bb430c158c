// Inputs of the model set-up that ordinary decks need: gravity with a time function, a node set
// as the intersection of a part and a box, and initial velocities per node set, uniform or
// linear in position (docs/input.md).
#include "TestUtil.hpp"
#include "driver/Solver.hpp"
#include "core/InputError.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace scpdyn;
using namespace scpdyn::test;

namespace
{

const std::string kRock = "materials:\n  - {name: rock, model: elastic, density: 2600, "
                          "youngs_modulus: 40.0e9, poisson_ratio: 0.25}\n";

/// Mass-weighted mean velocity of all nodes, component d.
double meanVelocity(const Solver &s, int d)
{
  auto v = Kokkos::create_mirror_view_and_copy(HostSpace(), s.nodes().v);
  auto m = Kokkos::create_mirror_view_and_copy(HostSpace(), s.nodes().mass);
  double P = 0, M = 0;
  for (Index n = 0; n < s.nodes().count; ++n)
    P += m(n) * v(n, d), M += m(n);
  return P / M;
}

} // namespace

// A free block under gravity ramped by a function, g(t) = g0 t/T up to T = 1 ms, then held:
// v(T) = g0 T/2 and v(2T) = 3 g0 T/2. Gravity is taken at the start of each cycle (first order
// in dt): with ~100 cycles per ms the error is below dt/T ~ 1 %; bound 2 %. A constant-gravity
// deck gives g0 t exactly (to round-off).
TEST(DeckInputs, GravityFollowsItsFunction)
{
  const std::string deck = "dimension: 2\ntime: {end: 2.0e-3, courant: 0.5, dt_max: 1.0e-5}\n" +
                           kRock +
                           "parts:\n  - {name: b, material: rock, mesh: {elements: [2, 2], size: "
                           "[0.1, 0.1]}}\n"
                           "functions:\n  - {name: ramp, points: [[0, 0], [1.0e-3, 1], [1, 1]]}\n"
                           "gravity: {value: [0, -10], function: ramp}\n";
  Solver s(deckFromText(deck, "gravity_ramp"));
  EXPECT_EQ(s.gravityAt(0.5e-3)[1], -5.0);
  double v_T = 0;
  while (s.time() < 2.0e-3 - 1e-12)
  {
    s.cycle();
    if (v_T == 0 && s.time() >= 1.0e-3 - 1e-12)
      v_T = meanVelocity(s, 1) * 1.0e-3 / s.time(); // scaled to t = T exactly
  }
  const double v_2T = meanVelocity(s, 1) + 10.0 * (s.time() - 2.0e-3); // back to t = 2T
  EXPECT_NEAR(v_T, -10.0 * 1.0e-3 / 2, 0.02 * 5e-3);
  EXPECT_NEAR(v_2T, -10.0 * 1.5e-3, 0.02 * 15e-3);
  RecordProperty("v_T", std::to_string(v_T));
}

// A node set with both part and box is the part's nodes in the box: of two stacked blocks
// (3 x 3 nodes each, merged along y = 0.1), "lower part, y >= 0.1" is the 3 nodes of the lower
// block's top row, where the box alone would also take the upper block's copies.
TEST(DeckInputs, NodeSetOfPartAndBox)
{
  const std::string deck =
      "dimension: 2\ntime: {end: 1.0e-6}\n" + kRock +
      "parts:\n  - {name: low, material: rock, mesh: {elements: [2, 2], size: [0.1, 0.1]}}\n"
      "  - {name: up, material: rock, mesh: {elements: [2, 2], origin: [0, 0.1], size: [0.1, "
      "0.1]}}\n"
      "node_sets:\n  - {name: low_top, part: low, box: {min: [0, 0.1], max: [0.1, 1]}}\n"
      "  - {name: band, box: {min: [0, 0.1], max: [0.1, 0.1]}}\n";
  Solver s(deckFromText(deck, "set_part_and_box"));
  EXPECT_EQ(s.model().node_sets.at("low_top").size(), 3u);
  EXPECT_EQ(s.model().node_sets.at("band").size(), 6u); // both blocks' copies
}

// Part placement: a 3D bar turned 60 deg about y through (0.05, 0, 0) and then shifted lands
// every node where the rotation matrix about y puts it (1e-12 m: round-off of a metre-sized
// mesh); a second, unplaced part stays put; a 2D square turned 90 deg about its centre maps
// onto its own node positions. Node sets by box see the moved nodes.
TEST(DeckInputs, PartsTurnAndShiftAsRigidBodies)
{
  const std::string deck3 =
      "dimension: 3\ntime: {end: 1.0e-6}\n" + kRock +
      "parts:\n  - {name: bar, material: rock, mesh: {elements: [1, 1, 4], size: [0.1, 0.1, "
      "1.0]},\n     rotate: {angle: 60, axis: [0, 2, 0], point: [0.05, 0, 0]}, translate: [1, 2, "
      "3]}\n"
      "  - {name: block, material: rock, mesh: {elements: [1, 1, 1], origin: [5, 5, 5], size: "
      "[0.1, 0.1, 0.1]}}\n"
      "node_sets:\n  - {name: moved_top, box: {min: [-10, -10, 3.2], max: [4, 4, 4]}}\n";
  Solver s(deckFromText(deck3, "place_3d"));
  const HostMesh &m = s.model().mesh;
  ASSERT_EQ(m.coords.size(), 20u + 8u);
  const double c = std::cos(M_PI / 3), sn = std::sin(M_PI / 3);
  size_t n = 0, tops = 0;
  for (int k = 0; k <= 4; ++k)
    for (int j = 0; j <= 1; ++j)
      for (int i = 0; i <= 1; ++i)
      {
        // the generator's node order: x fastest, then y, then z
        const double x = 0.1 * i - 0.05, y = 0.1 * j, z = 0.25 * k;
        const double want[3] = {0.05 + x * c + z * sn + 1, y + 2, -x * sn + z * c + 3};
        const auto &got = m.coords[n++];
        for (int d = 0; d < 3; ++d)
          EXPECT_NEAR(got[size_t(d)], want[d], 1e-12) << "node " << n - 1 << " component " << d;
        tops += want[2] >= 3.2 ? 1 : 0;
      }
  for (; n < m.coords.size(); ++n)
    EXPECT_GE(m.coords[n][0], 5.0); // the second part is not moved
  EXPECT_EQ(s.model().node_sets.at("moved_top").size(), tops);

  const std::string deck2 =
      "dimension: 2\ntime: {end: 1.0e-6}\n" + kRock +
      "parts:\n  - {name: sq, material: rock, mesh: {elements: [2, 2], size: [0.1, 0.1]}, "
      "rotate: {angle: 90, point: [0.05, 0.05]}}\n";
  Solver s2(deckFromText(deck2, "place_2d"));
  const HostMesh &q = s2.model().mesh;
  for (const auto &x : q.coords)
  {
    // the turned grid is the grid: every coordinate a multiple of 0.05
    EXPECT_NEAR(std::remainder(x[0], 0.05), 0.0, 1e-15);
    EXPECT_NEAR(std::remainder(x[1], 0.05), 0.0, 1e-15);
  }
  // node 0 at (0, 0) turns to (0.1, 0)
  EXPECT_NEAR(q.coords[0][0], 0.1, 1e-15);
  EXPECT_NEAR(q.coords[0][1], 0.0, 1e-15);
}

// initial_conditions: a uniform velocity on one node set, then a rigid rotation about the
// block's centre on another (v = w x (x - c), gradient [[0, -w], [w, 0]]): every node of the
// second set gets exactly that field, the others keep the earlier values, and the rotating
// block's kinetic energy is that of the nodes' masses on the field.
TEST(DeckInputs, InitialVelocityPerNodeSetAndLinearInPosition)
{
  const double w = 100.0; // rad/s
  const std::string deck =
      "dimension: 2\ntime: {end: 1.0e-6}\n" + kRock +
      "parts:\n  - {name: a, material: rock, mesh: {elements: [2, 2], size: [0.1, 0.1]}}\n"
      "  - {name: b, material: rock, mesh: {elements: [2, 2], origin: [0.2, 0], size: [0.1, "
      "0.1]}}\n"
      "node_sets:\n  - {name: sa, part: a}\n  - {name: sb, part: b}\n"
      "initial_conditions:\n  - {node_set: sa, velocity: [3, 4]}\n"
      "  - {node_set: sb, velocity_gradient: [[0, -100], [100, 0]], about: [0.25, 0.05]}\n";
  Solver s(deckFromText(deck, "initial_velocity_sets"));
  auto v = Kokkos::create_mirror_view_and_copy(HostSpace(), s.nodes().v);
  auto x = Kokkos::create_mirror_view_and_copy(HostSpace(), s.nodes().x0);
  int in_a = 0, in_b = 0;
  for (Index n = 0; n < s.nodes().count; ++n)
    if (x(n, 0) < 0.15)
    {
      ++in_a;
      EXPECT_DOUBLE_EQ(v(n, 0), 3.0);
      EXPECT_DOUBLE_EQ(v(n, 1), 4.0);
    }
    else
    {
      ++in_b;
      EXPECT_NEAR(v(n, 0), -w * (x(n, 1) - 0.05), 1e-12);
      EXPECT_NEAR(v(n, 1), w * (x(n, 0) - 0.25), 1e-12);
    }
  EXPECT_EQ(in_a, 9);
  EXPECT_EQ(in_b, 9);
}

// Bad input names the key: an unknown node set, a gradient of the wrong shape, an unknown
// gravity function.
TEST(DeckInputs, BadInitialConditionsAndGravityNameTheKey)
{
  const std::string base =
      "dimension: 2\ntime: {end: 1.0e-6}\n" + kRock +
      "parts:\n  - {name: a, material: rock, mesh: {elements: [2, 2], size: [0.1, 0.1]}}\n"
      "node_sets:\n  - {name: sa, part: a}\n";
  auto message = [&](const std::string &extra) {
    return inputErrorOf([&] { parseDeckString(base + extra, "bad.yaml"); });
  };
  EXPECT_NE(message("initial_conditions:\n  - {node_set: nope, velocity: [1, 0]}\n")
                .find("initial_conditions[0].node_set"),
            std::string::npos);
  EXPECT_NE(message("initial_conditions:\n  - {node_set: sa, velocity_gradient: [[0, 1]]}\n")
                .find("needs 2 rows"),
            std::string::npos);
  EXPECT_NE(message("gravity: {value: [0, -9.81], function: nope}\n").find("gravity.function"),
            std::string::npos);
}

// inputs/examples/spinning_block_gravity_ramp.yaml, the three inputs together: the corner starts
// at w x r = (-5, 5) m/s exactly, the block strikes the ground (contact energy > 0), and the
// energy balance, with the ramped gravity's work and the joint's, closes to 1e-3 (measured
// 3.4e-5).
TEST(DeckInputs, ExampleDeckRuns)
{
  Solver s(parseDeck(std::string(SCPDYN_SOURCE_DIR) +
                     "/inputs/examples/spinning_block_gravity_ramp.yaml"));
  const std::vector<Real> g0 = s.gaugeValues();
  ASSERT_EQ(g0.size(), 2u);
  EXPECT_NEAR(g0[0], -5.0, 1e-9);
  EXPECT_NEAR(g0[1], 5.0, 1e-9);
  double worst = 0;
  while (s.time() < s.deck().end_time)
  {
    s.cycle();
    worst = std::max(worst, std::fabs(s.energies().balance_error));
  }
  EXPECT_GT(s.energies().contact, 0.0);
  EXPECT_LT(worst, 1e-3);
}
