// The hex8 lanes' vectorised pieces against their scalar forms: the elastic update on a pack
// (the kernel runs it when all lanes share an elastic + linear EOS material) gives every
// lane the bits of updateMaterial(), so the pack and the scalar path stay bit-for-bit equal.
#include "element/ElementSolver.hpp"
#include "SameBits.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

using namespace scpdyn;

namespace
{

TEST(ElementLanes, ElasticPackUpdateIsUpdateMaterialPerLane)
{
#ifndef SCPDYN_ELEMENT_LANES
  GTEST_SKIP() << "no lane packs in this build (kElementLanes = 1)";
#else
  constexpr int W = kElementLanes;
  using P = LanePack;
  MaterialParams p;
  p.model = MaterialModel::Elastic;
  p.eos = EosModel::Linear;
  p.density = 7850;
  p.bulk = 166.7e9;
  p.shear = 76.9e9;
  ASSERT_TRUE(isElasticLinear(p));
  std::mt19937 gen(11);
  std::uniform_real_distribution<Real> u(-1, 1);
  const Real floor_c2 = soundSpeedSquaredFloor(p);
  for (int trial = 0; trial < 500; ++trial)
  {
    P D[6], stress[6], e, rho_old, rho_new, q;
    const Real dt = 1e-7 * (1 + 0.5 * u(gen));
    for (int l = 0; l < W; ++l)
    {
      for (int k = 0; k < 6; ++k)
      {
        D[k][l] = 1e3 * u(gen);
        stress[k][l] = 1e8 * u(gen);
      }
      e[l] = 50 * (1 + u(gen));
      rho_old[l] = p.density * (1 + 0.02 * u(gen));
      // every 7th trial lane 0 at 1e7 rho0, where (K + 4G/3) / rho is below the c^2 floor
      rho_new[l] = trial % 7 == 0 && l == 0 ? 1e7 * p.density : rho_old[l] * (1 + 1e-4 * u(gen));
      q[l] = 1e6 * (1 + u(gen));
    }
    P sp[6], ep = e;
    for (int k = 0; k < 6; ++k)
      sp[k] = stress[k];
    const P c2 = elasticLinearUpdate(p, D, dt, rho_old, rho_new, q, sp, ep);
    const P c = LaneOps<P>::sqrt(LaneOps<P>::max(c2, LaneOps<P>::broadcast(floor_c2)));
    for (int l = 0; l < W; ++l)
    {
      MaterialStep st;
      for (int k = 0; k < 6; ++k)
        st.D[k] = D[k][l];
      st.dt = dt;
      st.rho_old = rho_old[l];
      st.rho_new = rho_new[l];
      st.q = q[l];
      st.time = 0;
      st.length = 1e-3;
      Real s1[6], e1 = e[l], eps = 0, hist[kHistorySize] = {};
      for (int k = 0; k < 6; ++k)
        s1[k] = stress[k][l];
      const Real c1 = updateMaterial(p, st, s1, e1, eps, hist);
      // bit-for-bit: the same operations in the same order, each correctly rounded
      for (int k = 0; k < 6; ++k)
        ASSERT_TRUE(sameBits(sp[k][l], s1[k])) << "trial " << trial << " lane " << l << " k " << k;
      ASSERT_TRUE(sameBits(ep[l], e1)) << "trial " << trial << " lane " << l;
      ASSERT_TRUE(sameBits(c[l], c1)) << "trial " << trial << " lane " << l;
    }
  }
#endif
}

// A row pack's nodes (loadRowTriples, addRowTriples) against the per-lane forms with
// n[l] = base + l and base + l + 1: the same values read, the same sums in the same order
// (node base + j: lane j - 1's plus corner, then lane j's minus corner). Signed zeros and
// magnitudes far apart make a different order or a missing term show in the bits.
TEST(ElementLanes, RowTriplesGiveTheBitsOfThePerLaneTriples)
{
#ifndef SCPDYN_ELEMENT_LANES
  GTEST_SKIP() << "no lane packs in this build (kElementLanes = 1)";
#else
  constexpr int W = kElementLanes;
  using P = LanePack;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<Real> u(-1, 1);
  auto value = [&]() {
    const int kind = int(rng() % 8);
    return kind == 0 ? -0.0 : kind == 1 ? 0.0 : u(rng) * std::pow(10.0, int(rng() % 33) - 16);
  };
  for (int trial = 0; trial < 200; ++trial)
  {
    const Index nodes = W + 1 + Index(rng() % 5), base = Index(rng() % Index(nodes - W));
    std::vector<Real> p(size_t(3 * nodes));
    for (Real &a : p)
      a = value();
    Index n[2][W];
    for (int l = 0; l < W; ++l)
    {
      n[0][l] = base + l;
      n[1][l] = base + l + 1;
    }
    P minus[3], plus[3], lane_minus[3], lane_plus[3];
    loadRowTriples(p.data(), base, minus, plus);
    loadTriples(p.data(), n[0], lane_minus);
    loadTriples(p.data(), n[1], lane_plus);
    for (int i = 0; i < 3; ++i)
      for (int l = 0; l < W; ++l)
      {
        ASSERT_TRUE(sameBits(minus[i][l], lane_minus[i][l])) << trial << " " << i << " " << l;
        ASSERT_TRUE(sameBits(plus[i][l], lane_plus[i][l])) << trial << " " << i << " " << l;
      }
    P f[2][3];
    for (int c = 0; c < 2; ++c)
      for (int i = 0; i < 3; ++i)
        for (int l = 0; l < W; ++l)
          f[c][i][l] = value();
    std::vector<Real> row = p, lanes = p;
    addRowTriples(row.data(), base, f[0], f[1]);
    addTriples<2>(lanes.data(), n, f);
    for (size_t k = 0; k < p.size(); ++k)
      ASSERT_TRUE(sameBits(row[k], lanes[k])) << "trial " << trial << " slot " << k;
  }
#endif
}

} // namespace
