// The pre-flight block a run prints before its first cycle and summary.json's `preflight`: every
// part's mass against density x volume of its generated blocks (plane strain, axisymmetric, 3D),
// the sub-parts of a brick wall (grouped when there are many), many deck parts numbered alike,
// the sub-parts of a gmsh file's physical groups, the first time step against dt_min, and a
// two-rank run against the serial one.
#include "TestUtil.hpp"
#include "SummaryJson.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

using namespace scpdyn;
namespace fs = std::filesystem;

namespace
{

const std::string kWork = std::string(SCPDYN_TEST_WORKDIR) + "/preflight";

std::string deckFile(const std::string &name, const std::string &text)
{
  fs::create_directories(kWork);
  const std::string path = kWork + "/" + name + ".yaml";
  std::ofstream(path) << text;
  return path;
}

/// Runs `name`'s deck into its own directory; returns the directory, stdout in `out`.
std::string runDeck(const std::string &name, const std::string &text, std::string *out)
{
  const std::string dir = kWork + "/" + name;
  fs::remove_all(dir);
  std::string err;
  EXPECT_EQ(test::runBinary(deckFile(name, text) + " -o " + dir, &err,
                            "OMP_NUM_THREADS=1 OMP_PROC_BIND=false timeout 300", out),
            0)
      << err;
  return dir;
}

/// The lines of the block that start with `prefix`.
std::vector<std::string> linesStarting(const std::string &text, const std::string &prefix)
{
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (line.rfind(prefix, 0) == 0)
      lines.push_back(line);
  return lines;
}

/// A sum of a part's element masses, each density x volume to an ulp or so: a few ulps of the
/// part's mass per element, far above nothing and far below any real error.
double massTolerance(double mass, double elements) { return 4 * elements * 2.3e-16 * mass; }

// two blocks of different size and material, at rest (the time step stays the first one)
const std::string kTwoMaterials = R"(materials:
  - {name: ls, model: elastic, density: 2600, youngs_modulus: 43.875e9, poisson_ratio: 0.25}
  - {name: st, model: elastic, density: 7800, youngs_modulus: 200e9, poisson_ratio: 0.3}
)";

std::string twoBlocks2D(const std::string &geometry)
{
  return "dimension: 2\ngeometry: " + geometry + "\ntime: {end: 2.0e-6}\n" + kTwoMaterials +
         R"(parts:
  - {name: a, material: ls, mesh: {elements: [4, 4], size: [0.004, 0.004]}}
  - {name: b, material: st, mesh: {elements: [3, 2], origin: [0.004, 0.0], size: [0.006, 0.002]}}
)";
}

const std::string kTwoBlocks3D = "dimension: 3\ntime: {end: 2.0e-6}\n" + kTwoMaterials + R"(parts:
  - {name: a, material: ls, mesh: {elements: [4, 4, 2], size: [0.004, 0.004, 0.002]}}
  - {name: b, material: st, mesh: {elements: [3, 2, 1], origin: [0.004, 0.0, 0.0], size: [0.006, 0.002, 0.001]}}
)";

struct ExpectedPart
{
  std::string name, material;
  long elements;
  double mass;
};

