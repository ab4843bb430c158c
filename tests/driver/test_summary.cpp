// What summary.json tells a production run (docs/input.md, outputs): the build's commit, the
// deck's path, the smallest time step with the cycle that took it and what set it, and the
// final energies, checked against the run's own history.csv.
#include "TestUtil.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <regex>
#include <string>

using namespace scpdyn;
namespace fs = std::filesystem;

namespace
{

const std::string kWork = SCPDYN_TEST_WORKDIR;

/// The text of `"key": value` inside the object `"object": {...}` of a summary.json.
std::string field(const std::string &json, const std::string &object, const std::string &key)
{
  std::smatch m;
  const std::regex re("\"" + object + "\": \\{[^}]*?\"" + key + "\": (\"[^\"]*\"|[^,\\n]+)");
  return std::regex_search(json, m, re) ? m[1].str() : "";
}

std::string topField(const std::string &json, const std::string &key)
{
  std::smatch m;
  const std::regex re("\n  \"" + key + "\": (\"[^\"]*\"|[^,\\n]+)");
  return std::regex_search(json, m, re) ? m[1].str() : "";
}

const std::string kBlocks = R"(dimension: 2
time: {end: 2.0e-6, courant: 0.5}
output: {history_interval: 1.0e-12}
materials:
  - {name: ls, model: elastic, density: 2600, youngs_modulus: 43.875e9, poisson_ratio: 0.25}
parts:
  - {name: a, material: ls, mesh: {elements: [4, 4], size: [0.004, 0.004]}, initial_velocity: [1000.0, 0.0]}
  - {name: b, material: ls, mesh: {elements: [4, 4], origin: [0.004, 0.0], size: [0.004, 0.004]}}
)";

} // namespace

TEST(Summary, CommitDeckSmallestStepAndEnergiesOfTheRun)
{
  // without contact the elements set every step; with an explicit joint between the blocks,
  // touching at t = 0 at 1 km/s, the limit (19) sets the first one, 30x below the elements'
  const std::string contact = "contact:\n  surfaces:\n    - {name: j, part: \"*\", option: "
                              "explicit, a: 0.1, E0: 0.5, G: 0.3, C: 0.0, phi0: 38, phi1: 38}\n";
  for (bool joint : {false, true})
  {
    SCOPED_TRACE(joint ? "explicit joint" : "no contact");
    const std::string name = joint ? "summary_joint" : "summary_free";
    const std::string deck = test::writeWorkFile(name + ".yaml", kBlocks + (joint ? contact : ""));
    const std::string dir = kWork + "/" + name;
    ASSERT_EQ(test::runBinary(deck + " -o " + dir), 0);
    const std::string s = test::readText(dir + "/summary.json");

    EXPECT_EQ(topField(s, "deck"), "\"" + fs::absolute(deck).lexically_normal().string() + "\"");
    const std::string commit = topField(s, "commit");
    EXPECT_GT(commit.size(), 2u) << commit; // git describe, or the reason there is none
    // the smallest step: that of history.csv (a row every cycle: row c + 1 ends cycle c), and
    // what set it
    const auto h = test::readCsv(dir + "/history.csv");
    const auto &dt = h.at("dt");
    const auto least = std::min_element(dt.begin() + 1, dt.end()); // row 0: t = 0, no step yet
    EXPECT_DOUBLE_EQ(std::stod(field(s, "dt_min", "value")), *least);
    EXPECT_EQ(std::stol(field(s, "dt_min", "cycle")), long(least - dt.begin()) - 1);
    EXPECT_EQ(field(s, "dt_min", "control"),
              joint ? "\"contact (explicit joint limit 19)\"" : "\"elements (Courant)\"");
    // the final energies: the last row of history.csv
    for (const std::string q : {"kinetic", "internal", "hourglass", "contact", "external_work"})
      EXPECT_NEAR(std::stod(field(s, "energies", q)), h.at(q).back(),
                  1e-12 * std::abs(h.at("kinetic").front()))
          << q;
  }
}
