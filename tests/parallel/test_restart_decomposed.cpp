// Restart files of decomposed runs (docs/input.md, `output`): a run continued at the rank
// count that wrote the file is the uninterrupted run bit for bit (its rows and frames after the
// restart cycle in another directory; every file it continues in its own); a file written at one rank count and
// read at another (np - 1 -> np and np -> np - 1) gives the uninterrupted run's rows to round-off
// (1e-9 of each column's largest magnitude, the rank-count invariance of the solver); a bad file
// is refused on every rank together. The deck: two blocks meeting at a quasi-implicit joint
// with its histories, searched every 2 cycles, CPs and a joint gauge on several ranks; an
// explicit joint; a sleepy wall with a slide line.
#include "../TestUtil.hpp"
#include "Hdf5Frames.hpp"
#include "ParallelTestUtil.hpp"

#include "core/InputError.hpp"
#include "driver/Solver.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

using namespace scpdyn;
using namespace scpdyn::test;
namespace fs = std::filesystem;

namespace
{

const char *const kCsvFiles[] = {"history.csv", "gauges.csv", "rcforc.csv", "matsum.csv"};

/// tests/parallel/decks/<name>.yaml with restart files at half its end time.
std::string deckWithRestarts(const std::string &name)
{
  std::string text =
      readText(std::string(SCPDYN_SOURCE_DIR) + "/tests/parallel/decks/" + name + ".yaml");
  const std::string key = "\ntime: {end: ";
  const size_t at = text.find(key);
  const double end = std::stod(text.substr(at + key.size()));
  std::ostringstream output;
  output.precision(17);
  output << "\noutput: {restart_interval: " << 0.5 * end << ", field_interval: " << 0.2 * end
         << ", restart_keep: 10}";
  text.insert(text.find('\n', at + 1), output.str());
  return text;
}

/// Rank 0's `text` on every rank.
std::string broadcastText(const std::string &text)
{
  const std::vector<char> v = broadcastFromRoot(std::vector<char>(text.begin(), text.end()));
  return std::string(v.begin(), v.end());
}

/// `text` stopped at `cycle` (time.max_cycles, which a restart may change).
std::string stoppedAt(std::string text, long cycle)
{
  const std::string key = "\ntime: {";
  text.replace(text.find(key), key.size(), key + "max_cycles: " + std::to_string(cycle) + ", ");
  return text;
}

/// The first ranks of MPI_COMM_WORLD, or MPI_COMM_NULL on the others (collective).
MPI_Comm firstRanks(int count)
{
  MPI_Comm sub = MPI_COMM_NULL;
  MPI_Comm_split(MPI_COMM_WORLD, mpiRank() < count ? 0 : MPI_UNDEFINED, mpiRank(), &sub);
  return sub;
}

/// `yaml` run on the first `ranks` ranks into `dir` (from `restart` when given); collective.
void runOn(int ranks, const std::string &yaml, const std::string &dir,
           const std::string &restart = "")
{
  MPI_Comm comm = firstRanks(ranks);
  if (comm != MPI_COMM_NULL)
  {
    Solver solver(deckFromText(yaml, "restart_deck"), comm);
    solver.run(dir, restart);
    MPI_Comm_free(&comm);
  }
  MPI_Barrier(MPI_COMM_WORLD);
}

/// The restart file of `dir` at the smallest cycle (the half-time one); empty if none.
std::string firstRestartFile(const std::string &dir)
{
  const std::vector<std::string> files = restartFiles(dir);
  return files.empty() ? std::string() : files.front();
}

/// The columns judged on one scale: a gauge's quantities, a pair's forces, a part's energies,
/// a part's momentum, the model's momentum (a component that stays at round-off beside the
/// others, a symmetric model's, is not a quantity of its own); else the column alone.
std::string groupOf(const std::string &column)
{
  const size_t colon = column.find(':');
  const std::string q = colon == std::string::npos ? column : column.substr(colon + 1);
  const std::string momentum = q.rfind("momentum", 0) == 0 ? ":momentum" : "";
  if (colon == std::string::npos)
    return momentum.empty() ? column : momentum;
  return column.substr(0, colon) + momentum;
}

std::vector<std::string> cells(const std::string &line)
{
  std::vector<std::string> out;
  std::stringstream s(line);
  for (std::string cell; std::getline(s, cell, ',');)
    out.push_back(cell);
  return out;
}

/// Of the restarted run's rows (its last ones are the uninterrupted run's last ones): the
/// largest difference from the uninterrupted run's row of that cycle relative to the largest
/// magnitude of the column's group (groupOf()) in the uninterrupted run; `bitwise` stays true
/// while the rows' text is the same. 1e300 when the rows or columns differ.
double worstRowDifference(const std::string &full_path, const std::string &restarted_path,
                          bool &bitwise)
{
  const std::vector<std::string> full = lines(full_path), re = lines(restarted_path);
  if (re.size() < 2 || re.size() > full.size() || re.front() != full.front())
    return 1e300;
  const std::vector<std::string> header = cells(full.front());
  std::map<std::string, double> scale;
  for (size_t r = 1; r < full.size(); ++r)
  {
    const std::vector<std::string> v = cells(full[r]);
    for (size_t c = 0; c < v.size() && c < header.size(); ++c)
      scale[groupOf(header[c])] =
          std::max(scale[groupOf(header[c])], std::fabs(std::strtod(v[c].c_str(), nullptr)));
  }
  const size_t rows = re.size() - 1;
  double worst = 0;
  for (size_t r = 0; r < rows; ++r)
  {
    const std::string &a = full[full.size() - rows + r], &b = re[1 + r];
    bitwise = bitwise && a == b;
    const std::vector<std::string> va = cells(a), vb = cells(b);
    if (va.size() != vb.size() || va.size() != header.size())
      return 1e300;
    for (size_t c = 0; c < va.size(); ++c)
      worst = std::max(worst, std::fabs(std::strtod(va[c].c_str(), nullptr) -
                                        std::strtod(vb[c].c_str(), nullptr)) /
                                  std::max(scale[groupOf(header[c])], 1e-300));
  }
  return worst;
}

/// Rank 0: every CSV of `restarted` against `full`; bitwise or within `tolerance`.
void expectRows(const std::string &full, const std::string &restarted, bool bitwise_expected,
                double tolerance, const std::string &what)
{
  if (mpiRank() != 0)
    return;
  for (const char *csv : kCsvFiles)
  {
    if (!fs::exists(full + "/" + csv))
      continue;
    bool bitwise = true;
    const double worst = worstRowDifference(full + "/" + csv, restarted + "/" + csv, bitwise);
    std::printf("[restart decomposed] %s %-12s %s, worst relative difference %.3e\n", what.c_str(),
                csv, bitwise ? "bitwise" : "not bitwise", worst);
    if (bitwise_expected)
      EXPECT_TRUE(bitwise) << what << " " << csv;
    EXPECT_LE(worst, tolerance) << what << " " << csv;
  }
}

/// Rank 0: every frame of the field and contact files of `b` is the frame of that cycle in
/// `a` (`a`'s last frames; all of them when `b` continued `a`'s files), every dataset bit for bit.
void expectSameFrames(const std::string &a, const std::string &b, const std::string &what)
{
  if (mpiRank() != 0)
    return;
  for (const char *h5 : {"fields.h5", "contacts.h5"})
  {
    const std::string fa = a + "/" + h5, fb = b + "/" + h5;
    if (!fs::exists(fa))
      continue;
    const hsize_t na = frameCount(fa), nb = frameCount(fb);
    ASSERT_GE(nb, 2u) << what << " " << h5;
    ASSERT_LE(nb, na) << what << " " << h5;
    for (hsize_t k = 0; k < nb; ++k)
    {
      const auto da = datasetBytes(fa, "frames/" + std::to_string(na - nb + k));
      const auto db = datasetBytes(fb, "frames/" + std::to_string(k));
      ASSERT_FALSE(da.empty()) << what << " " << h5;
      ASSERT_EQ(da.size(), db.size()) << what << " " << h5;
      for (size_t d = 0; d < da.size(); ++d)
        EXPECT_TRUE(da[d].first == db[d].first && da[d].second == db[d].second)
            << what << " " << h5 << " frame " << k << ": " << da[d].first;
    }
  }
}

/// Rank 0: the whole text of the CSVs and fields.xmf of `b` is `a`'s, and so are its frames.
void expectSameOutputs(const std::string &a, const std::string &b, const std::string &what)
{
  if (mpiRank() != 0)
    return;
  for (const char *f :
       {"history.csv", "gauges.csv", "rcforc.csv", "matsum.csv", "fields.xmf", "contacts.xmf"})
    if (fs::exists(a + "/" + f))
      EXPECT_TRUE(readText(a + "/" + f) == readText(b + "/" + f)) << what << ": " << f;
  ASSERT_EQ(frameCount(a + "/fields.h5"), frameCount(b + "/fields.h5")) << what;
  expectSameFrames(a, b, what);
}

std::string workDir(const std::string &name)
{
  const std::string dir =
      std::string(SCPDYN_TEST_WORKDIR) + "/restart_np" + std::to_string(mpiSize()) + "/" + name;
  if (mpiRank() == 0)
    fs::remove_all(dir);
  MPI_Barrier(MPI_COMM_WORLD);
  return dir;
}

} // namespace

