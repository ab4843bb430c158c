#pragma once
/// \file bench_common.hpp
/// \brief Shared set-up of the perf/ drivers: the box deck, a Solver per scatter mode, the
/// per-element-cycle counters, a malloc counter and main() (Kokkos + Google Benchmark).
/// Include from exactly one translation unit per executable (it defines malloc & co.).
#include "driver/Solver.hpp"
#include "input/Deck.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>
#include <vector>

// ---- allocation counter -------------------------------------------------------------------
// Every heap allocation of the process (operator new, Kokkos View allocations, libc) goes
// through these glibc entry points, so a cycle that allocates shows up as allocs_per_cycle > 0.
extern "C" void *__libc_malloc(size_t);
extern "C" void *__libc_calloc(size_t, size_t);
extern "C" void *__libc_realloc(void *, size_t);
extern "C" void *__libc_memalign(size_t, size_t);
namespace scpdyn_bench
{
inline std::atomic<long> g_allocations{0};
}
extern "C" void *malloc(size_t n)
{
  scpdyn_bench::g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(n);
}
extern "C" void *calloc(size_t n, size_t s)
{
  scpdyn_bench::g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_calloc(n, s);
}
extern "C" void *realloc(void *p, size_t n)
{
  scpdyn_bench::g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_realloc(p, n);
}
extern "C" int posix_memalign(void **p, size_t a, size_t n)
{
  scpdyn_bench::g_allocations.fetch_add(1, std::memory_order_relaxed);
  *p = __libc_memalign(a, n);
  return *p || n == 0 ? 0 : 12; // ENOMEM
}
extern "C" void *aligned_alloc(size_t a, size_t n)
{
  scpdyn_bench::g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_memalign(a, n);
}

namespace scpdyn_bench
{
using namespace scpdyn;

/// \brief The box has boxCells()^3 hex8 elements: 64, or SCPDYN_BENCH_CELLS (e.g. 16 for a
/// quick run under valgrind --tool=callgrind).
inline int boxCells()
{
  const char *env = std::getenv("SCPDYN_BENCH_CELLS");
  return env && std::atoi(env) > 0 ? std::atoi(env) : 64;
}

/// \brief Objects holding Views, released by main() before Kokkos::finalize.
inline std::vector<std::shared_ptr<void>> &keepAlive()
{
  static std::vector<std::shared_ptr<void>> objects;
  return objects;
}

/// \brief The perf deck (same physics as perf/box64.yaml): elastic steel cube at 10 m/s
/// against a rigid wall at x = 0.
inline std::string boxDeck(int n, const std::string &scatter)
{
  const std::string cells = std::to_string(n);
  return "title: bench box\n"
         "dimension: 3\n"
         "time: {end: 1.0, courant: 0.5}\n"
         "numerics: {scatter: " +
         scatter +
         "}\n"
         "materials:\n"
         "  - {name: steel, model: elastic, density: 7850, youngs_modulus: 200.0e9, "
         "poisson_ratio: 0.3}\n"
         "parts:\n"
         "  - name: box\n"
         "    material: steel\n"
         "    mesh: {type: block, element: hex8, elements: [" +
         cells + ", " + cells + ", " + cells +
         "], size: [1, 1, 1]}\n"
         "    initial_velocity: [-10.0, 0.0, 0.0]\n"
         "node_sets:\n"
         "  - {name: wall, box: {min: [0, 0, 0], max: [0, 1, 1]}}\n"
         "boundary_conditions:\n"
         "  - {type: velocity, node_set: wall, component: x, value: 0.0}\n";
}

/// \brief One Solver per scatter mode, built once and advanced 20 cycles (or
/// SCPDYN_BENCH_WARMUP) so that the wave (and with it the compressive bulk-viscosity branch)
/// is in the box. Without `row_packs` every pack of step 6 takes the general path (per-lane
/// node reads and adds), as the packs of a mesh not numbered in rows do.
inline Solver &boxSolver(const std::string &scatter, bool row_packs = true)
{
  static std::map<std::string, Solver *> cache;
  Solver *&s = cache[scatter + (row_packs ? "" : "/general")];
  if (!s)
  {
    auto owned =
        std::make_shared<Solver>(parseDeckString(boxDeck(boxCells(), scatter), "bench_box.yaml"));
    if (!row_packs)
    {
      auto row_pack = owned->elements().row_pack; // a handle: the Solver's own flags
      Kokkos::deep_copy(row_pack, std::uint8_t(0));
    }
    const char *env = std::getenv("SCPDYN_BENCH_WARMUP");
    const int warmup = env ? std::atoi(env) : 20;
    for (int k = 0; k < warmup; ++k)
      owned->cycle();
    s = owned.get();
    keepAlive().push_back(owned);
  }
  return *s;
}

/// \brief Kernel inputs: the Solver's materials, and the corners it keeps private, rebuilt
/// here from its connectivity exactly as Setup.cpp builds them.
struct KernelExtras
{
  DeviceView<MaterialParams *> materials;
  NodeCorners corners;
};

inline KernelExtras makeKernelExtras(const Solver &s)
{
  KernelExtras k;
  k.materials = s.materials();
  k.corners = makeNodeCorners(s.elements(), s.groups(), s.nodes().count, ExecSpace().concurrency());
  return k;
}

/// \brief The element controls the Solver would use this cycle, with the given assembly.
inline ElementControls controlsOf(const Solver &s, bool gather)
{
  ElementControls c = s.elementControls();
  c.gather = gather;
  return c;
}

/// \brief Counters: ns_per_elem_cycle (seconds per element per iteration, real time, shown
/// as ns; the Kokkos threads are not benchmark threads), the thread count and the elements.
inline void setCounters(benchmark::State &state, double elements_per_iteration)
{
  state.counters["ns_per_elem_cycle"] =
      benchmark::Counter(elements_per_iteration * double(state.iterations()),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["threads"] = double(ExecSpace().concurrency());
  state.counters["elements"] = elements_per_iteration;
}

/// \brief Repetition statistic "min": on a shared machine the load only ever slows a run
/// down, so the fastest repetition is the best estimate of the unloaded time.
inline double minimum(const std::vector<double> &v)
{
  return v.empty() ? 0.0 : *std::min_element(v.begin(), v.end());
}

/// \brief Every perf benchmark: real time (Kokkos threads are not benchmark threads), ms,
/// and the "min" statistic next to mean/median when repeated.
inline void configure(benchmark::internal::Benchmark *b)
{
  b->UseRealTime()->Unit(benchmark::kMillisecond)->ComputeStatistics("min", minimum);
}

} // namespace scpdyn_bench

/// Kokkos reads OMP_NUM_THREADS at initialize: run one process per thread count.
#define SCPDYN_BENCH_MAIN()                                                                        \
  int main(int argc, char **argv)                                                                  \
  {                                                                                                \
    Kokkos::initialize(argc, argv);                                                                \
    int rc = 0;                                                                                    \
    {                                                                                              \
      benchmark::Initialize(&argc, argv);                                                          \
      if (benchmark::ReportUnrecognizedArguments(argc, argv))                                      \
        rc = 1;                                                                                    \
      else                                                                                         \
        benchmark::RunSpecifiedBenchmarks();                                                       \
      benchmark::Shutdown();                                                                       \
      scpdyn_bench::keepAlive().clear();                                                           \
    }                                                                                              \
    Kokkos::finalize();                                                                            \
    return rc;                                                                                     \
  }
