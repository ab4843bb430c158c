// Restart files (README, "Running a deck"; docs/input.md, `output`): a run continued from the
// restart file written at half time is the uninterrupted run bit for bit at one thread (its
// rows and frames after the restart cycle), on decks whose cycles read contact
// histories (a sleepy wall with plasticity and a slide line; an implicit and an explicit
// joint); a run stopped by SIGTERM leaves a restart file that continues to the uninterrupted
// run's state; a restart file of another deck, a truncated one and one of another format version
// are refused with exit status 2 and a one-line cause.
#include "Hdf5Frames.hpp"
#include "StartedProcess.hpp"
#include "TestUtil.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

using namespace scpdyn;
using namespace scpdyn::test;
namespace fs = std::filesystem;

namespace
{

const std::string kWork = std::string(SCPDYN_TEST_WORKDIR) + "/restart";
const std::string kEnv = "OMP_NUM_THREADS=1 OMP_PROC_BIND=false";

/// The deck tests/parallel/decks/<name>.yaml with restart files at half its end time.
std::string deckWithRestarts(const std::string &name, const std::string &dir)
{
  std::string text =
      readText(std::string(SCPDYN_SOURCE_DIR) + "/tests/parallel/decks/" + name + ".yaml");
  const std::string key = "\ntime: {end: ";
  const size_t at = text.find(key);
  EXPECT_NE(at, std::string::npos) << name;
  const double end = std::stod(text.substr(at + key.size()));
  std::ostringstream output;
  output.precision(17);
  output << "\noutput: {restart_interval: " << 0.5 * end << ", field_interval: " << 0.2 * end
         << ", restart_keep: 10}";
  text.insert(text.find('\n', at + 1), output.str());
  fs::create_directories(dir);
  const std::string path = dir + "/" + name + ".yaml";
  std::ofstream(path) << text;
  return path;
}

/// The cycle of restart file `path` (restart_<cycle>.h5).
long cycleOf(const std::string &path)
{
  return std::stol(fs::path(path).filename().string().substr(8));
}

/// `deck` stopped at `cycle` (time.max_cycles, which a restart may change), as `path`.
std::string stoppedAt(const std::string &deck, long cycle, const std::string &path)
{
  std::string text = readText(deck);
  const std::string key = "\ntime: {";
  text.replace(text.find(key), key.size(), key + "max_cycles: " + std::to_string(cycle) + ", ");
  std::ofstream(path) << text;
  return path;
}

/// The outputs a run continues (docs/input.md, `output`).
const char *const kContinuedFiles[] = {"history.csv",  "gauges.csv", "rcforc.csv",
                                       "spcforc.csv",  "matsum.csv", "fields.xmf",
                                       "contacts.xmf", "fields.h5",  "contacts.h5"};

/// Every output file of `b` is `a`'s: the CSV and XDMF text byte for byte, the HDF5 files'
/// frames (their count, every dataset of every frame bit for bit) and mesh.
void expectSameOutputs(const std::string &a, const std::string &b)
{
  for (const std::string f : kContinuedFiles)
  {
    const std::string pa = a + "/" + f, pb = b + "/" + f;
    ASSERT_EQ(fs::exists(pa), fs::exists(pb)) << pb;
    if (!fs::exists(pa))
      continue;
    if (fs::path(f).extension() != ".h5")
    {
      EXPECT_TRUE(readText(pa) == readText(pb)) << pb << " differs from " << pa;
      continue;
    }
    const hsize_t frames = frameCount(pa);
    ASSERT_EQ(frameCount(pb), frames) << pb;
    std::vector<std::string> groups;
    if (f == std::string("fields.h5"))
      groups.push_back("mesh");
    for (hsize_t k = 0; k < frames; ++k)
      groups.push_back("frames/" + std::to_string(k));
    for (const std::string &g : groups)
    {
      const auto da = datasetBytes(pa, g), db = datasetBytes(pb, g);
      ASSERT_FALSE(da.empty()) << pa << ":" << g;
      ASSERT_EQ(da.size(), db.size()) << pb << ":" << g;
      for (size_t d = 0; d < da.size(); ++d)
      {
        EXPECT_EQ(da[d].first, db[d].first) << pb << ":" << g;
        EXPECT_TRUE(da[d].second == db[d].second) << pb << ":" << g << "/" << da[d].first;
      }
    }
  }
}

class RestartBitwise : public ::testing::TestWithParam<const char *>
{
};

TEST_P(RestartBitwise, ContinuesAsTheUninterruptedRun)
{
  const std::string name = GetParam();
  const std::string dir = kWork + "/bitwise_" + name;
  fs::remove_all(dir);
  const std::string deck = deckWithRestarts(name, dir);
  std::string err;
  ASSERT_EQ(runBinary(deck + " -o " + dir + "/full", &err, kEnv), 0) << err;
  const std::vector<std::string> files = restartFiles(dir + "/full");
  ASSERT_GE(files.size(), 2u) << "one at half time, one at the end";
  ASSERT_EQ(runBinary(deck + " -o " + dir + "/restarted --restart " + files.front(), &err, kEnv), 0)
      << err;
  // every row the restarted run writes is the uninterrupted run's row of that cycle, bit for bit
  for (const char *csv : {"history.csv", "gauges.csv", "rcforc.csv", "matsum.csv", "spcforc.csv"})
  {
    const std::string full_path = dir + "/full/" + csv;
    if (!fs::exists(full_path))
      continue;
    const std::vector<std::string> full = lines(full_path);
    const std::vector<std::string> restarted = lines(dir + "/restarted/" + csv);
    ASSERT_GE(restarted.size(), 2u) << csv;
    ASSERT_LE(restarted.size(), full.size()) << csv;
    EXPECT_EQ(restarted.front(), full.front()) << csv << ": header";
    const size_t rows = restarted.size() - 1;
    for (size_t r = 0; r < rows; ++r)
      EXPECT_EQ(restarted[1 + r], full[full.size() - rows + r]) << csv << " row " << r;
  }
  // every frame the restarted run writes is the uninterrupted run's frame of that cycle: every
  // dataset, bit for bit
  for (const char *h5 : {"fields.h5", "contacts.h5"})
  {
    const std::string full_file = dir + "/full/" + h5, re_file = dir + "/restarted/" + h5;
    if (!fs::exists(full_file))
      continue;
    const hsize_t full_frames = frameCount(full_file), re_frames = frameCount(re_file);
    ASSERT_GE(re_frames, 2u) << h5;
    ASSERT_LT(re_frames, full_frames) << h5;
    for (hsize_t k = 0; k < re_frames; ++k)
    {
      const auto a =
          datasetBytes(full_file, "frames/" + std::to_string(full_frames - re_frames + k));
      const auto b = datasetBytes(re_file, "frames/" + std::to_string(k));
      ASSERT_FALSE(a.empty()) << h5;
      ASSERT_EQ(a.size(), b.size()) << h5;
      for (size_t d = 0; d < a.size(); ++d)
      {
        EXPECT_EQ(a[d].first, b[d].first) << h5;
        EXPECT_TRUE(a[d].second == b[d].second) << h5 << " frame " << k << ": " << a[d].first;
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(ContactDecks, RestartBitwise,
                         ::testing::Values("sleepy_wall_2d", "block_impact_2d",
                                           "explicit_touching_2d"));

class RestartInPlace : public ::testing::TestWithParam<const char *>
{
};

TEST_P(RestartInPlace, ContinuesTheOutputsOfItsDirectoryAsTheUninterruptedRun)
{
  const std::string name = GetParam();
  const std::string dir = kWork + "/in_place_" + name;
  fs::remove_all(dir);
  const std::string deck = deckWithRestarts(name, dir);
  std::string err;
  ASSERT_EQ(runBinary(deck + " -o " + dir + "/full", &err, kEnv), 0) << err;
  const std::string half = fs::path(restartFiles(dir + "/full").front()).filename().string();
  const long cycle = cycleOf(half);

  // a run stopped at the half-time restart file's cycle (its last frame and rows at that cycle
  // are not the uninterrupted run's, unless due), continued in its own directory
  const std::string stopped = stoppedAt(deck, cycle, dir + "/stopped.yaml");
  ASSERT_EQ(runBinary(stopped + " -o " + dir + "/stopped", &err, kEnv), 0) << err;
  ASSERT_TRUE(fs::exists(dir + "/stopped/" + half));
  ASSERT_EQ(
      runBinary(deck + " -o " + dir + "/stopped --restart " + dir + "/stopped/" + half, &err, kEnv),
      0)
      << err;
  EXPECT_NE(err.find("continuing the outputs in " + dir + "/stopped after cycle " +
                     std::to_string(cycle)),
            std::string::npos)
      << err;
  expectSameOutputs(dir + "/full", dir + "/stopped");

  // the uninterrupted run's own directory continued from half time: the rows and frames after
  // it are dropped and written again, the same
  fs::copy(dir + "/full", dir + "/rewound", fs::copy_options::recursive);
  ASSERT_EQ(
      runBinary(deck + " -o " + dir + "/rewound --restart " + dir + "/rewound/" + half, &err, kEnv),
      0)
      << err;
  expectSameOutputs(dir + "/full", dir + "/rewound");

  // a directory of another run (one that ended before the restart file's cycle): refused, and
  // its files are left as they were
  const std::string early = stoppedAt(deck, cycle / 2, dir + "/early.yaml");
  ASSERT_EQ(runBinary(early + " -o " + dir + "/early", &err, kEnv), 0) << err;
  const std::string before = readText(dir + "/early/history.csv");
  EXPECT_EQ(
      runBinary(deck + " -o " + dir + "/early --restart " + dir + "/full/" + half, &err, kEnv), 2);
  EXPECT_NE(err.find("cannot continue '" + dir + "/early/"), std::string::npos) << err;
  EXPECT_EQ(readText(dir + "/early/history.csv"), before);
}

INSTANTIATE_TEST_SUITE_P(ContactDecks, RestartInPlace,
                         ::testing::Values("sleepy_wall_2d", "block_impact_2d",
                                           "explicit_touching_2d"));

TEST(RestartFile, BadFilesAreRefusedWithTheirCause)
{
  const std::string dir = kWork + "/bad_files";
  fs::remove_all(dir);
  const std::string deck = deckWithRestarts("block_impact_2d", dir);
  std::string err;
  ASSERT_EQ(runBinary(deck + " -o " + dir + "/full", &err, kEnv), 0) << err;
  const std::string good = restartFiles(dir + "/full").front();

  // another deck: the same mesh with another joint aperture
  std::string other = readText(deck);
  other.replace(other.find("a: 0.2"), 6, "a: 0.3");
  const std::string other_deck = dir + "/other.yaml";
  std::ofstream(other_deck) << other;
  EXPECT_EQ(runBinary(other_deck + " -o " + dir + "/other --restart " + good, &err, kEnv), 2);
  EXPECT_NE(err.find("restart file '" + good + "': written by another deck"), std::string::npos)
      << err;

  // truncated: the first half of the file
  const std::string cut = dir + "/truncated.h5";
  {
    const std::string bytes = readText(good);
    std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  }
  EXPECT_EQ(runBinary(deck + " -o " + dir + "/cut --restart " + cut, &err, kEnv), 2);
  EXPECT_NE(err.find("restart file '" + cut + "': "), std::string::npos) << err;
  EXPECT_NE(err.find("truncated or corrupt"), std::string::npos) << err;

  // another format version
  const std::string version = dir + "/version.h5";
  fs::copy_file(good, version);
  {
    const hid_t f = H5Fopen(version.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    const hid_t a = H5Aopen(f, "format_version", H5P_DEFAULT);
    const long v = 999;
    H5Awrite(a, H5T_NATIVE_LONG, &v);
    H5Aclose(a);
    H5Fclose(f);
  }
  EXPECT_EQ(runBinary(deck + " -o " + dir + "/version --restart " + version, &err, kEnv), 2);
  EXPECT_NE(err.find("restart file '" + version + "': file-format version 999"), std::string::npos)
      << err;
}

TEST(RestartFile, KeepsTheNewestFiles)
{
  const std::string dir = kWork + "/keep";
  fs::remove_all(dir);
  std::string text = readText(deckWithRestarts("block_impact_2d", dir));
  text = std::regex_replace(text, std::regex("restart_keep: 10"), "restart_keep: 1");
  const std::string deck = dir + "/keep.yaml";
  std::ofstream(deck) << text;
  std::string err;
  ASSERT_EQ(runBinary(deck + " -o " + dir + "/out", &err, kEnv), 0) << err;
  const std::vector<std::string> files = restartFiles(dir + "/out");
  ASSERT_EQ(files.size(), 1u);
  for (const auto &e : fs::directory_iterator(dir + "/out"))
    EXPECT_EQ(e.path().extension().string() == ".tmp", false) << e.path();
}

TEST(RestartFile, SigtermLeavesAFileThatContinuesTheRun)
{
  // The signalled run would take hours (time.end 1 s), so the signal always comes first; the
  // restarted and the reference runs stop at the same cycle past the restart with
  // time.max_cycles, which a restart file's deck may change.
  const std::string dir = kWork + "/sigterm";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::string text =
      readText(std::string(SCPDYN_SOURCE_DIR) + "/tests/parallel/decks/block_impact_2d.yaml");
  const std::string key = "\ntime: {end: ";
  const size_t at = text.find(key);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, text.find('\n', at + 1) - at, key + "1.0, courant: 0.25}");
  const std::string long_deck = dir + "/long.yaml";
  std::ofstream(long_deck) << text;

  const Started run = start({SCPDYN_BINARY, long_deck, "-o", dir + "/signalled"},
                            dir + "/signalled", {}, {"OMP_NUM_THREADS=1", "OMP_PROC_BIND=false"});
  // generous bounds: they only end a test that would otherwise hang
  ASSERT_TRUE(waitForFile(run.pid, dir + "/signalled/fields.xmf", 300)) << readText(run.err);
  kill(run.pid, SIGTERM);
  const int status = waitForExit(run.pid, 300);
  ASSERT_TRUE(WIFEXITED(status)) << readText(run.err);
  ASSERT_EQ(WEXITSTATUS(status), 143) << readText(run.err);
  const std::vector<std::string> files = restartFiles(dir + "/signalled");
  ASSERT_EQ(files.size(), 1u) << readText(run.err);
  const std::string name = fs::path(files[0]).filename().string();
  const long cycle = std::stol(name.substr(8));

  const size_t t = text.find(key);
  text.replace(t, text.find('\n', t + 1) - t,
               key + "1.0, courant: 0.25, max_cycles: " + std::to_string(cycle + 20) + "}");
  const std::string short_deck = dir + "/short.yaml";
  std::ofstream(short_deck) << text;
  std::string err;
  ASSERT_EQ(runBinary(short_deck + " -o " + dir + "/reference", &err, kEnv), 0) << err;
  ASSERT_EQ(runBinary(short_deck + " -o " + dir + "/restarted --restart " + files[0], &err, kEnv),
            0)
      << err;
  const std::vector<std::string> ref = lines(dir + "/reference/history.csv");
  const std::vector<std::string> re = lines(dir + "/restarted/history.csv");
  ASSERT_GE(re.size(), 2u);
  EXPECT_EQ(re.back(), ref.back()) << "the last row (cycle " << cycle + 20 << ")";
  const auto a =
      datasetBytes(dir + "/reference/fields.h5",
                   "frames/" + std::to_string(frameCount(dir + "/reference/fields.h5") - 1));
  const auto b =
      datasetBytes(dir + "/restarted/fields.h5",
                   "frames/" + std::to_string(frameCount(dir + "/restarted/fields.h5") - 1));
  ASSERT_FALSE(a.empty());
  ASSERT_EQ(a.size(), b.size());
  for (size_t k = 0; k < a.size(); ++k)
    EXPECT_TRUE(a[k].second == b[k].second) << a[k].first;
}

} // namespace

// a restart after the neck eroded (at a quarter of the run): the eroded flags and the eroded
// energy come back, and the run goes on bit for bit; with contact, also the faces erosion had
// exposed and the elements eroded since the last search
INSTANTIATE_TEST_SUITE_P(ErodingDeck, RestartBitwise,
                         ::testing::Values("necked_bar_2d", "eroding_plate_2d"));
