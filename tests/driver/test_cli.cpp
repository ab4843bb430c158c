// The scpdyn command line as a user meets it: every broken deck in inputs/broken gives one
// clear error naming its key and exit status 2; a failing run exits 3 and keeps its outputs;
// results do not depend on the thread count.
#include "TestUtil.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <dirent.h>
#include <cstdio>
#include <fstream>
#include <sstream>

using namespace scpdyn;

namespace
{
std::vector<std::string> brokenDecks()
{
  const std::string dir = std::string(SCPDYN_SOURCE_DIR) + "/inputs/broken";
  std::vector<std::string> files;
  if (DIR *d = opendir(dir.c_str()))
  {
    while (dirent *e = readdir(d))
    {
      const std::string n = e->d_name;
      if (n.size() > 5 && n.substr(n.size() - 5) == ".yaml")
        files.push_back(dir + "/" + n);
    }
    closedir(d);
  }
  std::sort(files.begin(), files.end());
  return files;
}

/// the key path named on the deck's first line "# expect: <key path> ..."
std::string expectedKey(const std::string &file)
{
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  const std::string tag = "# expect:";
  if (line.compare(0, tag.size(), tag) != 0)
    return "";
  std::string rest = line.substr(tag.size());
  rest.erase(0, rest.find_first_not_of(' '));
  return rest.substr(0, rest.find(' '));
}
} // namespace

TEST(Cli, HelpAndVersion)
{
  std::string err;
  EXPECT_EQ(test::runBinary("--help", &err), 0);
  EXPECT_EQ(test::runBinary("--version", &err), 0);
  EXPECT_EQ(test::runBinary("", &err), 2);
  EXPECT_NE(err.find("usage"), std::string::npos);
  EXPECT_EQ(test::runBinary("no_such_deck.yaml", &err), 2);
  EXPECT_NE(err.find("no_such_deck.yaml"), std::string::npos) << err;
}

TEST(Cli, EveryBrokenDeckGivesItsErrorAndStatus2)
{
  const auto decks = brokenDecks();
  ASSERT_GE(decks.size(), 15u);
  for (const auto &deck : decks)
  {
    SCOPED_TRACE(deck);
    const std::string out = std::string(SCPDYN_TEST_WORKDIR) + "/broken_out";
    std::string err;
    const int status = test::runBinary(deck + " -o " + out, &err);
    EXPECT_EQ(status, 2) << err;
    EXPECT_NE(err.find("input error"), std::string::npos) << err;
    const std::string key = expectedKey(deck);
    ASSERT_FALSE(key.empty()) << "the deck's first line must be '# expect: <key path> ...'";
    EXPECT_NE(err.find(key), std::string::npos) << "expected key '" << key << "' in: " << err;
    // one line, no crash report
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  }
}

TEST(Cli, InvertedElementStopsWithStatus3AndKeepsOutputs)
{
  // the top of a block standing on a fixed base is driven down at 300 m/s: the 10 mm block is
  // flattened in 33 us (about 60 cycles), so an element inverts before the end time
  const std::string deck = test::writeWorkFile("crush.yaml", R"(
dimension: 2
time: {end: 1.0e-3, courant: 0.9}
materials:
  - {name: foam, model: elastic, density: 100, youngs_modulus: 1.0e9, poisson_ratio: 0.3}
parts:
  - {name: block, material: foam, mesh: {type: block, element: quad4, elements: [4, 4], size: [0.01, 0.01]}}
node_sets:
  - {name: top, box: {min: [0.0, 0.01], max: [0.01, 0.01]}}
  - {name: base, box: {min: [0.0, 0.0], max: [0.01, 0.0]}}
boundary_conditions:
  - {type: velocity, node_set: top, component: y, value: -300.0}
  - {type: velocity, node_set: base, component: y, value: 0.0}
)");
  const std::string out = std::string(SCPDYN_TEST_WORKDIR) + "/crush_out";
  std::string err;
  EXPECT_EQ(test::runBinary(deck + " -o " + out, &err), 3) << err;
  EXPECT_NE(err.find("inverted"), std::string::npos) << err;
  EXPECT_NE(test::readText(out + "/summary.json").find("\"failed\""), std::string::npos);
  EXPECT_TRUE(std::ifstream(out + "/fields.xmf").good());
  EXPECT_GT(test::readCsv(out + "/history.csv")["time"].size(), 1u);
}

