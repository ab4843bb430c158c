// MpiSession gives a process started without mpirun its own Open MPI session directory, so
// that singletons starting together (ctest -j2, a sweep of runs) do not race to create the
// shared one (open-mpi/ompi#8510: the loser aborts in MPI_Init), and removes it at the end.
#include "TestUtil.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace scpdyn
{
namespace
{

namespace fs = std::filesystem;

TEST(MpiSession, ThisTestProcessHasItsOwnSessionDirectory)
{
  if (std::getenv("OMPI_COMM_WORLD_SIZE"))
    GTEST_SKIP() << "started by mpirun: mpirun's session directory is used";
  const char *dir = std::getenv("OMPI_MCA_orte_tmpdir_base");
  ASSERT_NE(dir, nullptr);
  EXPECT_TRUE(fs::is_directory(dir)) << dir;
  EXPECT_EQ(fs::path(dir).filename().string().rfind("scpdyn-mpi-", 0), 0u) << dir;
}

TEST(MpiSession, EightRunsStartedTogetherAllRunAndLeaveNoDirectory)
{
  const fs::path work = fs::path(SCPDYN_TEST_WORKDIR) / "mpi_session";
  const fs::path tmp = work / "tmp";
  fs::remove_all(work);
  fs::create_directories(tmp);
  // each run: a deck that does not exist, so it starts MPI and Kokkos and stops with status 2
  const std::string cmd = "cd " + work.string() + " && for i in 1 2 3 4 5 6 7 8; do " +
                          "(env -u OMPI_MCA_orte_tmpdir_base TMPDIR=" + tmp.string() + " " +
                          SCPDYN_BINARY + " missing.yaml > /dev/null 2> err_$i.txt; " +
                          "echo $? > rc_$i.txt) & done; wait";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  for (int i = 1; i <= 8; ++i)
  {
    const std::string n = std::to_string(i);
    EXPECT_EQ(test::readText((work / ("rc_" + n + ".txt")).string()), "2\n") << "run " << n;
    EXPECT_NE(test::readText((work / ("err_" + n + ".txt")).string()).find("missing.yaml"),
              std::string::npos)
        << "run " << n;
  }
  std::string left;
  for (const auto &entry : fs::recursive_directory_iterator(tmp))
    left += " " + entry.path().string();
  EXPECT_TRUE(left.empty()) << "the runs left in " << tmp << ":" << left;
}

} // namespace
} // namespace scpdyn