void expectParts(const std::string &summary, const std::string &block,
                 const std::vector<ExpectedPart> &parts)
{
  double total = 0;
  long elements = 0;
  for (const ExpectedPart &p : parts)
  {
    SCOPED_TRACE(p.name);
    const std::vector<std::string> at{"preflight", "parts", p.name};
    auto path = [&](const std::string &key) {
      std::vector<std::string> v = at;
      v.push_back(key);
      return v;
    };
    EXPECT_EQ(test::jsonText(summary, path("material")), p.material);
    EXPECT_EQ(test::jsonNumber(summary, path("elements")), double(p.elements));
    EXPECT_NEAR(test::jsonNumber(summary, path("mass")), p.mass,
                massTolerance(p.mass, double(p.elements)));
    EXPECT_TRUE(test::jsonKeys(summary, path("sub_parts")).empty()) << "a block is one part";
    // its line of the block: name, material, elements, mass (to the 6 digits printed)
    const std::vector<std::string> lines = linesStarting(block, "  " + p.name + " ");
    ASSERT_EQ(lines.size(), 1u) << block;
    std::istringstream line(lines[0]);
    std::string name, material;
    long n = 0;
    double mass = 0;
    line >> name >> material >> n >> mass;
    EXPECT_EQ(material, p.material) << lines[0];
    EXPECT_EQ(n, p.elements) << lines[0];
    EXPECT_NEAR(mass, p.mass, 5e-6 * p.mass) << lines[0];
    total += p.mass;
    elements += p.elements;
  }
  EXPECT_NEAR(test::jsonNumber(summary, {"preflight", "mass"}), total,
              massTolerance(total, double(elements)));
  EXPECT_EQ(test::jsonNumber(summary, {"preflight", "elements"}), double(elements));
}

} // namespace

TEST(Preflight, MassPerPartIsDensityTimesVolumeOfItsBlock)
{
  const double rho_a = 2600, rho_b = 7800;
  struct Case
  {
    std::string name, deck, unit;
    double mass_a, mass_b;
  };
  const std::vector<Case> cases = {
      {"plane_strain", twoBlocks2D("plane_strain"), "kg per metre (plane strain)",
       rho_a * 0.004 * 0.004, rho_b * 0.006 * 0.002},
      // per radian: rho h (r_out^2 - r_in^2) / 2
      {"axisymmetric", twoBlocks2D("axisymmetric"), "kg per radian (axisymmetric)",
       rho_a * 0.004 * (0.004 * 0.004) / 2, rho_b * 0.002 * (0.010 * 0.010 - 0.004 * 0.004) / 2},
      {"3d", kTwoBlocks3D, "kg", rho_a * 0.004 * 0.004 * 0.002, rho_b * 0.006 * 0.002 * 0.001}};
  for (const Case &c : cases)
  {
    SCOPED_TRACE(c.name);
    std::string block;
    const std::string dir = runDeck("mass_" + c.name, c.deck, &block);
    const std::string s = test::readText(dir + "/summary.json");
    EXPECT_EQ(test::jsonText(s, {"preflight", "mass_unit"}), c.unit);
    EXPECT_NE(block.find("mass [" + c.unit + "]"), std::string::npos) << block;
    const bool three_d = c.name == "3d";
    expectParts(s, block, {{"a", "ls", three_d ? 32 : 16, c.mass_a}, {"b", "st", 6, c.mass_b}});
  }
}

