// What a run writes, seen through the scpdyn binary: the estimate before the first cycle (a
// line of the pre-flight block, test_preflight.cpp) and the refusal of runs that would never
// end or fill the disk, output intervals far below the time step, the lock of the output
// directory, a rerun into a used directory, a full disk, and contacts.xmf read by meshio and
// ParaView.
#include "TestUtil.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sys/wait.h>
#include <unistd.h>

using namespace scpdyn;

namespace
{
namespace fs = std::filesystem;

const std::string kWork = std::string(SCPDYN_TEST_WORKDIR) + "/outputs";

// An elastic block at rest, no contact, no gauges: the time step stays the first one, 1.0408e-6 s
// (courant 0.5 x 0.01 m / 4804 m/s), so time.end 1.0e-5 takes 10 cycles.
const char *kBlockDeck = R"(dimension: 2
time: {end: 1.0e-5}
materials:
  - {name: rock, density: 2600, youngs_modulus: 5.0e10, poisson_ratio: 0.25}
parts:
  - {name: block, material: rock, mesh: {elements: [4, 2], size: [0.04, 0.02]}}
)";

// Two blocks stacked on a fixed ground, the top one moving down onto the other: common planes
// appear in the first cycles (4, then 6: the joint's faces and the two side pairs).
const char *kStackDeck = R"(dimension: 2
time: {end: 2.0e-5}
gravity: [0, -9.81]
output: {field_interval: 5.0e-6}
materials:
  - {name: rock, density: 2600, youngs_modulus: 5.0e10, poisson_ratio: 0.25}
parts:
  - {name: base, material: rock, mesh: {elements: [4, 2], size: [0.04, 0.02]}}
  - {name: top, material: rock, mesh: {elements: [4, 2], origin: [0, 0.02], size: [0.04, 0.02]},
     initial_velocity: [0, -1]}
node_sets:
  - {name: ground, box: {min: [-1, 0], max: [1, 0]}}
boundary_conditions:
  - {type: velocity, node_set: ground, component: y, value: 0}
gauges:
  - {name: corner, node: 0, quantities: [vy]}
contact:
  surfaces:
    - {name: joint, part: "*", option: implicit}
)";

std::string deckFile(const std::string &name, const std::string &text)
{
  fs::create_directories(kWork);
  const std::string path = kWork + "/" + name;
  std::ofstream(path) << text;
  return path;
}

std::string outDir(const std::string &name)
{
  const std::string dir = kWork + "/" + name;
  fs::remove_all(dir);
  return dir;
}

/// the binary under `timeout`: a run that does not end is a failure, not a hung test
int run(const std::string &args, std::string *err, const std::string &env = "",
        std::string *out = nullptr)
{
  return test::runBinary(args, err, "OMP_NUM_THREADS=1 OMP_PROC_BIND=false " + env + " timeout 120",
                         out);
}

int count(const std::string &text, const std::string &what)
{
  int n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
    ++n;
  return n;
}

long summaryCycles(const std::string &dir)
{
  const std::string s = test::readText(dir + "/summary.json");
  std::smatch m;
  return std::regex_search(s, m, std::regex("\"cycles\": ([0-9]+)")) ? std::stol(m[1]) : -1;
}

std::string hostName()
{
  char name[256] = {};
  gethostname(name, sizeof name - 1);
  return name;
}

bool python(const std::string &module)
{
  return std::system(("/usr/bin/python3 -c 'import " + module + "' > /dev/null 2>&1").c_str()) == 0;
}
} // namespace

TEST(Outputs, EstimateLineGivesTheCyclesTheRunTakes)
{
  const std::string dir = outDir("estimate");
  std::string err, out;
  ASSERT_EQ(run(deckFile("block.yaml", kBlockDeck) + " -o " + dir, &err, "", &out), 0) << err;
  // one line of the pre-flight block on stdout; at rest the time step stays the first, so the
  // estimate (end time / first dt, rounded up) is the cycle count exactly
  std::smatch m;
  ASSERT_TRUE(std::regex_search(out, m, std::regex("estimate: ([0-9]+) cycles .* of output\n")))
      << out;
  EXPECT_EQ(std::stol(m[1]), summaryCycles(dir)) << out;
  EXPECT_EQ(summaryCycles(dir), 10);
}

