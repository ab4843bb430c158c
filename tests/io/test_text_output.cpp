// TextOutput: CSV round trip bit for bit, flushing, JSON validity (Python's json) and
// escaping, mkdir -p.
#include "io/TextOutput.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <csignal>
#include <random>
#include <sstream>
#include <sys/resource.h>

namespace
{
using scpdyn::CsvWriter;
using scpdyn::JsonObject;

std::string workPath(const std::string &name)
{
  return std::string(SCPDYN_TEST_WORKDIR) + "/io_text_" + name;
}

std::vector<std::string> readLines(const std::string &path)
{
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);)
    lines.push_back(l);
  return lines;
}

std::vector<std::string> split(const std::string &line)
{
  std::vector<std::string> out;
  std::stringstream s(line);
  for (std::string f; std::getline(s, f, ',');)
    out.push_back(f);
  return out;
}

std::uint64_t bits(double d)
{
  std::uint64_t b;
  std::memcpy(&b, &d, sizeof b);
  return b;
}

bool havePython() { return std::system("/usr/bin/python3 -c 'import json' > /dev/null 2>&1") == 0; }

} // namespace

TEST(CsvWriter, SeventeenDigitsRoundTripBitForBit)
{
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> special = {0.1,
                                 -0.0,
                                 1.0 / 3.0,
                                 std::nextafter(1.0, 2.0), // needs all 17 digits
                                 std::numeric_limits<double>::denorm_min(),
                                 std::numeric_limits<double>::min(),
                                 std::numeric_limits<double>::max(),
                                 -std::numeric_limits<double>::epsilon(),
                                 6.02214076e23,
                                 inf};
  std::mt19937_64 rng(12345);
  std::uniform_int_distribution<std::uint64_t> any;
  std::vector<std::vector<double>> rows = {special};
  for (int r = 0; r < 200; ++r) // random bit patterns cover every exponent and mantissa
  {
    std::vector<double> row;
    while (row.size() < special.size())
    {
      const std::uint64_t b = any(rng);
      double d;
      std::memcpy(&d, &b, sizeof d);
      if (std::isfinite(d))
        row.push_back(d);
    }
    rows.push_back(row);
  }
  std::vector<std::string> cols;
  for (std::size_t i = 0; i < special.size(); ++i)
    cols.push_back("c" + std::to_string(i));
  cols[1] = "gauge 1, \"vx\""; // needs RFC 4180 quoting
  {
    CsvWriter csv(workPath("roundtrip.csv"), cols, 7);
    for (const auto &r : rows)
      csv.row(r);
  } // destructor flushes and closes

  const auto lines = readLines(workPath("roundtrip.csv"));
  ASSERT_EQ(lines.size(), rows.size() + 1);
  EXPECT_EQ(lines[0], "c0,\"gauge 1, \"\"vx\"\"\",c2,c3,c4,c5,c6,c7,c8,c9");
  for (std::size_t r = 0; r < rows.size(); ++r)
  {
    const auto fields = split(lines[r + 1]);
    ASSERT_EQ(fields.size(), cols.size());
    for (std::size_t c = 0; c < cols.size(); ++c)
      EXPECT_EQ(bits(std::strtod(fields[c].c_str(), nullptr)), bits(rows[r][c]))
          << "row " << r << " col " << c << ": " << fields[c];
  }
}

TEST(CsvWriter, FlushesEveryNRowsAndRejectsBadRows)
{
  const std::string path = workPath("flush.csv");
  CsvWriter csv(path, {"t", "e"}, 3);
  EXPECT_EQ(readLines(path).size(), 1u); // header on disk at once
  csv.row({1.0, 2.0});
  csv.row({2.0, 3.0});
  csv.row({3.0, 4.0}); // third row triggers the flush
  EXPECT_EQ(readLines(path).size(), 4u);
  csv.row({4.0, 5.0});
  csv.flush();
  EXPECT_EQ(readLines(path).size(), 5u);
  EXPECT_THROW(csv.row({1.0}), std::invalid_argument);
  csv.close();
  EXPECT_THROW(csv.row({1.0, 2.0}), std::logic_error);
  EXPECT_EQ(readLines(path).back(), "4,5");

  try
  {
    CsvWriter bad("/nonexistent_dir_io/x.csv", {"a"});
    FAIL();
  }
  catch (const std::runtime_error &e)
  {
    EXPECT_NE(std::string(e.what()).find("/nonexistent_dir_io/x.csv"), std::string::npos);
  }
}

TEST(CsvWriter, AFullDeviceGivesTheFileAndTheCause)
{
  // /dev/full: every write fails with ENOSPC, as on a full disk
  try
  {
    CsvWriter csv("/dev/full", {"t", "e"});
    csv.row({1.0, 2.0});
    csv.close();
    FAIL() << "no error on /dev/full";
  }
  catch (const std::runtime_error &e)
  {
    EXPECT_EQ(std::string(e.what()), "cannot write '/dev/full': " + std::string(strerror(ENOSPC)));
  }
}