class RestartDecomposed : public ::testing::TestWithParam<const char *>
{
};

TEST_P(RestartDecomposed, SameRankCountContinuesBitwise)
{
  const int np = mpiSize();
  const std::string dir = workDir(std::string("same_") + GetParam());
  const std::string yaml = deckWithRestarts(GetParam());
  runOn(np, yaml, dir + "/full");
  const std::string half = broadcastText(firstRestartFile(dir + "/full"));
  ASSERT_FALSE(half.empty());
  runOn(np, yaml, dir + "/restarted", half);
  const std::string what = std::string(GetParam()) + " np " + std::to_string(np);
  expectRows(dir + "/full", dir + "/restarted", true, 0.0, what);
  expectSameFrames(dir + "/full", dir + "/restarted", what);

  // in place: a run stopped at the restart cycle, continued in its own directory
  const long cycle = std::stol(fs::path(half).filename().string().substr(8));
  runOn(np, stoppedAt(yaml, cycle), dir + "/stopped");
  runOn(np, yaml, dir + "/stopped", dir + "/stopped/" + fs::path(half).filename().string());
  expectSameOutputs(dir + "/full", dir + "/stopped", "in place, " + what);
}

TEST_P(RestartDecomposed, AnotherRankCountContinuesToRoundOff)
{
  const int np = mpiSize();
  if (np < 2)
    GTEST_SKIP() << "needs two ranks";
  const std::string dir = workDir(std::string("across_") + GetParam());
  const std::string yaml = deckWithRestarts(GetParam());
  // the uninterrupted runs at np and np - 1 ranks, each leaving its restart files
  runOn(np, yaml, dir + "/full_np");
  runOn(np - 1, yaml, dir + "/full_fewer");
  const std::string from_np = broadcastText(firstRestartFile(dir + "/full_np"));
  const std::string from_fewer = broadcastText(firstRestartFile(dir + "/full_fewer"));
  runOn(np, yaml, dir + "/more", from_fewer);
  runOn(np - 1, yaml, dir + "/fewer", from_np);
  // 1e-9: the rank-count invariance of the uninterrupted runs (RunHistoriesDecomposed)
  const std::string n = std::to_string(np), m = std::to_string(np - 1), deck = GetParam();
  expectRows(dir + "/full_np", dir + "/more", false, 1e-9, deck + " " + m + " -> " + n + " ranks");
  expectRows(dir + "/full_fewer", dir + "/fewer", false, 1e-9,
             deck + " " + n + " -> " + m + " ranks");
}

