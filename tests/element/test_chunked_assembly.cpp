// The deterministic assembly (numerics.scatter gather): step 6 in C chunks, plain adds for the
// nodes of one chunk, corner stores + gather for the nodes two chunks share. The forces and
// the element state must be the same bits for every chunk count, C = 1 being the plain
// one-thread loop; and the shared nodes must be exactly those two chunks touch.
#include "StepFixtures.hpp"
#include "driver/Solver.hpp"
#include "element/ElementForces.hpp"
#include "input/Deck.hpp"

#include <gtest/gtest.h>

#include <set>
#include <vector>

namespace scpdyn
{
namespace
{

using test::gatherControls;
using test::kThreePartsDeck;

struct StepResult
{
  std::vector<Real> f_int, stress, energy, hourglass;
};

/// Step 6 on copies of the state; with `row_packs` false, every pack takes the general path.
StepResult runStep(const Solver &s, const ElementControls &ctl, const NodeCorners &corners,
                   const DeviceView<MaterialParams *> &materials, bool row_packs = true)
{
  const ElementFields &el = s.elements();
  const NodeFields &nodes = s.nodes();
  // the step changes the element state: run it on a copy of every state View
  ElementFields copy = test::copyElementState(el);
  if (!row_packs)
    copy.row_pack = DeviceView<std::uint8_t *>("no_row_packs", el.row_pack.extent(0));
  NodeFields n = nodes;
  n.f_int = VectorView("f_int", size_t(nodes.count));
  computeElementForces(s.groups(), ctl, n, copy, materials, corners);
  gatherCornerForces(n, corners);
  Kokkos::fence();
  StepResult r;
  auto f = Kokkos::create_mirror_view_and_copy(HostSpace(), n.f_int);
  auto st = Kokkos::create_mirror_view_and_copy(HostSpace(), copy.stress);
  auto e = Kokkos::create_mirror_view_and_copy(HostSpace(), copy.energy);
  auto hg = Kokkos::create_mirror_view_and_copy(HostSpace(), copy.hourglass);
  for (Index k = 0; k < nodes.count; ++k)
    for (int i = 0; i < 3; ++i)
      r.f_int.push_back(f(k, i));
  for (Index k = 0; k < el.count; ++k)
  {
    for (int j = 0; j < 6; ++j)
      r.stress.push_back(st(k, j));
    r.energy.push_back(e(k));
    for (int j = 0; j < kHourglassSize; ++j)
      r.hourglass.push_back(hg(k, j));
  }
  return r;
}

TEST(ChunkedAssembly, SameBitsForEveryChunkCountAndSharedNodesAreThoseTwoChunksTouch)
{
  Solver s(parseDeckString(kThreePartsDeck, "chunked.yaml"));
  for (int k = 0; k < 12; ++k) // stress, hourglass resistances and plastic flow in the parts
    s.cycle();
  const ElementControls ctl = gatherControls(s);
  const DeviceView<MaterialParams *> materials = s.materials();
  auto conn = Kokkos::create_mirror_view_and_copy(HostSpace(), s.elements().conn);

  StepResult one;
  for (int chunks : {1, 2, 3, 7})
  {
    const NodeCorners corners = makeNodeCorners(s.elements(), s.groups(), s.nodes().count, chunks);
    // the shared nodes, found here by brute force: touched by elements of two chunks
    std::vector<std::set<int>> touched(size_t(s.nodes().count));
    int chunk = 0;
    for (const auto &g : s.groups())
      for (int c = 0; c < chunks; ++c, ++chunk)
        for (Index e = chunkBegin(g, chunks, c); e < chunkBegin(g, chunks, c + 1); ++e)
          for (int a = 0; a < kMaxElementNodes; ++a)
            if (conn(e, a) >= 0)
              touched[size_t(conn(e, a))].insert(chunk);
    std::vector<Index> expected;
    for (Index n = 0; n < s.nodes().count; ++n)
      if (touched[size_t(n)].size() > 1)
        expected.push_back(n);
    auto shared = Kokkos::create_mirror_view_and_copy(HostSpace(), corners.shared_nodes);
    ASSERT_EQ(std::vector<Index>(shared.data(), shared.data() + shared.extent(0)), expected)
        << chunks << " chunks";
    // three groups (hex, tet, and the chunks cut both): some nodes are shared from 2 chunks on
    EXPECT_EQ(expected.empty(), chunks == 1) << chunks << " chunks";

    const StepResult r = runStep(s, ctl, corners, materials);
    if (chunks == 1)
    {
      one = r;
      Real fmax = 0;
      for (Real f : r.f_int)
        fmax = std::max(fmax, std::abs(f));
      ASSERT_GT(fmax, 0.0); // the step did produce forces
      continue;
    }
    EXPECT_EQ(r.f_int, one.f_int) << chunks << " chunks";
    EXPECT_EQ(r.stress, one.stress) << chunks << " chunks";
    EXPECT_EQ(r.energy, one.energy) << chunks << " chunks";
    EXPECT_EQ(r.hourglass, one.hourglass) << chunks << " chunks";
  }
}

// Row packs (markRowPacks) read and add whole node rows; the results must be the bits of the
// general path, with and without chunks. In part a (9 x 5 x 3 hexes) the packs from elements
// 0 and 72 are rows; part b's rows (4 hexes) are too short, so most packs are general.
TEST(ChunkedAssembly, RowPacksGiveTheBitsOfTheGeneralPath)
{
  Solver s(parseDeckString(kThreePartsDeck, "chunked.yaml"));
  for (int k = 0; k < 12; ++k)
    s.cycle();
  auto row = Kokkos::create_mirror_view_and_copy(HostSpace(), s.elements().row_pack);
  std::vector<Index> starts;
  for (Index e = 0; e < Index(row.extent(0)); ++e)
    if (row(e))
      starts.push_back(e);
  // part a's elements 0 .. 134 are e = i + 9 (j + 5 k): 8 hexes from e are a row if i <= 1
  std::vector<Index> expected;
  for (Index e = 0; e < 135 && kElementLanes == 8; ++e)
    if (e % 9 <= 1)
      expected.push_back(e);
  if (kElementLanes == 8)
    ASSERT_EQ(starts, expected);
  const ElementControls ctl = gatherControls(s);
  const NodeCorners one = makeNodeCorners(s.elements(), s.groups(), s.nodes().count, 1);
  const StepResult general = runStep(s, ctl, one, s.materials(), false);
  for (int chunks : {1, 2, 3})
  {
    const NodeCorners corners = makeNodeCorners(s.elements(), s.groups(), s.nodes().count, chunks);
    const StepResult r = runStep(s, ctl, corners, s.materials(), true);
    EXPECT_EQ(r.f_int, general.f_int) << chunks << " chunks";
    EXPECT_EQ(r.stress, general.stress) << chunks << " chunks";
    EXPECT_EQ(r.energy, general.energy) << chunks << " chunks";
    EXPECT_EQ(r.hourglass, general.hourglass) << chunks << " chunks";
  }
}

} // namespace
} // namespace scpdyn