TEST(Preflight, ABrickWallsBricksAreItsSubPartsGroupedWhenMany)
{
  // 10 bricks a course, 12 courses, every other one shifted by half a brick (a half brick at
  // each end): the bricks fill the wall's rectangle
  const double rho = 2600, width = 10 * 0.002, height = 12 * 0.001;
  const std::string deck = "dimension: 2\ntime: {end: 2.0e-6}\n" + kTwoMaterials + R"(parts:
  - {name: a, material: st, mesh: {elements: [2, 2], origin: [0, -0.002], size: [0.002, 0.002]}}
  - {name: wall, material: ls, mesh: {type: brick_wall, elements: [2, 2], brick_size: [0.002, 0.001], count: [10, 12]}}
)";
  std::string block;
  const std::string dir = runDeck("wall_many", deck, &block);
  const std::string s = test::readText(dir + "/summary.json");
  // the mesh parts of the wall: those of the `part` field (summary.json `parts`)
  std::vector<std::string> bricks;
  for (const std::string &k : test::jsonKeys(s, {"parts"}))
  {
    const std::string name = test::jsonText(s, {"parts", k});
    if (name.rfind("wall.", 0) == 0)
      bricks.push_back(name);
  }
  ASSERT_GT(bricks.size(), 8u) << "more than the block lists one by one";
  EXPECT_EQ(test::jsonKeys(s, {"preflight", "parts", "wall", "sub_parts"}), bricks);
  double mass = 0, elements = 0;
  for (const std::string &b : bricks)
  {
    mass += test::jsonNumber(s, {"preflight", "parts", "wall", "sub_parts", b, "mass"});
    elements += test::jsonNumber(s, {"preflight", "parts", "wall", "sub_parts", b, "elements"});
  }
  const double wall_mass = test::jsonNumber(s, {"preflight", "parts", "wall", "mass"});
  EXPECT_NEAR(wall_mass, rho * width * height, massTolerance(rho * width * height, elements));
  EXPECT_NEAR(mass, wall_mass, massTolerance(wall_mass, elements));
  EXPECT_EQ(test::jsonNumber(s, {"preflight", "parts", "wall", "elements"}), elements);
  // one line for the wall, naming the first and last brick; none of a brick of its own
  const std::vector<std::string> lines = linesStarting(block, "  wall ");
  ASSERT_EQ(lines.size(), 1u) << block;
  EXPECT_NE(lines[0].find(std::to_string(bricks.size()) + " sub-parts " + bricks.front() + " .. " +
                          bricks.back()),
            std::string::npos)
      << lines[0];
  EXPECT_NE(lines[0].find(" " + std::to_string(long(elements)) + " "), std::string::npos)
      << lines[0];
  EXPECT_TRUE(linesStarting(block, "    wall.").empty()) << block;
  EXPECT_LT(linesStarting(block, "  ").size(), 10u) << "a compact block:\n" << block;

  // a wall of a few bricks lists each on a line of its own, with its elements
  const std::string few =
      std::regex_replace(deck, std::regex("count: \\[10, 12\\]"), "count: [2, 2]");
  const std::string s_few = test::readText(runDeck("wall_few", few, &block) + "/summary.json");
  const std::vector<std::string> few_bricks =
      test::jsonKeys(s_few, {"preflight", "parts", "wall", "sub_parts"});
  ASSERT_GT(few_bricks.size(), 1u);
  ASSERT_LE(few_bricks.size(), 8u);
  for (const std::string &b : few_bricks)
  {
    const std::vector<std::string> brick_lines = linesStarting(block, "    " + b + " ");
    ASSERT_EQ(brick_lines.size(), 1u) << b << "\n" << block;
    const long n =
        long(test::jsonNumber(s_few, {"preflight", "parts", "wall", "sub_parts", b, "elements"}));
    EXPECT_NE(brick_lines[0].find(" " + std::to_string(n) + " "), std::string::npos)
        << brick_lines[0];
  }
}

TEST(Preflight, ManyDeckPartsNumberedAlikeAreOneLine)
{
  // 20 blocks b00 .. b19 in a row (a bar of blocks, as the paper's Fig. 2 decks have 100), and
  // an anvil of another material: more parts than the block lists one by one
  const int n = 20;
  std::string deck = "dimension: 2\ntime: {end: 2.0e-6}\n" + kTwoMaterials + "parts:\n";
  char line[256];
  for (int k = 0; k < n; ++k)
  {
    std::snprintf(line, sizeof line,
                  "  - {name: b%02d, material: ls, mesh: {elements: [2, 1], origin: [%.3f, 0], "
                  "size: [0.002, 0.001]}}\n",
                  k, 0.002 * k);
    deck += line;
  }
  deck += "  - {name: anvil, material: st, mesh: {elements: [4, 2], origin: [0, -0.002], size: "
          "[0.04, 0.002]}}\n";
  std::string block;
  const std::string s = test::readText(runDeck("many_parts", deck, &block) + "/summary.json");
  const std::vector<std::string> parts = test::jsonKeys(s, {"preflight", "parts"});
  ASSERT_EQ(parts.size(), size_t(n + 1)) << "summary.json lists every part";
  double mass = 0, elements = 0;
  for (int k = 0; k < n; ++k)
  {
    mass += test::jsonNumber(s, {"preflight", "parts", parts[size_t(k)], "mass"});
    elements += test::jsonNumber(s, {"preflight", "parts", parts[size_t(k)], "elements"});
  }
  const std::vector<std::string> lines = linesStarting(block, "  b00 .. b19 ");
  ASSERT_EQ(lines.size(), 1u) << block;
  std::istringstream in(lines[0].substr(std::string("  b00 .. b19 ").size()));
  std::string material;
  long shown_elements = 0;
  double shown_mass = 0;
  in >> material >> shown_elements >> shown_mass;
  EXPECT_EQ(material, "ls");
  EXPECT_EQ(double(shown_elements), elements);
  EXPECT_NEAR(shown_mass, mass, 5e-6 * mass) << "to the 6 digits printed";
  EXPECT_NEAR(mass, 2600 * n * 0.002 * 0.001, massTolerance(2600 * n * 0.002 * 0.001, elements));
  EXPECT_NE(lines[0].find("20 parts, 2 elements each"), std::string::npos) << lines[0];
  EXPECT_EQ(linesStarting(block, "  anvil ").size(), 1u) << block;
  EXPECT_TRUE(linesStarting(block, "  b01 ").empty()) << block;
}