TEST(Cli, OneAndTwoThreadsAgree)
{
  // a 2D scene with atomic scatter, which sums in another order on 2 threads, so gauges may
  // differ by round-off only: 1e-10 of each gauge's largest magnitude
  const std::string text =
      test::readText(std::string(SCPDYN_SOURCE_DIR) + "/inputs/examples/wall_pulse_2d.yaml");
  const std::string deck =
      test::writeWorkFile("wall_atomic.yaml", text + "numerics: {scatter: atomic}\n");
  const std::string o1 = std::string(SCPDYN_TEST_WORKDIR) + "/threads1";
  const std::string o2 = std::string(SCPDYN_TEST_WORKDIR) + "/threads2";
  ASSERT_EQ(test::runBinary(deck + " -o " + o1, nullptr, "OMP_NUM_THREADS=1 OMP_PROC_BIND=false"),
            0);
  ASSERT_EQ(test::runBinary(deck + " -o " + o2, nullptr, "OMP_NUM_THREADS=2 OMP_PROC_BIND=false"),
            0);
  auto g1 = test::readCsv(o1 + "/gauges.csv"), g2 = test::readCsv(o2 + "/gauges.csv");
  ASSERT_EQ(g1.size(), g2.size());
  ASSERT_GT(g1.size(), 4u);
  for (const auto &kv : g1)
  {
    const auto &a = kv.second, &b = g2[kv.first];
    ASSERT_EQ(a.size(), b.size());
    double scale = 0, diff = 0;
    for (size_t k = 0; k < a.size(); ++k)
    {
      scale = std::max(scale, std::abs(a[k]));
      diff = std::max(diff, std::abs(a[k] - b[k]));
    }
    std::printf("[threads] %-20s max |1T - 2T| = %.3e of %.3e\n", kv.first.c_str(), diff, scale);
    EXPECT_LE(diff, 1e-10 * scale) << kv.first;
  }
}

namespace
{
/// Runs the deck `text` at 1 and at 2 threads; every gauge must be the same bits. Returns the
/// gauge rows of the run.
size_t expectSameGaugesAtOneAndTwoThreads(const std::string &text, const std::string &name)
{
  const std::string deck = test::writeWorkFile(name + ".yaml", text);
  const std::string o1 = std::string(SCPDYN_TEST_WORKDIR) + "/" + name + "1";
  const std::string o2 = std::string(SCPDYN_TEST_WORKDIR) + "/" + name + "2";
  EXPECT_EQ(test::runBinary(deck + " -o " + o1, nullptr, "OMP_NUM_THREADS=1 OMP_PROC_BIND=false"),
            0);
  EXPECT_EQ(test::runBinary(deck + " -o " + o2, nullptr, "OMP_NUM_THREADS=2 OMP_PROC_BIND=false"),
            0);
  auto g1 = test::readCsv(o1 + "/gauges.csv"), g2 = test::readCsv(o2 + "/gauges.csv");
  for (const auto &kv : g1)
    EXPECT_EQ(kv.second, g2[kv.first]) << kv.first;
  return g1["time"].size();
}
} // namespace

TEST(Cli, GatherScatterIsBitwiseThreadIndependent)
{
  // the deterministic corner gather sums every node's corners in a fixed order
  std::string text =
      test::readText(std::string(SCPDYN_SOURCE_DIR) + "/inputs/examples/wall_pulse_2d.yaml");
  text += "numerics: {scatter: gather}\n";
  EXPECT_GT(expectSameGaugesAtOneAndTwoThreads(text, "wall_gather"), 10u);
}