// decks whose cycles read contact histories: a quasi-implicit joint, an explicit one (its time
// step from the CPs' approach), a sleepy wall with plasticity and a slide line, a slide line on
// faces that erosion exposes (restart while the plate erodes), the search gap from the motion
// (its motion bound and gap carried over)
INSTANTIATE_TEST_SUITE_P(ContactDecks, RestartDecomposed,
                         ::testing::Values("block_impact_2d", "explicit_touching_2d",
                                           "sleepy_wall_2d", "eroding_plate_2d",
                                           "released_impact_motion_2d"));

TEST(RestartDecomposedFile, BadFileIsRefusedOnEveryRank)
{
  const std::string dir = workDir("bad");
  const std::string yaml = deckWithRestarts("block_impact_2d");
  runOn(mpiSize(), yaml, dir + "/full");
  const std::string good = broadcastText(firstRestartFile(dir + "/full"));
  const std::string cut = dir + "/truncated.h5";
  if (mpiRank() == 0)
  {
    const std::string bytes = readText(good);
    std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  std::string message;
  try
  {
    Solver solver(deckFromText(yaml, "restart_deck"), MPI_COMM_WORLD);
    solver.run(dir + "/cut", cut);
  }
  catch (const InputError &e)
  {
    message = e.what();
  }
  EXPECT_NE(message.find("restart file '" + cut + "': truncated or corrupt"), std::string::npos)
      << message;
  MPI_Barrier(MPI_COMM_WORLD); // every rank got here: none is left in a collective
}