TEST(CsvWriter, AWriteCutShortLeavesWholeRows)
{
  // a file-size limit makes the write that crosses it stop part-way (then fail with EFBIG),
  // as a disk that fills up in the middle of a row does
  const std::string path = workPath("cut.csv");
  std::remove(path.c_str());
  rlimit saved{};
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &saved), 0);
  rlimit small = saved;
  small.rlim_cur = 1000; // bytes; rows are ~60, flushed 4 at a time: 1000 falls inside a row
  auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &small), 0);
  std::string error;
  {
    CsvWriter csv(path, {"t", "a", "b"}, 4);
    try
    {
      for (int r = 0; r < 1000; ++r)
        csv.row({1.0 / 3 + r, 2.0 / 3, -1e-300 / 7});
      csv.close();
    }
    catch (const std::runtime_error &e)
    {
      error = e.what();
    }
  }
  setrlimit(RLIMIT_FSIZE, &saved);
  std::signal(SIGXFSZ, old_handler);
  EXPECT_EQ(error, "cannot write '" + path + "': " + std::string(strerror(EFBIG)));
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.back(), '\n');
  const auto lines = readLines(path);
  ASSERT_GT(lines.size(), 2u);
  for (const auto &l : lines)
    EXPECT_EQ(split(l).size(), 3u) << l;
}

TEST(ReplaceFile, AFailedWriteKeepsTheOldFileAndNoTemporary)
{
  const std::string path = workPath("replaced.xmf");
  scpdyn::replaceFile(path, "old\n");
  rlimit saved{};
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &saved), 0);
  rlimit small = saved;
  small.rlim_cur = 1000;
  auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &small), 0);
  std::string error;
  try
  {
    scpdyn::replaceFile(path, std::string(5000, 'x'));
  }
  catch (const std::runtime_error &e)
  {
    error = e.what();
  }
  setrlimit(RLIMIT_FSIZE, &saved);
  std::signal(SIGXFSZ, old_handler);
  EXPECT_EQ(error, "cannot write '" + path + ".tmp': " + std::string(strerror(EFBIG)));
  EXPECT_FALSE(std::ifstream(path + ".tmp").good()) << "the half-written temporary is removed";
  EXPECT_EQ(readLines(path), std::vector<std::string>{"old"});
}

TEST(Json, EscapeAndDump)
{
  EXPECT_EQ(scpdyn::jsonEscape("a\"b\\c\n\t\x01 \xc3\xa9"), "a\\\"b\\\\c\\n\\t\\u0001 \xc3\xa9");

  JsonObject inner;
  inner.add("dt", 1e-7).add("n", 3);
  JsonObject o;
  o.add("pi", 3.141592653589793).add("nan", std::nan("")).add("ok", true).add("s", "x");
  o.add("inner", inner).add("empty", JsonObject());
  o.add("ok", false); // replaces in place
  EXPECT_EQ(o.dump(0), "{\"pi\":3.1415926535897931,\"nan\":null,\"ok\":false,\"s\":\"x\","
                       "\"inner\":{\"dt\":9.9999999999999995e-08,\"n\":3},\"empty\":{}}");
  EXPECT_EQ(inner.dump(2), "{\n  \"dt\": 9.9999999999999995e-08,\n  \"n\": 3\n}");
}

TEST(Json, PythonParsesSummary)
{
  if (!havePython())
    GTEST_SKIP() << "/usr/bin/python3 not available";
  JsonObject energy;
  energy.add("kinetic", 0.1).add("internal", -std::numeric_limits<double>::infinity());
  JsonObject o;
  o.add("name", std::string("impact \"2d\"\n\ttab\x1f"))
      .add("cycles", 123456789012L)
      .add("threads", 2)
      .add("n_nodes", std::size_t(42))
      .add("converged", true)
      .add("tiny", std::numeric_limits<double>::denorm_min())
      .add("gauge_x", std::vector<double>{1.5, std::nan(""), -0.0})
      .add("energy", energy);
  const std::string path = workPath("summary.json");
  scpdyn::writeJson(path, o, 2);
  // Python checks validity and the decoded values (doubles exactly: %.17g round-trips).
  const std::string script = workPath("check_json.py");
  std::ofstream(script)
      << "import json, sys\n"
      << "d = json.load(open(sys.argv[1]))\n"
      << "assert d['name'] == 'impact \"2d\"\\n\\ttab\\x1f', d['name']\n"
      << "assert d['cycles'] == 123456789012 and d['threads'] == 2 and d['n_nodes'] == 42\n"
      << "assert d['converged'] is True and d['tiny'] == 5e-324\n"
      << "assert d['gauge_x'][0] == 1.5 and d['gauge_x'][1] is None\n"
      << "assert d['energy'] == {'kinetic': 0.1, 'internal': None}\n";
  EXPECT_EQ(std::system(("/usr/bin/python3 " + script + " " + path).c_str()), 0);
  EXPECT_EQ(
      std::system(
          ("/usr/bin/python3 -c 'import json,sys; json.load(open(sys.argv[1]))' " + path).c_str()),
      0);
}

TEST(EnsureDirectory, CreatesParentsAndNamesPathOnFailure)
{
  const std::string deep = workPath("dirs") + "/a/b/c";
  scpdyn::ensureDirectory(deep);
  std::ofstream(deep + "/probe") << "x";
  EXPECT_TRUE(std::ifstream(deep + "/probe").good());
  scpdyn::ensureDirectory(deep); // existing: no error

  const std::string blocked = deep + "/probe/sub"; // a regular file in the way
  try
  {
    scpdyn::ensureDirectory(blocked);
    FAIL();
  }
  catch (const std::runtime_error &e)
  {
    EXPECT_NE(std::string(e.what()).find(blocked), std::string::npos) << e.what();
  }
  EXPECT_THROW(scpdyn::ensureDirectory(deep + "/probe"), std::runtime_error);
}
