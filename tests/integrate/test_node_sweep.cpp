// Step 12 inside step 6 (integrate/NodeSweep.hpp, numerics.node_update fused): after each block of
// a chunk's elements, the nodes whose last element lies in it are integrated. The early nodes
// must be exactly those one chunk touches and nothing marks late, each integrated after its
// last element; and step 6 with the sweep, then step 12 on the late nodes, must leave x, v,
// both forces and the impulses with the bits of step 6 followed by step 12 on every node, for
// any chunk count, with and without loads, in 2D and 3D (the vector path and the scalar one).
#include "element/StepFixtures.hpp"
#include "integrate/NodeUpdate.hpp"
#include "driver/Solver.hpp"
#include "element/ElementForces.hpp"
#include "input/Deck.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

namespace scpdyn
{
namespace
{

using test::kThreePartsDeck;

const char *kDeck2 = R"(title: node sweep 2D
dimension: 2
time: {end: 1.0, courant: 0.5}
numerics: {scatter: gather}
gravity: [0.0, -9.81]
materials:
  - {name: steel, model: elastic, density: 7850, youngs_modulus: 200.0e9, poisson_ratio: 0.3}
parts:
  - name: a
    material: steel
    mesh: {type: block, element: quad4, elements: [13, 7], size: [1.3, 0.7]}
    initial_velocity: [-50.0, 20.0]
node_sets:
  - {name: wall, box: {min: [0, 0], max: [0, 0.7]}}
boundary_conditions:
  - {type: velocity, node_set: wall, component: x, value: 0.0}
)";

template <class V>
std::vector<Real> flat(const V &v)
{
  auto h = Kokkos::create_mirror_view_and_copy(HostSpace(), v);
  std::vector<Real> out;
  for (size_t n = 0; n < h.extent(0); ++n)
    for (size_t i = 0; i < h.extent(1); ++i)
      out.push_back(h(n, i));
  return out;
}

struct CycleEnd
{
  std::vector<Real> x, v, f_int, f_ext, impulse, stress;
  NodeSums sums;
};

/// Steps 6 and 12 of the solver's next cycle on copies of its state: with `sweep`, step 6
/// integrates the early nodes and step 12 the late ones; without, step 12 all of them.
CycleEnd runSteps(const Solver &s, const NodeCorners &corners, NodeSweep sweep, bool loads)
{
  const NodeFields n = test::copyNodeState(s.nodes());
  const ElementFields el = test::copyElementState(s.elements());
  const Deck &d = s.deck();
  BoundaryConditions bc; // the wall holds x at 0: one value, 0
  bc.velocity_current = RealView("vbc", 1);
  const Real *g = d.gravity.data();
  if (sweep.active)
  {
    sweep.node = nodeIntegrator(n, bc.velocity_current, s.dt(), IndexView(), g);
    sweep.loads = loads;
  }
  computeElementForces(s.groups(), test::gatherControls(s), n, el, s.materials(), corners, sweep);
  gatherCornerForces(n, corners);
  CycleEnd r;
  r.sums = updateNodes(n, bc, s.dt(), d.dimension, IndexView(), loads, g,
                       sweep.active ? &sweep.late_runs : nullptr);
  if (sweep.active)
    r.sums += sweepSums(sweep);
  Kokkos::fence();
  r.x = flat(n.x);
  r.v = flat(n.v);
  r.f_int = flat(n.f_int);
  r.f_ext = flat(n.f_ext);
  r.impulse = flat(n.external_impulse);
  r.stress = flat(el.stress);
  return r;
}

/// Every 29th node marked late by the caller (as contact or a load would). 29 divides no row of
/// the decks' blocks, so most constrained nodes are not among them and the sweep must find those;
/// and runs of early nodes stay long enough for whole packs (runFreeNodes), not only tails.
std::vector<char> callerLate(Index count)
{
  std::vector<char> late(size_t(count), 0);
  for (Index n = 3; n < count; n += 29)
    late[size_t(n)] = 1;
  return late;
}

TEST(NodeSweep, EarlyNodesAreIntegratedOnceAfterTheirLastElement)
{
  Solver s(parseDeckString(kThreePartsDeck, "sweep3.yaml"));
  auto conn = Kokkos::create_mirror_view_and_copy(HostSpace(), s.elements().conn);
  auto bc = Kokkos::create_mirror_view_and_copy(HostSpace(), s.nodes().bc);
  const Index count = s.nodes().count;
  const std::vector<char> late = callerLate(count);
  for (int chunks : {1, 2, 3, 7})
  {
    const NodeSweep sweep = makeNodeSweep(s.elements(), s.groups(), s.nodes(), chunks, late);
    ASSERT_TRUE(sweep.active);
    // by brute force: the chunks touching each node, its last element, and that element's block
    std::vector<std::set<int>> touched(static_cast<size_t>(count));
    std::vector<Index> block(size_t(count), -1);
    auto base = Kokkos::create_mirror_view_and_copy(HostSpace(), sweep.block_base);
    int chunk = 0;
    for (const auto &g : s.groups())
      for (int c = 0; c < chunks; ++c, ++chunk)
        for (Index e = chunkBegin(g, chunks, c); e < chunkBegin(g, chunks, c + 1); ++e)
          for (int a = 0; a < kMaxElementNodes && conn(e, a) >= 0; ++a)
          {
            touched[size_t(conn(e, a))].insert(chunk);
            block[size_t(conn(e, a))] =
                base(chunk) + (e - chunkBegin(g, chunks, c)) / NodeSweep::kSweepBlock;
          }
    std::vector<Index> expected_block(size_t(count), -1); // -1: late
    for (Index n = 0; n < count; ++n)
      if (touched[size_t(n)].size() == 1 && !late[size_t(n)] && bc(n, 0) < 0 && bc(n, 1) < 0 &&
          bc(n, 2) < 0)
        expected_block[size_t(n)] = block[size_t(n)];
    std::vector<Index> got_block(size_t(count), -2); // -2: in no list
    auto offsets = Kokkos::create_mirror_view_and_copy(HostSpace(), sweep.block_runs);
    auto runs = Kokkos::create_mirror_view_and_copy(HostSpace(), sweep.runs);
    auto late_runs = Kokkos::create_mirror_view_and_copy(HostSpace(), sweep.late_runs);
    int listed_twice = 0;
    for (Index b = 0; b + 1 < Index(offsets.extent(0)); ++b)
      for (Index r = offsets(b); r < offsets(b + 1); ++r)
        for (Index n = runs(r, 0); n < runs(r, 1); ++n)
          listed_twice += got_block[size_t(n)] != -2 ? 1 : 0, got_block[size_t(n)] = b;
    for (size_t r = 0; r < late_runs.extent(0); ++r)
    {
      EXPECT_LE(late_runs(r, 1) - late_runs(r, 0), 256);
      for (Index n = late_runs(r, 0); n < late_runs(r, 1); ++n)
        listed_twice += got_block[size_t(n)] != -2 ? 1 : 0, got_block[size_t(n)] = -1;
    }
    EXPECT_EQ(listed_twice, 0) << chunks << " chunks";
    EXPECT_EQ(got_block, expected_block) << chunks << " chunks";
    long early = 0;
    for (Index b : expected_block)
      early += b >= 0 ? 1 : 0;
    EXPECT_GT(early, count / 3) << chunks << " chunks"; // the sweep has work to do
  }
}

void expectSameCycleEnd(const char *deck, const char *name)
{
  Solver s(parseDeckString(deck, name));
  for (int k = 0; k < 12; ++k) // stress, hourglass resistances, plastic flow, impulses
    s.cycle();
  const std::vector<char> late = callerLate(s.nodes().count);
  Real mass = 0;
  auto m = Kokkos::create_mirror_view_and_copy(HostSpace(), s.nodes().mass);
  for (size_t n = 0; n < m.extent(0); ++n)
    mass += m(n);
  for (bool loads : {false, true})
    for (int chunks : {1, 2, 3, 7})
    {
      const NodeCorners corners =
          makeNodeCorners(s.elements(), s.groups(), s.nodes().count, chunks);
      const CycleEnd apart = runSteps(s, corners, NodeSweep(), loads);
      const NodeSweep sweep = makeNodeSweep(s.elements(), s.groups(), s.nodes(), chunks, late);
      const CycleEnd fused = runSteps(s, corners, sweep, loads);
      const std::string where = std::string(name) + ", " + std::to_string(chunks) +
                                " chunks, loads " + std::to_string(loads);
      EXPECT_EQ(fused.x, apart.x) << where;
      EXPECT_EQ(fused.v, apart.v) << where;
      EXPECT_EQ(fused.f_int, apart.f_int) << where;
      EXPECT_EQ(fused.f_ext, apart.f_ext) << where;
      EXPECT_EQ(fused.impulse, apart.impulse) << where;
      EXPECT_EQ(fused.stress, apart.stress) << where;
      // the sums add the same terms in another order: round-off of the largest term
      const Real k = apart.sums.kinetic;
      ASSERT_GT(k, 0) << where;
      EXPECT_NEAR(fused.sums.kinetic, k, 1e-13 * k) << where;
      EXPECT_NEAR(fused.sums.kinetic_mid, apart.sums.kinetic_mid, 1e-13 * k) << where;
      EXPECT_NEAR(fused.sums.external_work, apart.sums.external_work, 1e-13 * k) << where;
      // the momenta, against sum |m v| <= sqrt(2 K M) (Cauchy-Schwarz), M the total mass
      const Real p_scale = std::sqrt(2 * k * mass);
      for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(fused.sums.momentum[i], apart.sums.momentum[i], 1e-13 * p_scale) << where;
      if (loads)
        EXPECT_NE(apart.sums.external_work, 0) << where; // gravity did work
    }
}

TEST(NodeSweep, StepSixWithTheSweepGivesTheBitsOfStepTwelveAfterIt3D)
{
  expectSameCycleEnd(kThreePartsDeck, "sweep3.yaml");
}

TEST(NodeSweep, StepSixWithTheSweepGivesTheBitsOfStepTwelveAfterIt2D)
{
  expectSameCycleEnd(kDeck2, "sweep2.yaml");
}

} // namespace
} // namespace scpdyn
