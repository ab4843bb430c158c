// MPI helpers (src/parallel/Mpi.hpp) and the quiet-output set-up of the MPI test executable.
#include "parallel/ParallelTestUtil.hpp"

#include "integrate/TimeStep.hpp"

#include <cmath>

namespace scpdyn::test
{
namespace
{

/// On ranks other than 0, print failed assertions only (prefixed by the rank), so a 3-rank run
/// reads like a serial one.
class RankFailurePrinter : public ::testing::EmptyTestEventListener
{
public:
  void OnTestPartResult(const ::testing::TestPartResult &r) override
  {
    if (r.failed())
      std::printf("[rank %d] %s:%d: Failure\n%s\n", mpiRank(), r.file_name() ? r.file_name() : "?",
                  r.line_number(), r.summary());
  }
  void OnTestEnd(const ::testing::TestInfo &info) override
  {
    if (info.result()->Failed())
      std::printf("[rank %d] FAILED %s.%s\n", mpiRank(), info.test_suite_name(), info.name());
  }
};

class QuietRanks : public ::testing::Environment
{
public:
  void SetUp() override
  {
    if (mpiRank() == 0)
      return;
    auto &listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
    listeners.Append(new RankFailurePrinter);
  }
};

const auto *const quiet_ranks = ::testing::AddGlobalTestEnvironment(new QuietRanks);

} // namespace

TEST(Mpi, ReductionsAgreeOnEveryRank)
{
  const int rank = mpiRank(), size = mpiSize();
  EXPECT_TRUE(mpiActive());
  EXPECT_GE(rank, 0);
  EXPECT_LT(rank, size);
  // time steps: min is exact
  EXPECT_EQ(allReduceMin(1e-6 * (1.5 + rank)), 1.5e-6);
  EXPECT_EQ(allReduceMax(Real(rank)), Real(size - 1));
  // sum in ascending rank order of non-dyadic values: the reference is the same loop here
  Real ref = 0;
  for (int r = 0; r < size; ++r)
    ref += 1.0 / (3.0 + r);
  const Real s = allReduceSum(1.0 / (3.0 + rank));
  EXPECT_EQ(bits(s), bits(ref));
  const std::vector<Real> root = broadcastFromRoot(std::vector<Real>{s});
  EXPECT_EQ(bits(root[0]), bits(s)); // same bits on every rank
  Real several[2] = {Real(rank), 0.25};
  allReduceSum(several, 2);
  EXPECT_EQ(several[0], Real(size * (size - 1) / 2));
  EXPECT_EQ(several[1], 0.25 * size);
  EXPECT_EQ(allReduceSum((long long)(rank + 1)), (long long)(size * (size + 1) / 2));
  std::array<Real, 3> lo = {Real(rank), -1.0 - rank, 0.5}, hi = {Real(rank) + 2, 1.0, 0.5 + rank};
  allReduceBox(lo, hi);
  EXPECT_EQ(lo, (std::array<Real, 3>{0, -Real(size), 0.5}));
  EXPECT_EQ(hi, (std::array<Real, 3>{Real(size) + 1, 1.0, 0.5 + size - 1}));
  EXPECT_TRUE(allTrue(true));
  EXPECT_FALSE(allTrue(rank != size - 1)); // false on one rank only
}

TEST(Mpi, NextTimeStepReducesLimitsAndSumsInOneCollective)
{
  const int rank = mpiRank(), size = mpiSize();
  TimeStepControls ctl;
  ctl.courant = 0.5;
  TimeStepLimits limits;
  limits.element = 1e-6 * (2.0 + rank);                // rank 0 has the smallest element step
  limits.contact = rank == size - 1 ? 0.75e-6 : 1e300; // the last rank's contact limit
  NodeSums sums;
  sums.kinetic = 1.0 / (3.0 + rank);
  sums.momentum[1] = rank;
  const Real dt = nextTimeStep(limits, ctl, sums, MPI_COMM_WORLD);
  EXPECT_EQ(dt, std::min(1e-6, 0.75e-6)); // 0.5 * 2e-6 on rank 0, or the contact's
  Real ref = 0;
  for (int r = 0; r < size; ++r)
    ref += 1.0 / (3.0 + r);
  EXPECT_EQ(bits(sums.kinetic), bits(ref)); // rank order, the same bits on every rank
  EXPECT_EQ(sums.momentum[1], Real(size * (size - 1) / 2));
  // the contacts' horizon: the elements' own step over all ranks
  EXPECT_EQ(elementStep(limits, ctl, MPI_COMM_WORLD), 2e-6);
  // the first error of any rank reaches every rank
  const std::string e = firstErrorOfAnyRank(rank == size - 1 ? "last rank failed" : "");
  EXPECT_EQ(e, "last rank failed");
  EXPECT_EQ(firstErrorOfAnyRank(""), "");
}

TEST(Mpi, NextTimeStepTellsEveryRankOfAStopSignalOfAnyRank)
{
  // the last rank alone was signalled: every rank learns it from the one collective, and the
  // step is the same as without it; the larger of two signals wins, none leaves 0
  const int rank = mpiRank(), size = mpiSize();
  TimeStepLimits limits;
  limits.element = 1e-6 * (2.0 + rank);
  NodeSums sums;
  int signal = rank == size - 1 ? 15 : 0;
  const Real dt = nextTimeStep(limits, TimeStepControls(), sums, MPI_COMM_WORLD, &signal);
  EXPECT_EQ(signal, 15);
  EXPECT_EQ(dt, 0.5 * 2e-6);
  signal = rank == 0 ? 2 : (rank == size - 1 ? 15 : 0);
  nextTimeStep(limits, TimeStepControls(), sums, MPI_COMM_WORLD, &signal);
  EXPECT_EQ(signal, size == 1 ? 2 : 15);
  signal = 0;
  nextTimeStep(limits, TimeStepControls(), sums, MPI_COMM_WORLD, &signal);
  EXPECT_EQ(signal, 0);
}

} // namespace scpdyn::test
