// Google Benchmark of one whole cycle (Solver::cycle(), the 13 steps) on the 64^3 hex8
// elastic box, atomic scatter against the corner gather, with row packs (the built-in block
// mesh) and without (the general path of step 6). Counters: ns_per_elem_cycle (real
// time) and allocs_per_cycle (heap allocations inside the cycle; the goal is 0).
#include "bench_common.hpp"

namespace
{
using namespace scpdyn_bench;

void cycleBenchmark(benchmark::State &state, const std::string &scatter, bool row_packs = true)
{
  Solver &s = boxSolver(scatter, row_packs);
  const long allocs_before = g_allocations.load();
  for (auto _ : state)
    s.cycle();
  const long allocs = g_allocations.load() - allocs_before;
  setCounters(state, s.elements().count);
  state.counters["allocs_per_cycle"] = double(allocs) / double(state.iterations());
}

void BM_CycleAtomic(benchmark::State &state) { cycleBenchmark(state, "atomic"); }
void BM_CycleGather(benchmark::State &state) { cycleBenchmark(state, "gather"); }
// the same without row packs: a mesh whose node numbers do not run along element rows
void BM_CycleAtomicGeneral(benchmark::State &state) { cycleBenchmark(state, "atomic", false); }
void BM_CycleGatherGeneral(benchmark::State &state) { cycleBenchmark(state, "gather", false); }

BENCHMARK(BM_CycleAtomic)->Apply(configure);
BENCHMARK(BM_CycleGather)->Apply(configure);
BENCHMARK(BM_CycleAtomicGeneral)->Apply(configure);
BENCHMARK(BM_CycleGatherGeneral)->Apply(configure);

} // namespace

SCPDYN_BENCH_MAIN()
