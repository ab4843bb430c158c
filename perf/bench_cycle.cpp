// Google Benchmark of one whole cycle (Solver::cycle(), the 13 steps) on the 64^3 hex8
// elastic box, atomic scatter against the corner gather. Counters: ns_per_elem_cycle (real
// time) and allocs_per_cycle (heap allocations inside the cycle; the goal is 0).
#include "bench_common.hpp"

namespace
{
using namespace scpdyn_bench;

void cycleBenchmark(benchmark::State &state, const std::string &scatter)
{
  Solver &s = boxSolver(scatter);
  const long allocs_before = g_allocations.load();
  for (auto _ : state)
    s.cycle();
  const long allocs = g_allocations.load() - allocs_before;
  setCounters(state, s.elements().count);
  state.counters["allocs_per_cycle"] = double(allocs) / double(state.iterations());
}

void BM_CycleAtomic(benchmark::State &state) { cycleBenchmark(state, "atomic"); }
void BM_CycleGather(benchmark::State &state) { cycleBenchmark(state, "gather"); }

BENCHMARK(BM_CycleAtomic)->Apply(configure);
BENCHMARK(BM_CycleGather)->Apply(configure);

} // namespace

SCPDYN_BENCH_MAIN()
