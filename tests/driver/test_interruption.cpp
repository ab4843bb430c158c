// SIGINT and SIGTERM stop a run at the end of a cycle with complete outputs (README, "Running a
// deck"): the binary on a deck that would run for hours, signalled once its first frame is
// written, serial (through its restart with OMP_PROC_BIND) and on two ranks under mpirun.
#include "StartedProcess.hpp"
#include "SummaryJson.hpp"
#include "TestUtil.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <fcntl.h>
#include <sys/wait.h>
#include <thread>
#include <tuple>
#include <unistd.h>
#include <vector>

extern char **environ;

using namespace scpdyn;
using scpdyn::test::start;
using scpdyn::test::Started;
using scpdyn::test::waitForExit;
using scpdyn::test::waitForFile;
namespace fs = std::filesystem;

namespace
{

const std::string kWork = std::string(SCPDYN_TEST_WORKDIR) + "/interruption";

// About 1e7 cycles of a moving block: hours, so the signal always comes before the end; frames
// every 5e-5 s (some 480 cycles) and history rows every 1e-6 s
const char *kLongDeck = R"(dimension: 2
time: {end: 1.0}
output: {field_interval: 5.0e-5, history_interval: 1.0e-6}
materials:
  - {name: rock, density: 2600, youngs_modulus: 5.0e10, poisson_ratio: 0.25}
parts:
  - {name: block, material: rock, mesh: {elements: [40, 20], size: [0.04, 0.02]},
     initial_velocity: [1.0, 0.0]}
)";

// Generous bounds for a loaded machine: they only end a test that would otherwise hang.
constexpr double kStartSeconds = 300, kStopSeconds = 300;

/// The extents of dataset `path` of an open HDF5 file (empty if it cannot be opened).
std::vector<hsize_t> datasetDims(hid_t file, const std::string &path)
{
  std::vector<hsize_t> dims;
  if (H5Lexists(file, path.c_str(), H5P_DEFAULT) <= 0)
    return dims;
  const hid_t d = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  if (d < 0)
    return dims;
  const hid_t space = H5Dget_space(d);
  dims.resize(size_t(H5Sget_simple_extent_ndims(space)));
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  H5Sclose(space);
  H5Dclose(d);
  return dims;
}