TEST(Cli, GatherContactIsBitwiseThreadIndependent)
{
  // the joint CPs' shares summed at the nodes in CP order (ContactShares.cpp): a 3D brick wall
  // settling on quasi-implicit joints with the penetration weights, which amplify any round-off
  // by ~4 % a cycle (docs/theory.md 14.6: with atomic adds 1 and 2 threads part by 8e-3 within
  // 400 cycles), gives the gauges of one thread at two
  std::string text = test::readText(std::string(SCPDYN_SOURCE_DIR) +
                                    "/tests/parallel/decks/settling_wall_3d.yaml");
  for (size_t at; (at = text.find(", distribution: poc}")) != std::string::npos;)
    text.replace(at, std::string(", distribution: poc}").size(), "}");
  EXPECT_GE(expectSameGaugesAtOneAndTwoThreads(text, "wall_contact_gather"), 400u);
}

TEST(Cli, GatherConstraintsAreBitwiseThreadIndependent)
{
  // the velocity-constraint solves: their rows' nodal increments and forces summed in row order
  // (ContactShares.cpp) and their dot products exact (core/ExactSum.hpp). Before, with atomic
  // adds and thread-ordered sums, 1 and 2 threads parted by 1.0e-9 on the sticky stack and
  // 4.8e-12 on the incline (the bound solve with friction)
  const std::string dir = std::string(SCPDYN_SOURCE_DIR) + "/tests/parallel/decks/";
  EXPECT_GE(expectSameGaugesAtOneAndTwoThreads(test::readText(dir + "brick_stack_3d_sticky.yaml"),
                                               "stack_sticky_gather"),
            40u);
  EXPECT_GE(expectSameGaugesAtOneAndTwoThreads(test::readText(dir + "incline_friction_2d.yaml"),
                                               "incline_gather"),
            40u);
}

TEST(Cli, DashOWithoutADirectorySaysSo)
{
  std::string err;
  const std::string deck =
      test::writeWorkFile("cli_block.yaml", "dimension: 2\ntime: {end: 1.0e-5}\n"
                                            "materials: [{name: rock, density: 2600, "
                                            "youngs_modulus: 5.0e10, poisson_ratio: 0.25}]\n"
                                            "parts: [{name: block, material: rock, mesh: "
                                            "{elements: [4, 2], size: [0.04, 0.02]}}]\n");
  EXPECT_EQ(test::runBinary(deck + " -o", &err), 2);
  EXPECT_NE(err.find("-o needs a directory"), std::string::npos) << err;
  EXPECT_EQ(err.find("unknown option"), std::string::npos) << err;
}

TEST(Cli, PlainRunBindsThreadsWithoutKokkosWarning)
{
  // neither OMP_PROC_BIND nor OMP_PLACES set: Kokkos warned (on stdout) on every run
  const std::string deck = test::writeWorkFile(
      "cli_bind.yaml", "dimension: 2\ntime: {end: 1.0e-5}\n"
                       "materials: [{name: rock, density: 2600, youngs_modulus: 5.0e10, "
                       "poisson_ratio: 0.25}]\n"
                       "parts: [{name: block, material: rock, mesh: {elements: [4, 2], "
                       "size: [0.04, 0.02]}}]\n");
  const std::string out = std::string(SCPDYN_TEST_WORKDIR) + "/cli_bind";
  const std::string log = out + ".log";
  const std::string cmd = "env -u OMP_PROC_BIND -u OMP_PLACES OMP_NUM_THREADS=1 " +
                          std::string(SCPDYN_BINARY) + " " + deck + " -o " + out + " > " + log +
                          " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << test::readText(log);
  EXPECT_EQ(test::readText(log).find("OMP_PROC_BIND"), std::string::npos) << test::readText(log);
}