TEST(Outputs, IntervalsFarBelowTheTimeStepWriteOncePerCycle)
{
  // 1e-300 s never moves `next += interval` at t ~ 1e-6 s: the interval logic must not loop
  const std::string deck = deckFile(
      "tiny_intervals.yaml",
      std::string(kBlockDeck) + "output: {field_interval: 1.0e-300, history_interval: 1.0e-300}\n");
  const std::string dir = outDir("tiny_intervals");
  std::string err;
  ASSERT_EQ(run(deck + " -o " + dir, &err), 0) << err;
  const long cycles = summaryCycles(dir);
  EXPECT_EQ(cycles, 10);
  // the first frame and row, then one per cycle
  EXPECT_EQ(count(test::readText(dir + "/fields.xmf"), "<Grid Name=\"frame_"), cycles + 1);
  EXPECT_EQ(test::readCsv(dir + "/history.csv")["cycle"].size(), size_t(cycles + 1));
}

TEST(Outputs, RunsThatWouldNeverEndAreRefusedBeforeTheFirstCycle)
{
  // courant 1e-300 and E = 1e308 Pa give time steps of ~1e-306 s and ~1e-155 s: some 1e300
  // and 1e150 cycles, which ran (and wrote history) until killed
  const std::string base = kBlockDeck;
  const std::string courant =
      std::regex_replace(base, std::regex("end: 1.0e-5"), "end: 1.0e-5, courant: 1.0e-300");
  const std::string stiff =
      std::regex_replace(base, std::regex("youngs_modulus: 5.0e10"), "youngs_modulus: 1.0e308");
  for (const auto &[name, text] :
       {std::pair<std::string, std::string>{"courant", courant}, {"stiff", stiff}})
  {
    SCOPED_TRACE(name);
    const std::string dir = outDir("never_ends_" + name);
    std::string err;
    EXPECT_EQ(run(deckFile(name + ".yaml", text) + " -o " + dir, &err), 2) << err;
    EXPECT_NE(err.find("time.max_estimated_cycles"), std::string::npos) << err;
    EXPECT_FALSE(fs::exists(dir)) << "refused before anything is written";
  }
  // time.max_cycles bounds the estimate: the stiff block then runs its 5 cycles
  const std::string dir = outDir("never_ends_capped");
  std::string err;
  const std::string capped =
      std::regex_replace(stiff, std::regex("end: 1.0e-5"), "end: 1.0e-5, max_cycles: 5");
  EXPECT_EQ(run(deckFile("capped.yaml", capped) + " -o " + dir, &err), 0) << err;
  EXPECT_EQ(summaryCycles(dir), 5);
  // and the limit is the deck's: courant 0.01 takes 481 cycles
  const std::string slow = std::regex_replace(courant, std::regex("courant: 1.0e-300"),
                                              "courant: 0.01, max_estimated_cycles: 100");
  EXPECT_EQ(run(deckFile("limit_100.yaml", slow) + " -o " + outDir("never_ends_100"), &err), 2)
      << err;
  EXPECT_NE(err.find("time.max_estimated_cycles: the run needs about 481 cycles"),
            std::string::npos)
      << err;
  const std::string raised = std::regex_replace(slow, std::regex("max_estimated_cycles: 100"),
                                                "max_estimated_cycles: 1000");
  EXPECT_EQ(run(deckFile("limit_1000.yaml", raised) + " -o " + outDir("never_ends_1000"), &err), 0)
      << err;
}

TEST(Outputs, OutputAboveTheLimitIsRefused)
{
  // 11 history rows of 13 columns alone are some 3.6 kB
  const std::string deck =
      deckFile("small_limit.yaml", std::string(kBlockDeck) + "output: {max_output_bytes: 1000}\n");
  const std::string dir = outDir("small_limit");
  std::string err;
  EXPECT_EQ(run(deck + " -o " + dir, &err), 2) << err;
  EXPECT_NE(err.find("output.max_output_bytes: the run would write about"), std::string::npos)
      << err;
  EXPECT_FALSE(fs::exists(dir));
}