/// Checks what an interrupted run left in `dir`: summary.json interrupted by `signal`, every
/// frame fields.xmf names complete in fields.h5 and the last at the stop time, history.csv
/// ending with the whole row of the stop cycle, no lock, and the line of `stderr_text` that
/// says so.
/// Returns the stop cycle.
long expectInterruptedOutputs(const std::string &dir, const std::string &signal,
                              const std::string &stderr_text)
{
  const std::string s = test::readText(dir + "/summary.json");
  EXPECT_EQ(test::jsonText(s, {"status"}), "interrupted") << s.substr(0, 400);
  EXPECT_EQ(test::jsonText(s, {"interrupted_by"}), signal);
  const long cycle = std::stol("0" + test::jsonText(s, {"cycles"}));
  const std::string stop_time = test::jsonText(s, {"end_time"}); // "%.17g"
  EXPECT_GT(cycle, 0);
  EXPECT_LT(std::stod(stop_time), 1.0) << "stopped before the end";

  // frames: the last at the stop time; every dataset named in fields.xmf in fields.h5
  const std::string xmf = test::readText(dir + "/fields.xmf");
  std::vector<std::string> times;
  const std::regex time_re("<Time Value=\"([^\"]*)\"/>");
  for (auto it = std::sregex_iterator(xmf.begin(), xmf.end(), time_re);
       it != std::sregex_iterator(); ++it)
    times.push_back((*it)[1]);
  EXPECT_GE(times.size(), 2u) << "the first frame and the last";
  if (!times.empty())
    EXPECT_EQ(times.back(), stop_time);
  const hid_t file = H5Fopen((dir + "/fields.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_GE(file, 0) << dir << "/fields.h5";
  if (file >= 0)
  {
    const std::regex item_re("<DataItem Dimensions=\"([0-9 ]+)\"[^>]*>fields\\.h5:([^<]+)<");
    int items = 0;
    for (auto it = std::sregex_iterator(xmf.begin(), xmf.end(), item_re);
         it != std::sregex_iterator(); ++it, ++items)
    {
      std::vector<hsize_t> expected;
      std::istringstream in((*it)[1].str());
      for (hsize_t d; in >> d;)
        expected.push_back(d);
      EXPECT_EQ(datasetDims(file, (*it)[2]), expected) << (*it)[2];
    }
    EXPECT_GT(items, 0);
    H5Fclose(file);
  }
  EXPECT_FALSE(fs::exists(dir + "/fields.xmf.tmp"));

  // history.csv: whole rows, the last one at the stop cycle and time
  const std::string history = test::readText(dir + "/history.csv");
  EXPECT_FALSE(history.empty());
  if (!history.empty())
    EXPECT_EQ(history.back(), '\n');
  std::istringstream rows(history);
  std::string header, row, last;
  std::getline(rows, header);
  const auto columns = std::count(header.begin(), header.end(), ',');
  while (std::getline(rows, row))
  {
    EXPECT_EQ(std::count(row.begin(), row.end(), ','), columns) << row;
    last = row;
  }
  EXPECT_EQ(last.substr(0, last.find(',')), stop_time) << last;
  const auto h = test::readCsv(dir + "/history.csv");
  if (!h.at("cycle").empty())
    EXPECT_EQ(long(h.at("cycle").back()), cycle);

  EXPECT_FALSE(fs::exists(dir + "/scpdyn.lock")) << "released";
  char line[256];
  std::snprintf(line, sizeof line,
                "scpdyn: interrupted by %s at cycle %ld, t = %.6e s; outputs are complete to "
                "that cycle\n",
                signal.c_str(), cycle, std::stod(stop_time));
  const size_t at = stderr_text.find("scpdyn: interrupted");
  EXPECT_EQ(at == std::string::npos ? stderr_text
                                    : stderr_text.substr(at, stderr_text.find('\n', at) + 1 - at),
            line)
      << stderr_text;
  return cycle;
}

/// The long deck in a file of the test's own (tests may run at once).
std::string deckPath(const std::string &test)
{
  fs::create_directories(kWork);
  const std::string path = kWork + "/" + test + ".yaml";
  std::ofstream(path) << kLongDeck;
  return path;
}

/// The ranks of an mpirun, by the pid of each (its children that run the binary).
std::vector<pid_t> ranksOf(pid_t mpirun)
{
  std::vector<std::pair<int, pid_t>> ranks;
  for (const auto &task : fs::directory_iterator("/proc/" + std::to_string(mpirun) + "/task"))
  {
    std::istringstream children(test::readText(task.path().string() + "/children"));
    for (pid_t c; children >> c;)
    {
      std::ifstream env("/proc/" + std::to_string(c) + "/environ");
      for (std::string v; std::getline(env, v, '\0');)
        if (v.rfind("OMPI_COMM_WORLD_RANK=", 0) == 0)
          ranks.emplace_back(std::stoi(v.substr(21)), c);
    }
  }
  std::sort(ranks.begin(), ranks.end());
  std::vector<pid_t> pids;
  for (const auto &r : ranks)
    pids.push_back(r.second);
  return pids;
}

/// The variables of this test process's own MPI session, which would make mpirun join it.
std::vector<std::string> mpiSessionVariables()
{
  std::vector<std::string> names;
  for (char **e = environ; *e; ++e)
  {
    const std::string v = *e;
    const std::string name = v.substr(0, v.find('='));
    if ((name.rfind("OMPI_", 0) == 0 || name.rfind("PMIX_", 0) == 0 ||
         name.rfind("ORTE_", 0) == 0) &&
        name.find("ALLOW_RUN_AS_ROOT") == std::string::npos)
      names.push_back(name);
  }
  return names;
}

} // namespace

TEST(Interruption, SigtermAndSigintStopAtTheEndOfACycleWithCompleteOutputs)
{
  for (const auto &[signal, name, status] : {std::make_tuple(SIGTERM, std::string("SIGTERM"), 143),
                                             std::make_tuple(SIGINT, std::string("SIGINT"), 130)})
  {
    SCOPED_TRACE(name);
    const std::string dir = kWork + "/serial_" + name;
    fs::remove_all(dir);
    // without OMP_PROC_BIND scpdyn restarts itself (exec: the same process) to set it
    const Started run = start({SCPDYN_BINARY, deckPath("serial_" + name), "-o", dir}, dir,
                              {"OMP_PROC_BIND"}, {"OMP_NUM_THREADS=1"});
    ASSERT_GT(run.pid, 0);
    const bool started = waitForFile(run.pid, dir + "/fields.xmf", kStartSeconds);
    if (started)
      kill(run.pid, signal);
    if (started && signal == SIGTERM) // sent twice, as a batch system and mpirun may: the same
      kill(run.pid, signal);
    const int rc = waitForExit(run.pid, started ? kStopSeconds : 1);
    ASSERT_TRUE(started) << test::readText(run.err);
    ASSERT_TRUE(rc != -1 && WIFEXITED(rc)) << "status " << rc << ": " << test::readText(run.err);
    EXPECT_EQ(WEXITSTATUS(rc), status) << test::readText(run.err);
    expectInterruptedOutputs(dir, name, test::readText(run.err));
    EXPECT_EQ(test::readText(run.out).find("scpdyn: done"), std::string::npos);
  }
}

TEST(Interruption, TwoRanksStopAfterTheSameCycleWhenOneOfThemIsSignalled)
{
  if (std::system("command -v mpirun > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "no mpirun";
  // SIGTERM to rank 1 alone: the time-step reduction tells rank 0, and both end the same cycle
  const std::string dir = kWork + "/ranks_signal_one";
  fs::remove_all(dir);
  const Started run =
      start({"/bin/sh", "-c",
             "exec mpirun -np 2 --oversubscribe " + std::string(SCPDYN_BINARY) + " " +
                 deckPath("ranks_signal_one") + " -o " + dir},
            dir, mpiSessionVariables(), {"OMP_NUM_THREADS=1", "OMP_PROC_BIND=false"});
  ASSERT_GT(run.pid, 0);
  const bool started = waitForFile(run.pid, dir + "/fields.xmf", kStartSeconds);
  const std::vector<pid_t> ranks = started ? ranksOf(run.pid) : std::vector<pid_t>();
  if (ranks.size() == 2)
    kill(ranks[1], SIGTERM);
  const int rc = waitForExit(run.pid, ranks.size() == 2 ? kStopSeconds : 1);
  ASSERT_TRUE(started) << test::readText(run.err);
  ASSERT_EQ(ranks.size(), 2u);
  // mpirun passes on the ranks' status
  ASSERT_TRUE(rc != -1 && WIFEXITED(rc)) << "status " << rc << ": " << test::readText(run.err);
  EXPECT_EQ(WEXITSTATUS(rc), 143) << test::readText(run.err);
  expectInterruptedOutputs(dir, "SIGTERM", test::readText(run.err));
  const std::string s = test::readText(dir + "/summary.json");
  EXPECT_EQ(test::jsonText(s, {"ranks"}), "2");
}

TEST(Interruption, SigtermToMpirunReachesTheRanks)
{
  if (std::system("command -v mpirun > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "no mpirun";
  // Open MPI 4.1's mpirun, on SIGTERM, sends the ranks SIGCONT, then SIGTERM after
  // odls_base_sigkill_timeout seconds (default 1), then SIGKILL as long again after that: 1 s
  // to end a cycle and write a frame. 15 s here, for a loaded machine (mpirun itself waits out
  // the second interval before it exits, whenever the ranks end).
  const std::string dir = kWork + "/ranks_signal_mpirun";
  fs::remove_all(dir);
  const Started run =
      start({"/bin/sh", "-c",
             "exec mpirun --mca odls_base_sigkill_timeout 15 -np 2 --oversubscribe " +
                 std::string(SCPDYN_BINARY) + " " + deckPath("ranks_signal_mpirun") + " -o " + dir},
            dir, mpiSessionVariables(), {"OMP_NUM_THREADS=1", "OMP_PROC_BIND=false"});
  ASSERT_GT(run.pid, 0);
  const bool started = waitForFile(run.pid, dir + "/fields.xmf", kStartSeconds);
  if (started)
    kill(run.pid, SIGTERM);
  const int rc = waitForExit(run.pid, started ? kStopSeconds : 1);
  ASSERT_TRUE(started) << test::readText(run.err);
  ASSERT_NE(rc, -1) << test::readText(run.err);
  // mpirun itself reports the job it was told to end as failed (status 1), whatever the ranks did
  EXPECT_TRUE(WIFEXITED(rc) && WEXITSTATUS(rc) != 0) << rc;
  expectInterruptedOutputs(dir, "SIGTERM", test::readText(run.err));
}
