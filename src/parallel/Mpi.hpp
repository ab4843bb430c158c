#pragma once
/// \file Mpi.hpp
/// \brief Small MPI helpers: rank and size, reductions whose result has the same bits on every
/// rank, and the RAII session that owns MPI_Init/MPI_Finalize.
///
/// Sharing MPI_COMM_WORLD between main programs and tests: exactly one place initialises MPI
/// (the scpdyn binary's main, or tests/main.cpp), before Kokkos::initialize, and finalises it
/// after Kokkos::finalize. `MpiSession` does this and is a no-op when MPI is already
/// initialised, so library code and tests never call MPI_Init themselves; they take an
/// `MPI_Comm` argument that defaults to MPI_COMM_WORLD.
#include "core/Types.hpp"

#include <mpi.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

namespace scpdyn
{

/// \brief Initialises MPI on construction unless it already is, and finalises it on destruction
/// only if this object initialised it. Create it first in main(), before Kokkos.
///
/// A process started without mpirun (a singleton) gets its own Open MPI session directory
/// (`OMPI_MCA_orte_tmpdir_base`, a fresh directory under $TMPDIR or /tmp, removed at the end)
/// unless the variable is set already: Open MPI 4 singletons that start at the same moment race
/// to create the shared /tmp/ompi.<host>.<uid> and the loser aborts in MPI_Init ("A call to
/// mkdir was unable to create the desired directory ... File exists", open-mpi/ompi#8510),
/// which ctest -j2 and a sweep of runs both do. Other MPI libraries ignore the variable.
class MpiSession
{
public:
  MpiSession(int &argc, char **&argv)
  {
    int initialised = 0;
    MPI_Initialized(&initialised);
    if (!initialised)
    {
      useOwnSessionDirectory();
      MPI_Init(&argc, &argv);
      _owner = true;
    }
  }
  ~MpiSession()
  {
    int finalised = 0;
    MPI_Finalized(&finalised);
    if (_owner && !finalised)
      MPI_Finalize();
    if (!_session_dir.empty())
    {
      std::error_code ignored; // a leftover directory in /tmp is no reason to fail a run
      std::filesystem::remove_all(_session_dir, ignored);
    }
  }
  MpiSession(const MpiSession &) = delete;
  MpiSession &operator=(const MpiSession &) = delete;

private:
  void useOwnSessionDirectory()
  {
    // started by a launcher (mpirun, srun): it owns the session directory. A singleton's own
    // MPI_Init sets PMIX_RANK and OMPI_MCA_ess=singleton, which its child processes inherit.
    const char *ess = std::getenv("OMPI_MCA_ess");
    const bool singleton_parent = ess && std::string(ess) == "singleton";
    const bool launched =
        std::getenv("OMPI_COMM_WORLD_SIZE") ||
        ((std::getenv("PMIX_RANK") || std::getenv("PMI_RANK")) && !singleton_parent);
    if (launched || std::getenv("OMPI_MCA_orte_tmpdir_base"))
      return;
    const char *tmp = std::getenv("TMPDIR");
    std::string path = std::string(tmp && *tmp ? tmp : "/tmp") + "/scpdyn-mpi-XXXXXX";
    if (!mkdtemp(path.data()))
      return; // Open MPI's default session directory then
    _session_dir = path;
    setenv("OMPI_MCA_orte_tmpdir_base", path.c_str(), 1);
  }

