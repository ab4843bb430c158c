// The hex8 pack (kElementLanes hexes at once: ElementKernel::range) against the kernel's step
// of one element (ElementKernel::one) on the same state: every value step 6 writes must have
// the same bits, in both hourglass forms, for row, general and tail packs and for the
// lane-by-lane J2 update. The hourglass energy is among them: its trapezoidal work reads the
// last step's resistances, so a pack that lost them shows here.
#include "SameBits.hpp"
#include "StepFixtures.hpp"
#include "element/ElementKernel.hpp"
#include "input/Deck.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace scpdyn
{
namespace
{

/// Every value step 6 writes, in one list.
std::vector<Real> stepOutputs(const NodeFields &nodes, const ElementFields &el)
{
  std::vector<Real> out;
  const auto add = [&out](const auto &view) {
    auto h = Kokkos::create_mirror_view_and_copy(HostSpace(), view);
    for (size_t i = 0; i < h.span(); ++i)
      out.push_back(Real(h.data()[i]));
  };
  add(nodes.f_int);
  add(el.stress);
  add(el.energy);
  add(el.plastic_strain);
  add(el.volume);
  add(el.q);
  add(el.sound_speed);
  add(el.hourglass_energy);
  add(el.history);
  add(el.hourglass);
  return out;
}

/// Step 6 of the hex groups on copies of the solver's state: packs, or one element at a time.
std::vector<Real> hexStep(const Solver &s, const bool packs)
{
  ElementControls ctl = test::gatherControls(s);
  ctl.gather = false;
  NodeFields nodes = s.nodes();
  nodes.f_int = VectorView("f_int", size_t(nodes.count));
  const ElementFields el = test::copyElementState(s.elements());
  const auto k = element_kernel::makeElementKernel<ElementType::Hex8, false, false>(
      ctl, element_kernel::Scatter::Plain, nodes, el, s.materials(), NodeCorners());
  for (const ElementGroup &g : s.groups())
    if (g.type == ElementType::Hex8)
      Kokkos::parallel_for( // one thread: the plain adds need the element order
          "packStep", Kokkos::RangePolicy<ExecSpace>(0, 1), KOKKOS_LAMBDA(const int) {
            Real dt_min = 1e300;
            if (packs)
              k.range(g.begin, g.end, dt_min);
            else
              for (Index e = g.begin; e < g.end; ++e)
                k.one(e, dt_min);
          });
  Kokkos::fence();
  return stepOutputs(nodes, el);
}

/// kThreePartsDeck with part b held at its face x = 1 as well, so that it flows plastically,
/// and `numerics` as given.
std::string packDeck(const std::string &numerics)
{
  std::string deck = test::kThreePartsDeck;
  const auto replace = [&deck](const std::string &from, const std::string &to) {
    ASSERT_NE(deck.find(from), std::string::npos) << from;
    deck.replace(deck.find(from), from.size(), to);
  };
  replace("numerics: {scatter: gather}", "numerics: " + numerics);
  const std::string wall = "  - {name: wall, box: {min: [0, 0, 0], max: [0, 0.5, 0.3]}}\n";
  replace(wall, wall + "  - {name: wall_b, box: {min: [1, 0, 0], max: [1, 0.3, 0.5]}}\n");
  deck += "  - {type: velocity, node_set: wall_b, component: x, value: 0.0}\n";
  return deck;
}

void expectPacksGiveTheScalarBits(const std::string &deck, const char *name)
{
  Solver s(parseDeckString(deck, name));
  for (int k = 0; k < 12; ++k) // stress, hourglass resistances and plastic flow in the parts
    s.cycle();
  const std::vector<Real> one = hexStep(s, false), packed = hexStep(s, true);
  ASSERT_EQ(one.size(), packed.size());
  size_t differ = 0, first = one.size();
  for (size_t i = 0; i < one.size(); ++i)
    if (!sameBits(one[i], packed[i]))
      differ += 1, first = first < i ? first : i;
  EXPECT_EQ(differ, 0u) << name << ": first at " << first;
  // the state the comparison covers is not trivial
  const ElementFields &el = s.elements();
  Real hourglass_energy = 0, plastic = 0;
  auto hg = Kokkos::create_mirror_view_and_copy(HostSpace(), el.hourglass_energy);
  auto eps = Kokkos::create_mirror_view_and_copy(HostSpace(), el.plastic_strain);
  for (size_t e = 0; e < hg.extent(0); ++e)
    hourglass_energy += hg(e), plastic += eps(e);
  EXPECT_GT(hourglass_energy, 0) << name;
  EXPECT_GT(plastic, 0) << name;
}

TEST(PackStep, GivesTheBitsOfTheOneElementStepViscousHourglass)
{
#ifndef SCPDYN_ELEMENT_LANES
  GTEST_SKIP() << "no lane packs in this build (kElementLanes = 1)";
#else
  expectPacksGiveTheScalarBits(packDeck("{scatter: gather}"), "viscous.yaml");
#endif
}

TEST(PackStep, GivesTheBitsOfTheOneElementStepStiffnessHourglass)
{
#ifndef SCPDYN_ELEMENT_LANES
  GTEST_SKIP() << "no lane packs in this build (kElementLanes = 1)";
#else
  expectPacksGiveTheScalarBits(
      packDeck("{scatter: gather, hourglass: {type: stiffness, coefficient: 0.05}}"),
      "stiffness.yaml");
#endif
}

} // namespace
} // namespace scpdyn
