// rcforc.csv, spcforc.csv and matsum.csv of a decomposed run against the serial run's (np = 1,
// 2, 3, 4 in ctest): a CP counted once on two ranks, a shared node once, the node of two merged
// parts in one of them, and the ranks' sums agreeing with the serial sums to round-off.
#include "../TestUtil.hpp"
#include "ParallelTestUtil.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

using namespace scpdyn;
using namespace scpdyn::test;

namespace
{

std::string deckText(const std::string &name)
{
  return readText(std::string(SCPDYN_SOURCE_DIR) + "/tests/parallel/decks/" + name);
}

// A projectile into a wall held along its far side, each with its own contact surface; the
// pair takes sa's explicit option, so the time step (19) of CPs computed on two ranks is in
// the comparison (it took a ghost face's velocity a step old: 1e-2 off at 4 ranks).
const char *kWallDeck = R"(dimension: 2
time: {end: 3.0e-5}
materials:
  - {name: rock, density: 2600, youngs_modulus: 5.0e10, poisson_ratio: 0.25}
parts:
  - {name: a, material: rock, mesh: {elements: [6, 6], size: [0.02, 0.02]}, initial_velocity: [20, 1]}
  - {name: wall, material: rock, mesh: {elements: [5, 9], origin: [0.0201, -0.01], size: [0.015, 0.04]}}
node_sets:
  - {name: back, box: {min: [0.0351, -1], max: [0.0351, 1]}}
boundary_conditions:
  - {type: velocity, node_set: back, component: x, value: 0}
  - {type: velocity, node_set: back, component: y, value: 0}
contact:
  search_gap: 0.002
  surfaces:
    - {name: sa, part: a, option: explicit}
    - {name: sw, part: wall, option: implicit}
)";

/// The group a column is judged in: the components of one pair's forces, all the reactions
/// (a set held where the model is symmetric has a reaction of round-off), one part's energies,
/// one part's momentum: a value that stays at round-off beside the others of its group is not
/// a quantity of its own.
std::string groupOf(const std::string &column, bool reactions)
{
  const auto colon = column.find(':');
  if (reactions && colon != std::string::npos)
    return "reaction";
  const std::string q = colon == std::string::npos ? column : column.substr(colon + 1);
  return column.substr(0, colon) + (q.rfind("momentum", 0) == 0 ? ":momentum" : "");
}

/// Largest difference of file `b` from file `a` relative to the largest magnitude of the
/// column's group in `a`; 1e300 when the columns or the rows differ.
double worstDifference(const std::string &a_path, const std::string &b_path, std::string &where)
{
  const auto a = readCsv(a_path), b = readCsv(b_path);
  const bool reactions = a_path.find("spcforc") != std::string::npos;
  auto groupOf = [&](const std::string &c) { return ::groupOf(c, reactions); };
  if (a.empty() || a.size() != b.size())
    return where = "columns differ", 1e300;
  std::map<std::string, double> scale;
  for (const auto &[c, v] : a)
    for (double x : v)
      scale[groupOf(c)] = std::max(scale[groupOf(c)], std::fabs(x));
  double worst = 0;
  for (const auto &[c, v] : a)
  {
    const auto it = b.find(c);
    if (it == b.end() || it->second.size() != v.size())
      return where = c + " missing or rows differ", 1e300;
    for (size_t k = 0; k < v.size(); ++k)
    {
      const double e = std::fabs(v[k] - it->second[k]) / std::max(scale[groupOf(c)], 1e-300);
      if (!(e <= worst))
        worst = e, where = c;
    }
  }
  return worst;
}

void expectSameHistories(const std::string &yaml, const std::string &name,
                         const std::vector<std::string> &files)
{
  const std::string dir = std::string(SCPDYN_TEST_WORKDIR) + "/run_histories_np" +
                          std::to_string(mpiSize()) + "/" + name;
  if (mpiRank() == 0)
  {
    std::filesystem::remove_all(dir);
    Solver serial(deckFromText(yaml, name), MPI_COMM_SELF);
    serial.run(dir + "/serial");
  }
  MPI_Barrier(MPI_COMM_WORLD);
  Solver decomposed(deckFromText(yaml, name), MPI_COMM_WORLD);
  decomposed.run(dir + "/decomposed");
  if (mpiRank() != 0)
    return;
  for (const auto &f : files)
  {
    std::string where;
    const double worst = worstDifference(dir + "/serial/" + f, dir + "/decomposed/" + f, where);
    std::printf("[run histories] %s np %d %-12s worst relative difference %.3e (%s)\n",
                name.c_str(), mpiSize(), f.c_str(), worst, where.c_str());
    EXPECT_LT(worst, 1e-9) << name << " " << f << " " << where;
  }
}
} // namespace

TEST(RunHistoriesDecomposed, WallImpactAgreesWithTheSerialRun)
{
  expectSameHistories(kWallDeck, "wall_impact",
                      {"history.csv", "rcforc.csv", "spcforc.csv", "matsum.csv"});
}

TEST(RunHistoriesDecomposed, StickyBrickStackAgreesWithTheSerialRun)
{
  // sub-parts wall.C.K summed per deck part; base held in x, y, z; tied bricks
  expectSameHistories(deckText("brick_stack_3d_sticky.yaml"), "brick_stack",
                      {"rcforc.csv", "spcforc.csv", "matsum.csv"});
}

TEST(RunHistoriesDecomposed, MergedBlocksAgreeWithTheSerialRun)
{
  // the nodes merged between the parts may sit on several ranks: each counts in part a
  expectSameHistories(deckText("merged_blocks_3d.yaml"), "merged_blocks",
                      {"spcforc.csv", "matsum.csv"});
}
