// Google Benchmark of the common-plane contact (docs/theory.md 3, Appendix A) through the
// library's public contact functions:
//  * detection (computeFaceGeometry + sortFacesIntoBins + findCandidatePairs, the work of a
//    search cycle) on a fully jointed grid of 1e3 to 1e6 faces, 2D (quad cells) and 3D (hex
//    cells): counter faces_per_s should be flat in the size (linear scaling);
//  * the per-cycle CP update (ContactSystem::computeForces on a non-search cycle: v*, sub-steps
//    A-E for every CP, the constraint passes of sticky/slide-line, checks, scatter, energy) on a
//    jointed brick wall built by the Solver from a deck: counter ns_per_cp_cycle.
// Results: perf/README.md ("Where the time goes"); every measurement: perf/results/log.md.
#include "bench_common.hpp"

#include "contact/ContactSearch.hpp"
#include "contact/ContactSetup.hpp"
#include "contact/ContactSystem.hpp"
#include "mesh/MeshOps.hpp"

#include <cmath>
#include <ctime>

namespace
{
using namespace scpdyn_bench;

/// Process CPU time [s] (all threads): on a shared, loaded machine the real time of a
/// one-thread run grows with the load, its CPU time does not.
double cpuSeconds()
{
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// ---- detection on a synthetic jointed grid -------------------------------------------------

/// Every field of ContactFaceData is allocated by allocateFaces and filled as buildContactFaces
/// fills it for a serial run (a field added there with a non-zero value must be set here too).
/// Cells of edge h on an n^dim lattice, every cell with its own nodes, every cell face a
/// contact face (what a jointed rock mass of one-element blocks gives): 4 n^2 or 6 n^3 faces,
/// each interior face touching exactly one other.
struct JointedGrid
{
  int dim = 2;
  ContactFaceData faces;
  NodeFields nodes;
};

JointedGrid makeGrid(int dim, int n)
{
  const Real h = 0.01;
  const ElementType type = dim == 2 ? ElementType::Quad4 : ElementType::Hex8;
  const int npe = dim == 2 ? 4 : 8, nf = facesPerElement(type), npf = dim == 2 ? 2 : 4;
  const Index cells = dim == 2 ? Index(n) * n : Index(n) * n * n;
  const Index num_nodes = cells * npe, num_faces = cells * nf;
  JointedGrid g;
  g.dim = dim;
  g.nodes.count = num_nodes;
  g.nodes.x = VectorView("grid_x", size_t(num_nodes));
  g.nodes.v = VectorView("grid_v", size_t(num_nodes));
  g.nodes.mass = RealView("grid_mass", size_t(num_nodes));
  auto hx = Kokkos::create_mirror_view(g.nodes.x);
  // local node corners of Quad4 (counter-clockwise) and Hex8 (bottom then top), as the mesh
  // generators number them
  const int corner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                            {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (Index c = 0; c < cells; ++c)
  {
    const Index i = c % n, j = (c / n) % n, k = dim == 3 ? c / (Index(n) * n) : 0;
    for (int a = 0; a < npe; ++a)
    {
      hx(c * npe + a, 0) = (i + corner[a][0]) * h;
      hx(c * npe + a, 1) = (j + corner[a][1]) * h;
      hx(c * npe + a, 2) = dim == 3 ? (k + corner[a][2]) * h : 0.0;
    }
  }
  Kokkos::deep_copy(g.nodes.x, hx);
  Kokkos::deep_copy(g.nodes.mass, 1.0);

  ContactFaceData &F = g.faces;
  // every per-face View, zeroed: every face on the first surface and part, not rigid, no ghost
  // faces (a serial run); keys as ContactSetup builds them (element * 8 + local face); back only
  // matters in 1D
  allocateFaces(F, size_t(num_faces));
  F.params = DeviceView<JointParams *>("grid_params", 1);
  F.nodes_used = IndexView("grid_nodes_used", size_t(num_nodes));
  Kokkos::deep_copy(F.active, Index(1));
  Kokkos::deep_copy(F.back, Index(-1));
  Kokkos::deep_copy(F.density, 2600.0);
  auto hn = Kokkos::create_mirror_view(F.nodes);
  auto hnn = Kokkos::create_mirror_view(F.num_nodes);
  auto he = Kokkos::create_mirror_view(F.element);
  auto hk = Kokkos::create_mirror_view(F.key);
  for (Index c = 0; c < cells; ++c)
    for (int f = 0; f < nf; ++f)
    {
      const Index q = c * nf + f;
      for (int a = 0; a < kMaxFaceNodes; ++a)
        hn(q, a) = a < npf ? c * npe + faceLocalNode(type, f, a) : -1;
      hnn(q) = npf;
      he(q) = c;
      hk(q) = long(c) * 8 + f;
    }
  Kokkos::deep_copy(F.nodes, hn);
  Kokkos::deep_copy(F.num_nodes, hnn);
  Kokkos::deep_copy(F.element, he);
  Kokkos::deep_copy(F.key, hk);
  Kokkos::deep_copy(F.mass, 1.0);
  Kokkos::deep_copy(F.depth, h); // a cell's thickness behind each face
  auto hp = Kokkos::create_mirror_view(F.params);
  hp(0) = jointParamsOf(SurfaceSpec{}, 0);
  Kokkos::deep_copy(F.params, hp);
  auto hu = Kokkos::create_mirror_view(F.nodes_used);
  for (Index k = 0; k < num_nodes; ++k)
    hu(k) = k;
  Kokkos::deep_copy(F.nodes_used, hu);
  return g;
}

/// Lattice size for about `faces` faces.
int gridSize(int dim, double faces)
{
  return dim == 2 ? int(std::lround(std::sqrt(faces / 4.0)))
                  : int(std::lround(std::cbrt(faces / 6.0)));
}

void BM_Detection(benchmark::State &state)
{
  const int dim = int(state.range(0));
  const JointedGrid g = makeGrid(dim, gridSize(dim, double(state.range(1))));
  const Real dt = 1e-7;
  FaceGeometryData G;
  FaceBins bins;
  Index pairs = 0;
  const double cpu0 = cpuSeconds();
  for (auto _ : state)
  {
    computeFaceGeometry(g.faces, g.nodes, dt, dim, false, G);
    sortFacesIntoBins(G, g.faces.count, dim, 2.0 * G.h_max, bins);
    const CandidatePairs P = findCandidatePairs(g.faces, G, bins, g.nodes, dt, dim, false, G.h_max);
    pairs = P.count;
    Kokkos::fence();
  }
  const double cpu = cpuSeconds() - cpu0;
  state.counters["faces_per_cpu_s"] = double(g.faces.count) * double(state.iterations()) / cpu;
  state.counters["faces"] = double(g.faces.count);
  state.counters["pairs"] = double(pairs);
  state.counters["faces_per_s"] = benchmark::Counter(
      double(g.faces.count) * double(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["threads"] = double(ExecSpace().concurrency());
}

// ---- the per-cycle CP update on a jointed brick wall ---------------------------------------

std::string wallDeck(int dim, int n, const std::string &option)
{
  const std::string N = std::to_string(n);
  const bool d3 = dim == 3;
  return std::string("title: bench contact wall\n") + "dimension: " + std::to_string(dim) +
         "\ntime: {end: 1.0}\n"
         "materials:\n"
         "  - {name: rock, model: elastic, density: 2600, youngs_modulus: 50.0e9, poisson_ratio: "
         "0.25}\n"
         "parts:\n"
         "  - name: wall\n"
         "    material: rock\n"
         "    mesh: {type: brick_wall, element: " +
         (d3 ? "hex8" : "quad4") + ", elements: " + (d3 ? "[1, 1, 1]" : "[1, 1]") +
         ", brick_size: " + (d3 ? "[0.01, 0.01, 0.01]" : "[0.01, 0.01]") +
         ", count: " + (d3 ? "[" + N + ", " + N + ", " + N + "]" : "[" + N + ", " + N + "]") +
         ", stagger: 0.0}\n"
         "contact:\n"
         "  search_interval: 1000000000\n"
         "  surfaces:\n"
         "    - {name: joints, part: \"wall*\", option: " +
         option + "}\n";
}

struct WallCase
{
  std::shared_ptr<Solver> solver;
  std::shared_ptr<ContactSystem> contact;
  BoundaryConditions bc;
  std::vector<Index> h2d;
  std::vector<HostFace> external;
  std::map<std::string, std::vector<HostFace>> face_sets;
};

/// The Solver sets the wall up; the contact system is built here from the same inputs as
/// Solver::setupContact (the Solver's own one is not reachable for writing), detection runs
/// once (cycle 0), then every benchmark iteration is a non-search cycle.
WallCase &wallCase(int dim, int n, const std::string &option)
{
  static std::map<std::string, WallCase *> cache;
  const std::string key = std::to_string(dim) + "/" + std::to_string(n) + "/" + option;
  WallCase *&w = cache[key];
  if (w)
    return *w;
  auto owned = std::make_shared<WallCase>();
  owned->solver =
      std::make_shared<Solver>(parseDeckString(wallDeck(dim, n, option), "bench_wall.yaml"));
  const Solver &s = *owned->solver;
  owned->external = extractExternalFaces(s.mesh());
  for (Index e = 0; e < s.mesh().numElements(); ++e)
    owned->h2d.push_back(s.deviceElement(e));
  ContactMeshInput in;
  in.deck = &s.deck();
  in.mesh = &s.mesh();
  in.external_faces = &owned->external;
  in.face_sets = &owned->face_sets;
  in.host_to_device_element = &owned->h2d;
  in.nodes = s.nodes();
  in.elems = s.elements();
  owned->contact = std::make_shared<ContactSystem>(in);
  // a slow converging velocity field (1e-3 m/s per m towards the centre): every joint is
  // loading, by far too little to move within a benchmark
  NodeFields nodes = s.nodes();
  auto x = nodes.x, v = nodes.v;
  const Real c = 0.5 * 0.01 * n;
  Kokkos::parallel_for(
      "bench_wall_velocity", Kokkos::RangePolicy<ExecSpace>(0, nodes.count),
      KOKKOS_LAMBDA(const Index k) {
        for (int d = 0; d < 3; ++d)
          v(k, d) = -1e-3 * (x(k, d) - c);
      });
  const Real dt = 1e-7;
  owned->contact->sortIntoBins(nodes, dt, 0);
  const ContactFailure f = owned->contact->computeForces(nodes, owned->bc, dt, 0, 0.0);
  if (f.failed)
    throw std::runtime_error("bench wall: " + f.message);
  w = owned.get();
  keepAlive().push_back(owned);
  return *w;
}

const char *kOptions[] = {"implicit", "explicit", "sticky", "slide_line"};

void BM_CpUpdate(benchmark::State &state)
{
  const int dim = int(state.range(0)), n = int(state.range(1));
  const std::string option = kOptions[state.range(2)];
  WallCase &w = wallCase(dim, n, option);
  const NodeFields &nodes = w.solver->nodes();
  const Real dt = 1e-7;
  long cycle = 1;
  const double cpu0 = cpuSeconds();
  for (auto _ : state)
  {
    const ContactFailure f = w.contact->computeForces(nodes, w.bc, dt, cycle++, 0.0);
    if (f.failed)
    {
      state.SkipWithError(f.message.c_str());
      break;
    }
    Kokkos::fence();
  }
  const double cpu = cpuSeconds() - cpu0;
  const double cps = double(w.contact->count());
  state.counters["cpu_ns_per_cp_cycle"] = 1e9 * cpu / (cps * double(state.iterations()));
  state.SetLabel(option);
  state.counters["cps"] = cps;
  state.counters["ns_per_cp_cycle"] = benchmark::Counter(
      cps * double(state.iterations()), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["threads"] = double(ExecSpace().concurrency());
}

void detectionArgs(benchmark::internal::Benchmark *b)
{
  for (int dim : {2, 3})
    for (long faces : {1000L, 10000L, 100000L, 1000000L})
      b->Args({dim, faces});
}

void cpArgs(benchmark::internal::Benchmark *b)
{
  // 2D: n^2 bricks, about 2 n^2 CPs; 3D: n^3 bricks, about 3 n^3 CPs
  for (int opt = 0; opt < 4; ++opt)
  {
    for (int n : {22, 71, 224})
      b->Args({2, n, opt});
    for (int n : {7, 15, 32})
      b->Args({3, n, opt});
  }
}

BENCHMARK(BM_Detection)
    ->Apply(detectionArgs)
    ->ArgNames({"dim", "faces"})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CpUpdate)
    ->Apply(cpArgs)
    ->ArgNames({"dim", "n", "option"})
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);

} // namespace

SCPDYN_BENCH_MAIN()
