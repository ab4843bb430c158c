// numerics.node_update: with `fused` (the default) step 6 integrates the nodes nothing after it
// touches (integrate/NodeSweep.hpp) and step 12 the rest. On decks with contact (1D, 2D, 3D,
// joints and sticky), face pressure, gravity, velocity constraints and merged parts, a whole
// run must give the gauges of `separate` bit for bit, and the same energies to round-off (the
// sums add the same terms in another order). One thread: face pressure and contact forces are
// added atomically, so two runs on two threads may differ in the last bits whatever the mode.
// tests/element/test_node_sweep.cpp compares every node of one step, for any chunk count.
#include "TestUtil.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace scpdyn
{
namespace
{

using test::readText;

/// The deck with numerics.node_update set, run by the binary on one thread; its output directory.
std::string runDeck(const std::string &file, const std::string &mode)
{
  std::string text = readText(std::string(SCPDYN_SOURCE_DIR) + "/tests/parallel/decks/" + file);
  const std::string key = "numerics: {";
  const size_t at = text.find("\n" + key);
  if (at == std::string::npos)
    text += "numerics: {node_update: " + mode + "}\n";
  else
    text.insert(at + 1 + key.size(), "node_update: " + mode + ", ");
  const std::string stem = file.substr(0, file.find('.')) + "_" + mode;
  const std::string deck = test::writeWorkFile(stem + ".yaml", text);
  const std::string out = std::string(SCPDYN_TEST_WORKDIR) + "/" + stem;
  std::string err;
  EXPECT_EQ(test::runBinary(deck + " -o " + out, &err, "OMP_NUM_THREADS=1"), 0) << err;
  return out;
}

class FusedNodeUpdate : public ::testing::TestWithParam<const char *>
{
};

TEST_P(FusedNodeUpdate, GivesTheGaugesOfSeparateStepsBitForBit)
{
  const std::string apart = runDeck(GetParam(), "separate");
  const std::string fused = runDeck(GetParam(), "fused");
  const std::string gauges = readText(apart + "/gauges.csv");
  ASSERT_GT(gauges.size(), 200u);
  EXPECT_EQ(readText(fused + "/gauges.csv"), gauges);
  // summary.json says how many nodes step 6 integrated: none with separate steps
  EXPECT_NE(readText(apart + "/summary.json").find("\"nodes_in_element_sweep\": 0,"),
            std::string::npos);
  auto a = test::readCsv(apart + "/history.csv"), b = test::readCsv(fused + "/history.csv");
  ASSERT_EQ(a["time"], b["time"]);
  ASSERT_GT(a["time"].size(), 2u);
  for (size_t k = 0; k < a["time"].size(); ++k)
  {
    const Real scale = std::abs(a["kinetic"][k]) + std::abs(a["internal"][k]) +
                       std::abs(a["external_work"][k]) + std::abs(a["contact"][k]);
    for (const char *c : {"kinetic", "internal", "hourglass", "external_work", "contact"})
      EXPECT_NEAR(b[c][k], a[c][k], 1e-12 * scale) << c << " at row " << k;
  }
}

INSTANTIATE_TEST_SUITE_P(Decks, FusedNodeUpdate,
                         ::testing::Values("jointed_wave_1d.yaml", "block_impact_2d.yaml",
                                           "patch_2d.yaml", "merged_blocks_3d.yaml",
                                           "brick_stack_3d_sticky.yaml"),
                         [](const auto &info) {
                           std::string n = info.param;
                           return n.substr(0, n.find('.'));
                         });

// The node sweep has work on these decks (every node of the 1D wave touches a joint): nodes
// step 6 integrates, on one thread (one chunk) and on the test's threads.
TEST(FusedNodeUpdate, IntegratesTheInnerNodesInStepSix)
{
  for (const char *file :
       {"block_impact_2d.yaml", "merged_blocks_3d.yaml", "brick_stack_3d_sticky.yaml"})
  {
    Solver s(parseDeck(std::string(SCPDYN_SOURCE_DIR) + "/tests/parallel/decks/" + file));
    ASSERT_TRUE(s.nodeSweep().active) << file;
    auto runs = Kokkos::create_mirror_view_and_copy(HostSpace(), s.nodeSweep().runs);
    long early = 0;
    for (size_t k = 0; k < runs.extent(0); ++k)
      early += runs(k, 1) - runs(k, 0);
    EXPECT_GT(early, 0) << file;
    EXPECT_EQ(s.sweepNodeCount(), early) << file; // summary.json's nodes_in_element_sweep
    EXPECT_LT(early, s.nodes().count) << file;    // the contact, pressure and constrained nodes
  }
}

} // namespace
} // namespace scpdyn
