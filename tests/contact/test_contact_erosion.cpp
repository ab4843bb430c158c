// Contact with element erosion (docs/theory.md 11.6): a punch perforating a plate whose elements
// erode meets every layer the erosion exposes. Without the exposed interior faces the punch would
// run into the plate's second layer unopposed once the first had gone.
#include "TestUtil.hpp"

#include "driver/Solver.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace scpdyn;
using namespace scpdyn::test;

namespace
{

constexpr int kPunch = 0, kPlate = 1; // part indices in the deck
constexpr Real kElement = 0.5e-3;     // the plate's element size [m]
constexpr Real kPlateTop = 4e-3;      // the plate's top at t = 0 [m]

/// How deep any punch node lies inside a plate element that has not eroded [m] (0: none), in
/// `top` the plate's top layer of elements, in `below` the others.
void deepestPunchNode(const Solver &s, Real &top, Real &below)
{
  auto x0 = Kokkos::create_mirror_view_and_copy(HostSpace(), s.nodes().x0);
  auto x = Kokkos::create_mirror_view_and_copy(HostSpace(), s.nodes().x);
  auto conn = Kokkos::create_mirror_view_and_copy(HostSpace(), s.elements().conn);
  auto part = Kokkos::create_mirror_view_and_copy(HostSpace(), s.elements().part);
  auto eroded = Kokkos::create_mirror_view_and_copy(HostSpace(), s.elements().eroded);
  std::vector<Index> punch;
  for (Index e = 0; e < s.elements().count; ++e)
    if (part(e) == kPunch)
      for (int a = 0; a < 4; ++a)
        punch.push_back(conn(e, a));
  std::sort(punch.begin(), punch.end());
  punch.erase(std::unique(punch.begin(), punch.end()), punch.end());
  top = below = 0;
  for (Index e = 0; e < s.elements().count; ++e)
  {
    if (part(e) != kPlate || eroded(e) != 0)
      continue;
    Real area2 = 0, y0 = 0; // twice the signed area (the corners' orientation), the centroid at 0
    for (int a = 0; a < 4; ++a)
    {
      const Index i = conn(e, a), j = conn(e, (a + 1) % 4);
      area2 += x(i, 0) * x(j, 1) - x(j, 0) * x(i, 1);
      y0 += 0.25 * x0(i, 1);
    }
    Real &deepest = y0 > kPlateTop - kElement ? top : below;
    const Real sign = area2 > 0 ? 1 : -1;
    for (Index n : punch)
    {
      Real depth = 1e300; // the distance to the nearest edge, > 0 inside
      for (int a = 0; a < 4; ++a)
      {
        const Index i = conn(e, a), j = conn(e, (a + 1) % 4);
        const Real ex = x(j, 0) - x(i, 0), ey = x(j, 1) - x(i, 1);
        const Real d = sign * (ex * (x(n, 1) - x(i, 1)) - ey * (x(n, 0) - x(i, 0))) /
                       std::sqrt(ex * ex + ey * ey);
        depth = std::min(depth, d);
      }
      deepest = std::max(deepest, depth);
    }
  }
}

} // namespace

// The 2 x 3 mm punch at 600 m/s into the 4 mm plate (tests/parallel/decks/eroding_plate_2d.yaml);
// the plate erodes from the top down under it. Pass:
// - no punch node gets deeper than 5 % of an element into a plate element below the top layer
//   that is still there: the slide line holds the nodes on the faces erosion exposes (measured
//   0.008 of an element, a corner between two CPs); with those faces left out of the contact a
//   node reaches 0.36 of an element into the plate and the punch leaves at 417 instead of 375 m/s;
// - in the top layer, the single normal row of a slide-line CP lets the punch's corners in by up
//   to 0.14 of an element (docs/theory.md 11.5), so 0.2;
// - the punch perforates (its tip below the plate) and leaves slower than it came;
// - the energy balance with the eroded energy booked within 1 % (measured 1.2e-3).
TEST(ContactErosion, PunchMeetsEveryLayerErosionExposes)
{
  Solver s(deckFromText(readText(std::string(SCPDYN_SOURCE_DIR) +
                                 "/tests/parallel/decks/eroding_plate_2d.yaml"),
                        "eroding_plate"),
           MPI_COMM_SELF);
  const Real p0 = s.energies().momentum[1];
  Real deepest_top = 0, deepest = 0, worst_balance = 0;
  while (s.time() < s.deck().end_time)
  {
    s.cycle();
    Real top, below;
    deepestPunchNode(s, top, below);
    deepest_top = std::max(deepest_top, top);
    deepest = std::max(deepest, below);
    worst_balance = std::max(worst_balance, std::fabs(s.energies().balance_error));
  }
  const EnergyReport end = s.energies();
  auto x = Kokkos::create_mirror_view_and_copy(HostSpace(), s.nodes().x);
  auto v = Kokkos::create_mirror_view_and_copy(HostSpace(), s.nodes().v);
  auto conn = Kokkos::create_mirror_view_and_copy(HostSpace(), s.elements().conn);
  auto part = Kokkos::create_mirror_view_and_copy(HostSpace(), s.elements().part);
  Real tip = 1e300, vy = 0;
  int n = 0;
  for (Index e = 0; e < s.elements().count; ++e)
    if (part(e) == kPunch)
      for (int a = 0; a < 4; ++a)
      {
        tip = std::min(tip, x(conn(e, a), 1));
        vy += v(conn(e, a), 1), ++n;
      }
  vy /= n;
  std::printf("[ contact erosion ] %ld eroded, deepest punch node %.3e m in the plate's top "
              "layer, %.3e m in the layers below, tip at y = %.3e m, punch vy %.1f m/s, balance "
              "worst %.3e, "
              "momentum y %.4e of %.4e\n",
              end.eroded_elements, deepest_top, deepest, tip, vy, worst_balance, end.momentum[1],
              p0);
  EXPECT_GE(end.eroded_elements, 16); // two layers of the 8 under and beside the punch
  EXPECT_LT(deepest_top, 0.2 * kElement);
  EXPECT_LT(deepest, 0.05 * kElement);
  EXPECT_LT(tip, 0.0);
  EXPECT_GT(vy, -600.0 * 0.9);
  EXPECT_LT(vy, 0.0);
  EXPECT_LT(worst_balance, 1e-2);
}