  bool _owner = false;
  std::string _session_dir;
};

/// \brief True between MPI_Init and MPI_Finalize.
inline bool mpiActive()
{
  int initialised = 0, finalised = 0;
  MPI_Initialized(&initialised);
  MPI_Finalized(&finalised);
  return initialised && !finalised;
}

/// \brief This process's rank in `comm` (0 when MPI is not active).
inline int mpiRank(MPI_Comm comm = MPI_COMM_WORLD)
{
  int r = 0;
  if (mpiActive())
    MPI_Comm_rank(comm, &r);
  return r;
}

/// \brief Number of ranks in `comm` (1 when MPI is not active).
inline int mpiSize(MPI_Comm comm = MPI_COMM_WORLD)
{
  int s = 1;
  if (mpiActive())
    MPI_Comm_size(comm, &s);
  return s;
}

/// \brief Global minimum over the ranks (exact, so every rank gets the same bits): the stable
/// time step of step 12 [s].
inline Real allReduceMin(Real value, MPI_Comm comm = MPI_COMM_WORLD)
{
  Real out = value;
  if (mpiActive())
    MPI_Allreduce(&value, &out, 1, MPI_DOUBLE, MPI_MIN, comm);
  return out;
}

/// \brief Global maximum over the ranks (exact).
inline Real allReduceMax(Real value, MPI_Comm comm = MPI_COMM_WORLD)
{
  Real out = value;
  if (mpiActive())
    MPI_Allreduce(&value, &out, 1, MPI_DOUBLE, MPI_MAX, comm);
  return out;
}

/// \brief In one all-gather: the element-wise global sum of `n` values, added in ascending
/// rank order (0 + v_0 + v_1 + ...), and the global minimum of `m` others. MPI_SUM leaves the
/// order to the library; this way the sums are bitwise the same on every rank and for every run
/// with the same rank count (energies, momenta); a minimum is exact in any order. Cost:
/// (n + m) * size values per rank, fine for the handful of values of a cycle.
inline void allReduceSumMin(Real *sums, int n, Real *mins, int m, MPI_Comm comm = MPI_COMM_WORLD)
{
  const int size = mpiSize(comm);
  const int w = n + m;
  if (size == 1 || w <= 0)
    return;
  std::vector<Real> mine(static_cast<size_t>(w));
  std::vector<Real> all(static_cast<size_t>(w) * static_cast<size_t>(size));
  std::copy(sums, sums + n, mine.begin());
  std::copy(mins, mins + m, mine.begin() + n);
  MPI_Allgather(mine.data(), w, MPI_DOUBLE, all.data(), w, MPI_DOUBLE, comm);
  for (int i = 0; i < n; ++i)
  {
    Real s = -0.0; // the identity of +: a sum of one rank's -0 and the others' -0 stays -0
    for (int r = 0; r < size; ++r)
      s += all[size_t(r) * size_t(w) + size_t(i)];
    sums[i] = s;
  }
  for (int i = 0; i < m; ++i)
    for (int r = 0; r < size; ++r)
      mins[i] = std::min(mins[i], all[size_t(r) * size_t(w) + size_t(n + i)]);
}

/// \brief The message of the lowest rank whose `local` is not empty, on every rank (empty when
/// no rank failed): the ranks of a run that cannot go on all stop with the same message.
inline std::string firstErrorOfAnyRank(const std::string &local, MPI_Comm comm = MPI_COMM_WORLD)
{
  const int rank = mpiRank(comm), size = mpiSize(comm);
  int first = local.empty() ? size : rank;
  MPI_Allreduce(MPI_IN_PLACE, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first == size)
    return std::string();
  int length = int(local.size());
  MPI_Bcast(&length, 1, MPI_INT, first, comm);
  std::string message = local;
  message.resize(size_t(length));
  MPI_Bcast(&message[0], length, MPI_CHAR, first, comm);
  return message;
}

/// \brief The `local` vectors of all ranks concatenated in rank order on rank 0 (empty on the
/// others), with each rank's length in `counts` (rank 0). MPI_COMM_NULL: `local` itself.
inline std::vector<double> gatherToRoot(const std::vector<double> &local, MPI_Comm comm,
                                        std::vector<int> *counts = nullptr)
{
  if (comm == MPI_COMM_NULL)
  {
    if (counts)
      *counts = {int(local.size())};
    return local;
  }
  const int rank = mpiRank(comm), size = mpiSize(comm);
  int mine = int(local.size());
  std::vector<int> n(rank == 0 ? size_t(size) : 0), displs(n.size(), 0);
  MPI_Gather(&mine, 1, MPI_INT, n.data(), 1, MPI_INT, 0, comm);
  for (size_t r = 1; r < n.size(); ++r)
    displs[r] = displs[r - 1] + n[r - 1];
  std::vector<double> all(n.empty() ? 0 : size_t(displs.back() + n.back()));
  MPI_Gatherv(local.data(), mine, MPI_DOUBLE, all.data(), n.data(), displs.data(), MPI_DOUBLE, 0,
              comm);
  if (counts)
    *counts = n;
  return all;
}

/// \brief Element-wise global sum of `n` values in ascending rank order (allReduceSumMin()).
inline void allReduceSum(Real *values, int n, MPI_Comm comm = MPI_COMM_WORLD)
{
  allReduceSumMin(values, n, nullptr, 0, comm);
}

/// \brief Global sum of one value in ascending rank order (see the array version).
inline Real allReduceSum(Real value, MPI_Comm comm = MPI_COMM_WORLD)
{
  allReduceSum(&value, 1, comm);
  return value;
}

/// \brief Integer global sum (exact).
inline long long allReduceSum(long long value, MPI_Comm comm = MPI_COMM_WORLD)
{
  long long out = value;
  if (mpiActive())
    MPI_Allreduce(&value, &out, 1, MPI_LONG_LONG, MPI_SUM, comm);
  return out;
}

/// \brief Global bounding box [m]: lo and hi become the minimum and maximum over the ranks
/// (exact, one message), so every rank derives the same sorting bins from them (step 2, and
/// contact search cycles once nodes move).
inline void allReduceBox(std::array<Real, 3> &lo, std::array<Real, 3> &hi,
                         MPI_Comm comm = MPI_COMM_WORLD)
{
  if (!mpiActive())
    return;
  Real v[6] = {lo[0], lo[1], lo[2], -hi[0], -hi[1], -hi[2]};
  MPI_Allreduce(MPI_IN_PLACE, v, 6, MPI_DOUBLE, MPI_MIN, comm);
  lo = {v[0], v[1], v[2]};
  hi = {-v[3], -v[4], -v[5]};
}

/// \brief True on every rank iff `flag` is true on every rank (collective pass/fail).
inline bool allTrue(bool flag, MPI_Comm comm = MPI_COMM_WORLD)
{
  int in = flag ? 1 : 0, out = in;
  if (mpiActive())
    MPI_Allreduce(&in, &out, 1, MPI_INT, MPI_LAND, comm);
  return out != 0;
}

} // namespace scpdyn
