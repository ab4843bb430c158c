// OutputDirectoryLock: one run per output directory (a live holder is named, a dead one's lock
// is taken over), and removeFiles.
#include "io/OutputDirectory.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <sys/wait.h>
#include <unistd.h>

namespace
{
namespace fs = std::filesystem;
using scpdyn::OutputDirectoryLock;

std::string freshDir(const std::string &name)
{
  const std::string dir = std::string(SCPDYN_TEST_WORKDIR) + "/io_lock_" + name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string readText(const std::string &path)
{
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string lockError(const std::string &dir)
{
  try
  {
    OutputDirectoryLock second(dir);
  }
  catch (const std::runtime_error &e)
  {
    return e.what();
  }
  return "(no error)";
}
} // namespace

TEST(OutputDirectoryLock, ALiveHolderKeepsOthersOutUntilItEnds)
{
  const std::string dir = freshDir("live");
  const std::string me = std::to_string(getpid());
  {
    OutputDirectoryLock first(dir);
    EXPECT_EQ(readText(first.path()), me + " " + scpdyn::hostName() + "\n");
    EXPECT_TRUE(first.warning().empty());
    const std::string error = lockError(dir);
    EXPECT_NE(error.find("output directory '" + dir + "'"), std::string::npos) << error;
    EXPECT_NE(error.find("pid " + me), std::string::npos) << error;
    EXPECT_TRUE(fs::exists(first.path())) << "a refused run leaves the holder's lock alone";
  }
  EXPECT_FALSE(fs::exists(dir + "/scpdyn.lock")) << "released by its holder";
  OutputDirectoryLock again(dir);
  EXPECT_TRUE(again.warning().empty());
}

TEST(OutputDirectoryLock, ADeadHoldersLockIsTakenOverWithAWarning)
{
  const pid_t child = fork();
  if (child == 0)
    _exit(0);
  ASSERT_GT(child, 0);
  waitpid(child, nullptr, 0);
  const std::string dir = freshDir("stale");
  std::ofstream(dir + "/scpdyn.lock") << child << " " << scpdyn::hostName() << "\n";
  OutputDirectoryLock lock(dir);
  EXPECT_NE(lock.warning().find("stale lock of pid " + std::to_string(child)), std::string::npos)
      << lock.warning();
  EXPECT_EQ(readText(lock.path()), std::to_string(getpid()) + " " + scpdyn::hostName() + "\n");
}

TEST(OutputDirectoryLock, AnotherHostsLockIsNotTakenOver)
{
  // its pid cannot be checked from here: 1 is alive on every host, the lock is refused anyway
  const std::string dir = freshDir("other_host");
  std::ofstream(dir + "/scpdyn.lock") << "1 some-other-host\n";
  const std::string error = lockError(dir);
  EXPECT_NE(error.find("pid 1 on host some-other-host"), std::string::npos) << error;
  EXPECT_EQ(readText(dir + "/scpdyn.lock"), "1 some-other-host\n");
}

TEST(RemoveFiles, RemovesTheNamedFilesOnly)
{
  const std::string dir = freshDir("remove");
  for (const char *name : {"contacts.xmf", "history.csv", "mine.txt"})
    std::ofstream(dir + "/" + name) << "x";
  fs::create_directories(dir + "/gauges.csv"); // a directory of that name is not scpdyn's file
  const auto removed =
      scpdyn::removeFiles(dir, {"fields.xmf", "contacts.xmf", "history.csv", "gauges.csv"});
  EXPECT_EQ(removed, (std::vector<std::string>{"contacts.xmf", "history.csv"}));
  EXPECT_TRUE(fs::exists(dir + "/mine.txt"));
  EXPECT_TRUE(fs::is_directory(dir + "/gauges.csv"));
  EXPECT_FALSE(fs::exists(dir + "/contacts.xmf"));
}