TEST(Preflight, AGmshFilesPhysicalGroupsAreItsSubParts)
{
  if (std::system("gmsh --version > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "no gmsh";
  // [0,2]x[0,1] in 4 x 2 quads ("rock") and [2,3]x[0,1] in 2 x 2 ("fault")
  fs::create_directories(kWork);
  const std::string base = kWork + "/groups";
  std::ofstream(base + ".geo") << R"(
Point(1) = {0, 0, 0}; Point(2) = {2, 0, 0}; Point(3) = {2, 1, 0}; Point(4) = {0, 1, 0};
Point(5) = {3, 0, 0}; Point(6) = {3, 1, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {2, 5}; Line(6) = {5, 6}; Line(7) = {6, 3};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Curve Loop(2) = {-2, 5, 6, 7}; Plane Surface(2) = {2};
Transfinite Curve{1, 3} = 5; Transfinite Curve{2, 4, 5, 6, 7} = 3;
Transfinite Surface{1, 2}; Recombine Surface{1, 2};
Physical Surface("rock") = {1}; Physical Surface("fault") = {2};
)";
  ASSERT_EQ(std::system(("gmsh -2 " + base + ".geo -format msh41 -o " + base + ".msh > " + base +
                         ".log 2>&1")
                            .c_str()),
            0);
  const std::string deck = "dimension: 2\ntime: {end: 2.0e-3}\n" + kTwoMaterials +
                           "parts:\n  - {name: m, material: ls, mesh: {type: gmsh, file: " + base +
                           ".msh}}\n";
  std::string block;
  const std::string s = test::readText(runDeck("gmsh_groups", deck, &block) + "/summary.json");
  EXPECT_EQ(test::jsonKeys(s, {"preflight", "parts", "m", "sub_parts"}),
            (std::vector<std::string>{"m.rock", "m.fault"}));
  const struct
  {
    std::string name;
    long elements;
    double area;
  } groups[] = {{"m.rock", 8, 2.0}, {"m.fault", 4, 1.0}};
  for (const auto &g : groups)
  {
    const std::vector<std::string> at{"preflight", "parts", "m", "sub_parts", g.name};
    auto path = [&](const std::string &key) {
      std::vector<std::string> v = at;
      v.push_back(key);
      return v;
    };
    EXPECT_EQ(test::jsonNumber(s, path("elements")), double(g.elements)) << g.name;
    EXPECT_NEAR(test::jsonNumber(s, path("mass")), 2600 * g.area,
                massTolerance(2600 * g.area, double(g.elements)))
        << g.name;
    const std::vector<std::string> lines = linesStarting(block, "    " + g.name + " ");
    ASSERT_EQ(lines.size(), 1u) << block;
    EXPECT_NE(lines[0].find(" " + std::to_string(g.elements) + " "), std::string::npos) << lines[0];
  }
}

TEST(Preflight, TheFirstStepIsDtMinWhenNoLaterStepIsSmaller)
{
  // at rest the step stays the first one: the smallest is taken by cycle 0
  std::string block;
  const std::string dir = runDeck("first_dt", twoBlocks2D("plane_strain"), &block);
  const std::string s = test::readText(dir + "/summary.json");
  const auto h = test::readCsv(dir + "/history.csv");
  ASSERT_GT(h.at("dt").size(), 2u);
  ASSERT_EQ(h.at("dt")[1], *std::min_element(h.at("dt").begin() + 1, h.at("dt").end()));
  EXPECT_EQ(test::jsonText(s, {"dt_min", "cycle"}), "0");
  // the same double, printed the same way (round-trip digits)
  EXPECT_EQ(test::jsonText(s, {"preflight", "first_dt", "value"}),
            test::jsonText(s, {"dt_min", "value"}));
  EXPECT_EQ(test::jsonText(s, {"preflight", "first_dt", "control"}),
            test::jsonText(s, {"dt_min", "control"}));
  EXPECT_EQ(test::jsonText(s, {"preflight", "first_dt", "control"}), "elements (Courant)");
  // the block's estimate line names it too
  char dt[32];
  std::snprintf(dt, sizeof dt, "%.3e", test::jsonNumber(s, {"dt_min", "value"}));
  EXPECT_NE(block.find("(first dt " + std::string(dt) + " s, set by elements (Courant))"),
            std::string::npos)
      << block;
  EXPECT_GT(test::jsonNumber(s, {"preflight", "memory", "resident_bytes"}), 0);
  EXPECT_EQ(test::jsonNumber(s, {"preflight", "memory", "ranks"}), 1);
}

TEST(Preflight, TwoRanksGiveTheSerialMassesAndTheirMemory)
{
  if (std::system("command -v mpirun > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "no mpirun";
  std::string serial_block;
  const std::string serial =
      test::readText(runDeck("ranks_1", kTwoBlocks3D, &serial_block) + "/summary.json");
  const std::string dir = kWork + "/ranks_2";
  fs::remove_all(dir);
  // the variables of this test process's own MPI session would make mpirun join it
  const std::string cmd =
      "for v in $(env | grep -o -E '^(OMPI|PMIX|ORTE)_[A-Za-z0-9_]*' | grep -v ALLOW_RUN_AS_ROOT); "
      "do unset $v; done; OMP_NUM_THREADS=1 OMP_PROC_BIND=false timeout 300 mpirun -np 2 "
      "--oversubscribe " +
      std::string(SCPDYN_BINARY) + " " + deckFile("ranks_2", kTwoBlocks3D) + " -o " + dir + " > " +
      dir + ".out 2> " + dir + ".err";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << test::readText(dir + ".err");
  const std::string s = test::readText(dir + "/summary.json");
  const std::string block = test::readText(dir + ".out");
  EXPECT_EQ(linesStarting(block, "scpdyn: pre-flight").size(), 1u) << "rank 0 prints:\n" << block;
  for (const char *part : {"a", "b"})
  {
    const double elements = test::jsonNumber(serial, {"preflight", "parts", part, "elements"});
    const double mass = test::jsonNumber(serial, {"preflight", "parts", part, "mass"});
    EXPECT_EQ(test::jsonNumber(s, {"preflight", "parts", part, "elements"}), elements) << part;
    // the ranks' partial sums add in another order
    EXPECT_NEAR(test::jsonNumber(s, {"preflight", "parts", part, "mass"}), mass,
                massTolerance(mass, elements))
        << part;
  }
  EXPECT_EQ(test::jsonNumber(s, {"preflight", "memory", "ranks"}), 2);
  const double total = test::jsonNumber(s, {"preflight", "memory", "resident_bytes"});
  const double largest =
      test::jsonNumber(s, {"preflight", "memory", "resident_bytes_largest_rank"});
  EXPECT_GT(largest, 0);
  EXPECT_GT(total, largest) << "the sum of two ranks' memory";
  EXPECT_NE(block.find("over 2 ranks"), std::string::npos) << block;
}