TEST(Cli, ProgressEndsWithTimeMaxCycles)
{
  // time.end 1 s is 1e6 cycles away; max_cycles 40 ends the run first, and the progress line
  // (every cycle: progress_interval 1 ns) must count towards that
  const std::string deck = test::writeWorkFile(
      "cli_eta.yaml", "dimension: 2\ntime: {end: 1.0, max_cycles: 40}\n"
                      "output: {progress_interval: 1.0e-9, history_interval: 1.0e-3}\n"
                      "materials: [{name: rock, density: 2600, youngs_modulus: 5.0e10, "
                      "poisson_ratio: 0.25}]\n"
                      "parts: [{name: block, material: rock, mesh: {elements: [4, 2], "
                      "size: [0.04, 0.02]}}]\n");
  std::string err;
  ASSERT_EQ(test::runBinary(deck + " -o " + std::string(SCPDYN_TEST_WORKDIR) + "/cli_eta", &err,
                            "OMP_NUM_THREADS=1 OMP_PROC_BIND=false"),
            0)
      << err;
  std::istringstream lines(err);
  int seen = 0;
  for (std::string line; std::getline(lines, line);)
  {
    long cycle = 0;
    double t = 0, dt = 0, percent = 0;
    if (std::sscanf(line.c_str(), "scpdyn: cycle %ld t = %lf s dt = %lf s %lf%%", &cycle, &t, &dt,
                    &percent) != 4)
      continue;
    ++seen;
    // the line prints one decimal: within 0.05 % of cycle / max_cycles
    EXPECT_NEAR(percent, 100.0 * double(cycle) / 40, 0.051) << line;
  }
  EXPECT_GE(seen, 20) << err;
}

TEST(Cli, RunScriptHelpAndTheDecksOutputDirectory)
{
  const std::string work = std::string(SCPDYN_TEST_WORKDIR) + "/run_script";
  const std::string script = std::string(SCPDYN_SOURCE_DIR) + "/scripts/run.sh";
  std::system(("rm -rf " + work + " && mkdir -p " + work).c_str());
  const std::string log = work + "/log.txt";
  // --help is the script's usage, not a deck named "--help"
  ASSERT_EQ(std::system(("bash " + script + " --help > " + log + " 2>&1").c_str()), 0)
      << test::readText(log);
  EXPECT_NE(test::readText(log).find("scripts/run.sh [DECK [scpdyn options]]"), std::string::npos)
      << test::readText(log);
  // without -o the deck's output.directory holds the results (relative to the working directory)
  test::writeWorkFile("run_script/deck_dir.yaml",
                      "dimension: 2\ntime: {end: 1.0e-5}\noutput: {directory: results/mine}\n"
                      "materials: [{name: rock, density: 2600, youngs_modulus: 5.0e10, "
                      "poisson_ratio: 0.25}]\n"
                      "parts: [{name: block, material: rock, mesh: {elements: [4, 2], "
                      "size: [0.04, 0.02]}}]\n");
  const std::string cmd = "cd " + work +
                          " && OMP_NUM_THREADS=1 OMP_PROC_BIND=false SCPDYN_BIN=" + SCPDYN_BINARY +
                          " bash " + script + " deck_dir.yaml > " + log + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << test::readText(log);
  EXPECT_TRUE(std::ifstream(work + "/results/mine/summary.json").good()) << test::readText(log);
  EXPECT_FALSE(std::ifstream(work + "/out/deck_dir/summary.json").good());
  EXPECT_NE(test::readText(log).find("results: results/mine"), std::string::npos)
      << test::readText(log);
}

// summary.json names the values of the `part` field (a brick wall's sub-parts), and the start
// line says "1 thread", not "1 threads".
TEST(Cli, SummaryNamesThePartsAndTheStartLineItsThreads)
{
  const std::string deck = test::writeWorkFile(
      "part_names.yaml", "dimension: 2\ntime: {end: 1.0e-6}\n"
                         "materials: [{name: rock, density: 2600, youngs_modulus: 5.0e10, "
                         "poisson_ratio: 0.25}]\n"
                         "parts: [{name: wall, material: rock, mesh: {type: brick_wall, "
                         "brick_size: [0.2, 0.1], count: [2, 2]}}]\n");
  const std::string out = std::string(SCPDYN_TEST_WORKDIR) + "/part_names";
  std::string err;
  ASSERT_EQ(test::runBinary(deck + " -o " + out, &err, "OMP_NUM_THREADS=1"), 0) << err;
  const std::string summary = test::readText(out + "/summary.json");
  EXPECT_NE(summary.find("\"0\": \"wall.0.0\""), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"wall.1.2\""), std::string::npos) << summary; // staggered course
  EXPECT_NE(err.find(" 1 thread -> "), std::string::npos) << err;
}
