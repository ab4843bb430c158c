// Steps 5 and 12 (driver/NodeUpdate). Without external loads in the deck (hasExternalLoads()
// false) they neither write nor read f_ext, nor the impulse of a node component without a
// velocity constraint: the new x, v, impulses and every sum must then be the same bits as the
// general path given f_ext = 0, in 1, 2 and 3 dimensions, with and without an owned-node mask,
// over several steps (the previous impulse enters the external work). Step 12 can also do the
// next cycle's step 5 in its sweep.
#include "integrate/NodeUpdate.hpp"
#include "SameBits.hpp"

#include <gtest/gtest.h>

#include <random>
#include <string>

namespace scpdyn
{
namespace
{

VectorView copyOf(const VectorView &a, const char *label)
{
  VectorView b(std::string(label), a.extent(0));
  Kokkos::deep_copy(b, a);
  return b;
}

/// 1 000 nodes (more than one work item of step 12) with random x, v, f_int and mass; every
/// seventh node component held at one of two prescribed velocities.
NodeFields randomNodes(std::mt19937 &rng)
{
  std::uniform_real_distribution<Real> u(-1, 1);
  NodeFields n;
  n.count = 1000;
  const size_t c = size_t(n.count);
  n.x = VectorView("x", c);
  n.v = VectorView("v", c);
  n.f_int = VectorView("f_int", c);
  n.f_ext = VectorView("f_ext", c);
  n.external_impulse = VectorView("impulse", c);
  n.mass = RealView("mass", c);
  n.bc = DeviceView<int *[3]>("bc", c);
  auto x = Kokkos::create_mirror_view(n.x), v = Kokkos::create_mirror_view(n.v);
  auto f = Kokkos::create_mirror_view(n.f_int);
  auto m = Kokkos::create_mirror_view(n.mass);
  auto bc = Kokkos::create_mirror_view(n.bc);
  for (size_t k = 0; k < c; ++k)
  {
    m(k) = 1 + u(rng) * u(rng);
    for (int i = 0; i < 3; ++i)
    {
      x(k, i) = u(rng);
      v(k, i) = u(rng);
      f(k, i) = 1e3 * u(rng);
      bc(k, i) = (3 * k + size_t(i)) % 7 == 0 ? int(k % 2) : -1;
    }
  }
  Kokkos::deep_copy(n.x, x);
  Kokkos::deep_copy(n.v, v);
  Kokkos::deep_copy(n.f_int, f);
  Kokkos::deep_copy(n.mass, m);
  Kokkos::deep_copy(n.bc, bc);
  return n;
}

void expectSameBits(const VectorView &a, const VectorView &b, const char *what)
{
  auto ha = Kokkos::create_mirror_view_and_copy(HostSpace(), a);
  auto hb = Kokkos::create_mirror_view_and_copy(HostSpace(), b);
  int differing = 0;
  for (size_t k = 0; k < ha.extent(0); ++k)
    for (int i = 0; i < 3; ++i)
      differing += !sameBits(ha(k, i), hb(k, i));
  EXPECT_EQ(differing, 0) << what;
}

TEST(NodeUpdate, WithoutLoadsTheSameBitsAsTheGeneralPathWithZeroExternalForce)
{
  for (int dim = 1; dim <= 3; ++dim)
    for (bool masked : {false, true})
    {
      std::mt19937 rng(7 + dim);
      const NodeFields general = randomNodes(rng);
      NodeFields lean = general;
      lean.x = copyOf(general.x, "x2");
      lean.v = copyOf(general.v, "v2");
      lean.external_impulse = copyOf(general.external_impulse, "impulse2");
      BoundaryConditions bcs;
      bcs.velocity_current = RealView("vbc", 2);
      Kokkos::deep_copy(Kokkos::subview(bcs.velocity_current, 1), 0.25);
      IndexView owned;
      if (masked)
      {
        owned = IndexView("owned", size_t(general.count));
        auto h = Kokkos::create_mirror_view(owned);
        for (size_t k = 0; k < h.extent(0); ++k)
          h(k) = k % 3 != 1;
        Kokkos::deep_copy(owned, h);
      }
      const Real zero_g[3] = {0, 0, 0};
      for (int step = 0; step < 3; ++step)
      {
        zeroForces(general, zero_g, true);                        // f_ext = m g = 0
        zeroForces(lean, zero_g, false);                          // f_int (shared by both) = 0
        Kokkos::deep_copy(general.f_int, randomNodes(rng).f_int); // new forces every step
        const NodeSums a = updateNodes(general, bcs, 1e-3, dim, owned, true);
        const NodeSums b = updateNodes(lean, bcs, 1e-3, dim, owned, false);
        const std::string where = "dim " + std::to_string(dim) + (masked ? ", masked" : "") +
                                  ", step " + std::to_string(step);
        EXPECT_TRUE(sameBits(a.kinetic, b.kinetic)) << where;
        EXPECT_TRUE(sameBits(a.kinetic_mid, b.kinetic_mid)) << where;
        EXPECT_TRUE(sameBits(a.external_work, b.external_work)) << where;
        for (int i = 0; i < 3; ++i)
          EXPECT_TRUE(sameBits(a.momentum[i], b.momentum[i])) << where;
        EXPECT_NE(a.external_work, 0) << where << ": the constraints must do work";
        expectSameBits(general.x, lean.x, where.c_str());
        expectSameBits(general.v, lean.v, where.c_str());
        expectSameBits(general.external_impulse, lean.external_impulse, where.c_str());
      }
    }
}

// With next_gravity, step 12 leaves the forces as step 5 (zeroForces) would set them for the
// next cycle, in all three components, and its own results keep their bits: compared with
// step 12 alone followed by step 5, with and without loads, in 1, 2 and 3 dimensions.
TEST(NodeUpdate, StepTwelveWithNextGravityLeavesTheForcesOfStepFive)
{
  const Real g[3] = {0.5, -9.81, 2.0};
  for (int dim = 1; dim <= 3; ++dim)
    for (bool loads : {false, true})
    {
      std::mt19937 rng(11 + dim);
      const NodeFields apart = randomNodes(rng);
      Kokkos::deep_copy(apart.f_ext, randomNodes(rng).f_int); // nonzero, to see what is kept
      NodeFields fused = apart;
      for (VectorView *f :
           {&fused.x, &fused.v, &fused.f_int, &fused.f_ext, &fused.external_impulse})
        *f = copyOf(*f, "fused");
      BoundaryConditions bcs;
      bcs.velocity_current = RealView("vbc", 2);
      const NodeSums a = updateNodes(apart, bcs, 1e-3, dim, IndexView(), loads);
      zeroForces(apart, g, loads);
      const NodeSums b = updateNodes(fused, bcs, 1e-3, dim, IndexView(), loads, g);
      const std::string where = "dim " + std::to_string(dim) + (loads ? ", loads" : "");
      EXPECT_TRUE(sameBits(a.kinetic, b.kinetic)) << where;
      EXPECT_TRUE(sameBits(a.external_work, b.external_work)) << where;
      expectSameBits(apart.x, fused.x, where.c_str());
      expectSameBits(apart.v, fused.v, where.c_str());
      expectSameBits(apart.external_impulse, fused.external_impulse, where.c_str());
      expectSameBits(apart.f_int, fused.f_int, where.c_str());
      expectSameBits(apart.f_ext, fused.f_ext, where.c_str());
      auto f_int = Kokkos::create_mirror_view_and_copy(HostSpace(), fused.f_int);
      auto f_ext = Kokkos::create_mirror_view_and_copy(HostSpace(), fused.f_ext);
      auto m = Kokkos::create_mirror_view_and_copy(HostSpace(), fused.mass);
      int wrong = 0;
      for (size_t k = 0; k < f_int.extent(0); ++k)
        for (int i = 0; i < 3; ++i)
          wrong += f_int(k, i) != 0 || (loads && f_ext(k, i) != m(k) * g[i]) ||
                   (!loads && f_ext(k, i) == 0);
      EXPECT_EQ(wrong, 0) << where << ": f_int = 0, f_ext = m g (with loads) or left alone";
    }
}

TEST(NodeUpdate, ExternalLoadsAreGravityNodalForcesOrPressure)
{
  BoundaryConditions bc;
  const Real none[3] = {0, 0, 0}, down[3] = {0, 0, -9.81};
  EXPECT_FALSE(hasExternalLoads(bc, none));
  EXPECT_TRUE(hasExternalLoads(bc, down));
  bc.force_value.push_back({1, 0, 0});
  EXPECT_TRUE(hasExternalLoads(bc, none));
  bc.force_value.clear();
  bc.pressure_value.push_back(1e5);
  EXPECT_TRUE(hasExternalLoads(bc, none));
}

} // namespace
} // namespace scpdyn