TEST(Outputs, ALiveRunsLockKeepsASecondRunOut)
{
  const std::string dir = outDir("locked");
  fs::create_directories(dir);
  // this test process stands for the live run that holds the directory
  const std::string holder = std::to_string(getpid());
  std::ofstream(dir + "/scpdyn.lock") << holder << " " << hostName() << "\n";
  std::string err;
  EXPECT_EQ(run(deckFile("block.yaml", kBlockDeck) + " -o " + dir, &err), 2) << err;
  EXPECT_NE(err.find("'" + dir + "'"), std::string::npos) << err;
  EXPECT_NE(err.find("pid " + holder), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir + "/history.csv"));
  EXPECT_EQ(test::readText(dir + "/scpdyn.lock"), holder + " " + hostName() + "\n");
}

TEST(Outputs, AStaleLockIsTakenOverWithAWarning)
{
  const pid_t child = fork();
  if (child == 0)
    _exit(0);
  ASSERT_GT(child, 0);
  waitpid(child, nullptr, 0); // now no process has this pid (until the system reuses it)
  const std::string dir = outDir("stale_lock");
  fs::create_directories(dir);
  std::ofstream(dir + "/scpdyn.lock") << child << " " << hostName() << "\n";
  std::string err;
  EXPECT_EQ(run(deckFile("block.yaml", kBlockDeck) + " -o " + dir, &err), 0) << err;
  EXPECT_NE(err.find("warning: took over the stale lock of pid " + std::to_string(child)),
            std::string::npos)
      << err;
  EXPECT_TRUE(fs::exists(dir + "/summary.json"));
  EXPECT_FALSE(fs::exists(dir + "/scpdyn.lock")) << "released at the end of the run";
}

TEST(Outputs, ARerunLeavesNoFileOfThePreviousRun)
{
  const std::string dir = outDir("rerun");
  std::string err;
  ASSERT_EQ(run(deckFile("stack.yaml", kStackDeck) + " -o " + dir, &err), 0) << err;
  ASSERT_TRUE(fs::exists(dir + "/contacts.xmf"));
  ASSERT_TRUE(fs::exists(dir + "/gauges.csv"));
  // the second deck has neither contact nor gauges
  ASSERT_EQ(run(deckFile("block.yaml", kBlockDeck) + " -o " + dir, &err), 0) << err;
  for (const char *stale : {"contacts.xmf", "contacts.h5", "gauges.csv"})
    EXPECT_FALSE(fs::exists(dir + "/" + stale)) << stale;
  EXPECT_NE(err.find("removed the previous run's outputs from " + dir), std::string::npos) << err;
  EXPECT_NE(err.find("contacts.xmf"), std::string::npos) << err;
  EXPECT_TRUE(fs::exists(dir + "/fields.xmf"));
}

