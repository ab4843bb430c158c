// Google Benchmark of the element step (step 6) and the node kernels (steps 5, 12) on the
// 64^3 hex8 elastic box, called directly on the Solver's Views. Counter ns_per_elem_cycle:
// real time per element per call. Run once per thread count (OMP_NUM_THREADS).
#include "bench_common.hpp"

#include "integrate/NodeUpdate.hpp"
#include "element/ElementForces.hpp"

namespace
{
using namespace scpdyn_bench;

struct KernelSetup
{
  Solver &solver;
  KernelExtras extras;
  explicit KernelSetup(Solver &s) : solver(s), extras(makeKernelExtras(s)) {}
};

KernelSetup &setup()
{
  static KernelSetup *k = nullptr;
  if (!k)
  {
    auto owned = std::make_shared<KernelSetup>(boxSolver("atomic"));
    keepAlive().push_back(owned);
    k = owned.get();
  }
  return *k;
}

/// Element forces scattered with atomic adds into f_int.
void BM_HexKernelAtomic(benchmark::State &state)
{
  KernelSetup &k = setup();
  const ElementControls ctl = controlsOf(k.solver, false);
  for (auto _ : state)
  {
    const Real dt = computeElementForces(k.solver.groups(), ctl, k.solver.nodes(),
                                         k.solver.elements(), k.extras.materials, k.extras.corners)
                        .dt;
    benchmark::DoNotOptimize(dt);
  }
  setCounters(state, k.solver.elements().count);
}

/// The deterministic assembly's element step: one chunk a thread, plain adds, corner stores
/// for the nodes two chunks share (NodeCorners); their gather is timed separately.
void BM_HexKernelCorners(benchmark::State &state)
{
  KernelSetup &k = setup();
  const ElementControls ctl = controlsOf(k.solver, true);
  for (auto _ : state)
  {
    const Real dt = computeElementForces(k.solver.groups(), ctl, k.solver.nodes(),
                                         k.solver.elements(), k.extras.materials, k.extras.corners)
                        .dt;
    benchmark::DoNotOptimize(dt);
  }
  setCounters(state, k.solver.elements().count);
}

/// The corner gather alone (f_int(n) = sum of its corner forces, for the shared nodes).
void BM_GatherCornerForces(benchmark::State &state)
{
  KernelSetup &k = setup();
  for (auto _ : state)
  {
    gatherCornerForces(k.solver.nodes(), k.extras.corners);
    Kokkos::fence();
  }
  setCounters(state, k.solver.elements().count);
}

/// Chunks + gather: the deterministic variant of BM_HexKernelAtomic.
void BM_HexKernelGather(benchmark::State &state)
{
  KernelSetup &k = setup();
  const ElementControls ctl = controlsOf(k.solver, true);
  for (auto _ : state)
  {
    const Real dt = computeElementForces(k.solver.groups(), ctl, k.solver.nodes(),
                                         k.solver.elements(), k.extras.materials, k.extras.corners)
                        .dt;
    gatherCornerForces(k.solver.nodes(), k.extras.corners);
    Kokkos::fence();
    benchmark::DoNotOptimize(dt);
  }
  setCounters(state, k.solver.elements().count);
}

/// Step 5 (zero f_int, and f_ext = m g with loads), per element of the box for comparison.
void BM_ZeroForces(benchmark::State &state, bool loads)
{
  KernelSetup &k = setup();
  const Real g[3] = {0, 0, 0};
  for (auto _ : state)
  {
    zeroForces(k.solver.nodes(), g, loads);
    Kokkos::fence();
  }
  setCounters(state, k.solver.elements().count);
}

/// Step 12 (velocities, positions, energy sums) with zero forces: the nodes stay put.
void BM_UpdateNodes(benchmark::State &state, bool loads)
{
  KernelSetup &k = setup();
  NodeFields nodes = k.solver.nodes();
  // a private copy so the Solver's own state is untouched; bc indices point at value 0
  NodeFields mine = nodes;
  mine.x = VectorView("bench_x", size_t(nodes.count));
  mine.v = VectorView("bench_v", size_t(nodes.count));
  mine.f_int = VectorView("bench_f_int", size_t(nodes.count));
  mine.f_ext = VectorView("bench_f_ext", size_t(nodes.count));
  mine.external_impulse = VectorView("bench_impulse", size_t(nodes.count));
  Kokkos::deep_copy(mine.x, nodes.x);
  BoundaryConditions bc;
  bc.velocity_current = RealView("bench_vbc", 4);
  const Real dt = k.solver.dt();
  for (auto _ : state)
  {
    const NodeSums s = updateNodes(mine, bc, dt, 3, IndexView(), loads);
    benchmark::DoNotOptimize(s.kinetic);
  }
  setCounters(state, k.solver.elements().count);
}

BENCHMARK(BM_HexKernelAtomic)->Apply(configure);
BENCHMARK(BM_HexKernelCorners)->Apply(configure);
BENCHMARK(BM_GatherCornerForces)->Apply(configure);
BENCHMARK(BM_HexKernelGather)->Apply(configure);
// with f_ext (gravity, nodal forces or pressure in the deck) and without (hasExternalLoads())
BENCHMARK_CAPTURE(BM_ZeroForces, Loads, true)->Apply(configure);
BENCHMARK_CAPTURE(BM_ZeroForces, NoLoads, false)->Apply(configure);
BENCHMARK_CAPTURE(BM_UpdateNodes, Loads, true)->Apply(configure);
BENCHMARK_CAPTURE(BM_UpdateNodes, NoLoads, false)->Apply(configure);

} // namespace

SCPDYN_BENCH_MAIN()
