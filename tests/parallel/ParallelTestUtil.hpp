#pragma once
// Helpers of the MPI tests: meshes, collective pass/fail, gathering vectors to every rank.
// Every rank runs every test in the same order, so collectives match; a check that could fail
// on one rank only uses EXPECT (not ASSERT) before any later collective, or agrees first.
#include "mesh/MeshGenerators.hpp"
#include "mesh/MeshOps.hpp"
#include "parallel/Mpi.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace scpdyn::test
{

inline HostMesh quadBlock(int nx, int ny)
{
  HostMesh m;
  appendBlock(m, "block", ElementType::Quad4, {nx, ny, 1}, {0, 0, 0}, {1.0, 0.8, 1.0});
  return m;
}

inline HostMesh hexBlock(int nx, int ny, int nz)
{
  HostMesh m;
  appendBlock(m, "block", ElementType::Hex8, {nx, ny, nz}, {0, 0, 0}, {1.0, 0.9, 0.8});
  return m;
}

/// Bit pattern of a double: == on it is bitwise equality (+0 and -0 differ, NaN == NaN).
inline std::uint64_t bits(double x)
{
  std::uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

/// Rank 0's copy of `v` on every rank.
template <class T>
std::vector<T> broadcastFromRoot(std::vector<T> v)
{
  long long n = (long long)v.size();
  MPI_Bcast(&n, 1, MPI_LONG_LONG, 0, MPI_COMM_WORLD);
  v.resize(size_t(n));
  MPI_Bcast(v.data(), int(n * sizeof(T)), MPI_BYTE, 0, MPI_COMM_WORLD);
  return v;
}

/// Element-wise integer sum over the ranks.
inline std::vector<int> sumOverRanks(std::vector<int> v)
{
  MPI_Allreduce(MPI_IN_PLACE, v.data(), int(v.size()), MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  return v;
}

/// Concatenation of every rank's `v` in rank order, on every rank.
template <class T>
std::vector<T> allGatherV(const std::vector<T> &v)
{
  const int size = mpiSize();
  int mine = int(v.size() * sizeof(T));
  std::vector<int> counts(static_cast<size_t>(size)), displs(static_cast<size_t>(size), 0);
  MPI_Allgather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
  for (int r = 1; r < size; ++r)
    displs[size_t(r)] = displs[size_t(r - 1)] + counts[size_t(r - 1)];
  std::vector<T> out(size_t(displs.back() + counts.back()) / sizeof(T));
  MPI_Allgatherv(v.data(), mine, MPI_BYTE, out.data(), counts.data(), displs.data(), MPI_BYTE,
                 MPI_COMM_WORLD);
  return out;
}

/// A mesh and its element -> rank map for mpiSize() ranks (LocalDomain and NodeHalo tests).
struct DecomposedCase
{
  std::string name;
  HostMesh mesh;
  std::vector<int> rank;
};

/// METIS and round-robin decompositions of quad, hex and merged-brick meshes with node and
/// face sets (defined in test_local_domain.cpp).
std::vector<DecomposedCase> decomposedCases();

/// Print on rank 0 only (the numbers the report quotes).
#define SCPDYN_ROOT_PRINT(...)                                                                     \
  do                                                                                               \
  {                                                                                                \
    if (::scpdyn::mpiRank() == 0)                                                                  \
    {                                                                                              \
      std::printf(__VA_ARGS__);                                                                    \
      std::fflush(stdout);                                                                         \
    }                                                                                              \
  } while (0)

} // namespace scpdyn::test
