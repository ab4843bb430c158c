// The hex8 lanes' vectorised pieces against their scalar forms: the elastic update on a pack
// (the kernel runs it when all lanes share an elastic + linear EOS material) gives every
// lane the bits of updateMaterial(), so the pack and the scalar path stay bit-for-bit equal.
#include "element/ElementSolver.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <random>

using namespace scpdyn;

namespace
{

bool sameBits(Real a, Real b) { return std::memcmp(&a, &b, sizeof(Real)) == 0; }

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

} // namespace
