// Test entry point: MPI and Kokkos are initialised once for every test of the executable.
#include "parallel/Mpi.hpp"

#include <Kokkos_Core.hpp>
#include <gtest/gtest.h>

#include <cstdlib>

int main(int argc, char **argv)
{
  // ctest runs the tests with OMP_PROC_BIND=false but lists them (gtest_discover_tests) without
  // it; Kokkos' warning about the unset variable on stdout would be read as three extra
  // "tests" that run nothing. (OpenMP has read its environment already: this changes no binding.)
  setenv("OMP_PROC_BIND", "false", 0);
  // every Solver of the suite checks that no room writes an early node of the fused step 12
  // without declaring it (integrate/LateNodes.hpp), the scpdyn binaries the tests start too
  setenv("SCPDYN_CHECK_NODE_SWEEP", "1", 0);
  scpdyn::MpiSession mpi(argc, argv); // finalised after Kokkos, when main returns
  Kokkos::initialize(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  const int result = RUN_ALL_TESTS();
  Kokkos::finalize();
  return result;
}