TEST(Outputs, TwoRanksLockTheDirectoryOnce)
{
  if (std::system("command -v mpirun > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "no mpirun";
  const std::string dir = outDir("two_ranks");
  const std::string deck = deckFile("block.yaml", kBlockDeck);
  // the variables of this test process's own MPI session would make mpirun join it
  const std::string mpirun =
      "for v in $(env | grep -o -E '^(OMPI|PMIX|ORTE)_[A-Za-z0-9_]*' | grep -v ALLOW_RUN_AS_ROOT); "
      "do unset $v; done; OMP_NUM_THREADS=1 OMP_PROC_BIND=false timeout 300 mpirun -np 2 "
      "--oversubscribe " +
      std::string(SCPDYN_BINARY) + " " + deck + " -o " + dir;
  // rank 1 taking a lock too would find rank 0's, held by a live process
  const std::string err_file = kWork + "/two_ranks.err";
  EXPECT_EQ(std::system((mpirun + " > " + err_file + " 2>&1").c_str()), 0)
      << test::readText(err_file);
  EXPECT_FALSE(fs::exists(dir + "/scpdyn.lock"));
  // a held directory stops every rank, with the one message of rank 0
  std::ofstream(dir + "/scpdyn.lock") << getpid() << " " << hostName() << "\n";
  const int rc = std::system((mpirun + " > " + err_file + " 2>&1").c_str());
  EXPECT_TRUE(WIFEXITED(rc) && WEXITSTATUS(rc) == 2) << test::readText(err_file);
  EXPECT_EQ(count(test::readText(err_file), "is in use by the run of pid"), 1)
      << test::readText(err_file);
}

TEST(Outputs, NoGaugesNoGaugesCsv)
{
  const std::string dir = outDir("no_gauges");
  std::string err;
  ASSERT_EQ(run(deckFile("block.yaml", kBlockDeck) + " -o " + dir, &err), 0) << err;
  EXPECT_TRUE(fs::exists(dir + "/history.csv"));
  EXPECT_FALSE(fs::exists(dir + "/gauges.csv"));
}

TEST(Outputs, ContactsXmfIsReadByMeshio)
{
  if (!python("meshio") || !python("h5py"))
    GTEST_SKIP() << "meshio or h5py not installed for /usr/bin/python3";
  const std::string dir = outDir("contacts_meshio");
  std::string err;
  ASSERT_EQ(run(deckFile("stack.yaml", kStackDeck) + " -o " + dir, &err), 0) << err;
  const std::string summary = test::readText(dir + "/summary.json");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(summary, m, std::regex("\"common_planes_max\": ([0-9]+)")));
  const int cps = std::stoi(m[1]);
  ASSERT_GT(cps, 1);
  // every frame as meshio reads it (its time-series reader takes the mesh from one grid:
  // pointed at each frame's grid in turn), against the CPs scpdyn wrote in that frame; the last
  // frame holds the most CPs of the run
  const std::string script = dir + "/check_meshio.py";
  std::ofstream(script)
      << "import sys, h5py, meshio\n"
      << "d, cps = sys.argv[1], int(sys.argv[2])\n"
      << "h5 = h5py.File(d + '/contacts.h5', 'r')\n"
      << "with meshio.xdmf.TimeSeriesReader(d + '/contacts.xmf') as r:\n"
      << "    assert r.num_steps == len(h5['frames']) == 5, r.num_steps\n"
      << "    for k in range(r.num_steps):\n"
      << "        r.mesh_grid = r.collection[k]\n"
      << "        points, cells = r.read_points_cells()\n"
      << "        t, pd, cd = r.read_data(k)\n"
      << "        n = len(h5['frames/%d/point_data/area' % k])\n"
      << "        assert points.shape == (n, 3), (k, points.shape, n)\n"
      << "        assert [(c.type, c.data.shape) for c in cells] == [('vertex', (n, 1))], k\n"
      << "        assert sorted(c for c in cells[0].data[:, 0]) == list(range(n)), k\n"
      << "        assert all(len(v) == n for v in pd.values()) and 'area' in pd, k\n"
      << "    assert n == cps, (n, cps)\n";
  EXPECT_EQ(
      std::system(("/usr/bin/python3 " + script + " " + dir + " " + std::to_string(cps)).c_str()),
      0);
}

TEST(Outputs, ContactsXmfIsReadByParaView)
{
  if (std::system("command -v pvbatch > /dev/null 2>&1") != 0)
  {
    if (const char *ci = std::getenv("CI"); ci && std::string(ci) == "true")
      FAIL() << "pvbatch not installed: CI (CI=true) runs the ParaView checks (.ci/run)";
    GTEST_SKIP() << "pvbatch not installed (Debian paraview + python3-paraview)";
  }
  const std::string dir = outDir("contacts_paraview");
  std::string err;
  ASSERT_EQ(run(deckFile("stack.yaml", kStackDeck) + " -o " + dir, &err), 0) << err;
  // both readers: one vertex cell per contact point in every frame, as many as scpdyn wrote
  const std::string script = dir + "/check_pv.py";
  std::ofstream(script)
      << "import sys, h5py\nfrom paraview.simple import *\n"
      << "d = sys.argv[1]\nh5 = h5py.File(d + '/contacts.h5', 'r')\n"
      << "counts = [len(h5['frames/%d/points' % k]) for k in range(len(h5['frames']))]\n"
      << "for name in ['XDMFReader', 'Xdmf3ReaderS']:\n"
      << "    fn = [d + '/contacts.xmf']\n"
      << "    r = XDMFReader(FileNames=fn) if name == 'XDMFReader' else Xdmf3ReaderS(FileName=fn)\n"
      << "    times = list(r.TimestepValues)\n"
      << "    assert len(times) == len(counts), (name, times)\n"
      << "    for t, n in zip(times, counts):\n"
      << "        r.UpdatePipeline(t)\n"
      << "        o = servermanager.Fetch(r)\n"
      << "        got = (o.GetNumberOfPoints(), o.GetNumberOfCells())\n"
      << "        assert got == (n, n), (name, t, got, n)\n"
      << "        assert o.GetPointData().GetArray('normal_force') is not None, name\n"
      << "print('paraview ok', counts)\n";
  EXPECT_EQ(std::system(("pvbatch " + script + " " + dir).c_str()), 0);
}

TEST(Outputs, AFullDiskGivesOneLineWithThePathAndTheCause)
{
  if (geteuid() != 0)
    GTEST_SKIP() << "mounting a small tmpfs needs root";
  const std::string mnt = outDir("full_disk");
  fs::create_directories(mnt);
  if (std::system(("mount -t tmpfs -o size=200k tmpfs " + mnt + " 2> /dev/null").c_str()) != 0)
    GTEST_SKIP() << "cannot mount a tmpfs here";
  // fields fill the 200 kB first (861 nodes, 800 cells: 132 kB a frame, one every cycle) ...
  const std::string fields = deckFile("fields_fill.yaml", R"(dimension: 2
time: {end: 1.0e-4}
output: {field_interval: 1.0e-6, history_interval: 1.0e-5}
materials:
  - {name: rock, density: 2600, youngs_modulus: 5.0e10, poisson_ratio: 0.25}
parts:
  - {name: base, material: rock, mesh: {elements: [40, 20], size: [0.04, 0.02]}, initial_velocity: [1, 0]}
)");
  // ... or history rows do (some 300 B a cycle with the gauge's row, 19216 cycles)
  const std::string rows = deckFile(
      "rows_fill.yaml",
      std::regex_replace(std::string(kBlockDeck), std::regex("end: 1.0e-5"), "end: 2.0e-2") +
          "gauges:\n  - {name: corner, node: 0, quantities: [vx, vy]}\n");
  struct Unmount
  {
    std::string dir;
    ~Unmount() { std::system(("umount " + dir).c_str()); }
  } unmount{mnt};
  for (const auto &[deck, file] :
       {std::pair<std::string, std::string>{fields, "fields.h5'"}, {rows, ".csv'"}})
  {
    SCOPED_TRACE(deck);
    const std::string dir = mnt + "/run";
    fs::remove_all(dir);
    std::string err;
    EXPECT_NE(run(deck + " -o " + dir, &err), 0) << err;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(err, m, std::regex("scpdyn: error: (.*)\n"))) << err;
    EXPECT_NE(m[1].str().find("'" + dir + "/"), std::string::npos) << err;
    EXPECT_NE(m[1].str().find(file), std::string::npos) << err;
    EXPECT_NE(m[1].str().find("No space left on device"), std::string::npos) << err;
    EXPECT_EQ(err.find("HDF5-DIAG"), std::string::npos) << err;
    EXPECT_LE(count(err, "\n"), 3) << err; // the run line, the estimate, the error
    for (const auto &e : fs::directory_iterator(dir))
      EXPECT_NE(e.path().extension(), ".tmp") << e.path();
    // whole rows only: every line of the CSV files has all its columns
    for (const char *csv : {"history.csv", "gauges.csv"})
    {
      const std::string text = test::readText(dir + "/" + csv);
      if (text.empty())
        continue;
      EXPECT_EQ(text.back(), '\n') << csv;
      std::istringstream lines(text);
      std::string line;
      std::getline(lines, line);
      const int commas = count(line, ",");
      while (std::getline(lines, line))
        EXPECT_EQ(count(line, ","), commas) << csv << ": " << line;
    }
  }
}
