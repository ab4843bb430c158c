// The templated metal stages (MetalUpdate.hpp) through updateMaterial(): the elastic + linear
// EOS step against the closed-form hypoelastic increment and the trapezoidal work, and the
// per-model "uses history" fact the element kernel relies on to skip the history slots.
#include "MaterialTestUtil.hpp"
#include "SameBits.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

namespace scpdyn::test
{
namespace
{

MaterialSpec steelElastic(const std::string &eos)
{
  if (eos == "linear")
    return makeSpec("elastic", "linear",
                    {{"density", 7850}, {"youngs_modulus", 200e9}, {"poisson_ratio", 0.3}});
  return makeSpec("elastic", "mie_gruneisen",
                  {{"density", 7850},
                   {"shear_modulus", 77e9},
                   {"eos.c0", 4570},
                   {"eos.s", 1.49},
                   {"eos.gamma0", 1.93}});
}

MaterialSpec steelJ2(const std::string &eos)
{
  if (eos == "linear")
    return makeSpec("elastic_plastic", "linear",
                    {{"density", 7850},
                     {"youngs_modulus", 200e9},
                     {"poisson_ratio", 0.3},
                     {"yield_stress", 400e6},
                     {"hardening_modulus", 2e9}});
  return makeSpec("elastic_plastic", "mie_gruneisen",
                  {{"density", 7850},
                   {"shear_modulus", 77e9},
                   {"yield_stress", 400e6},
                   {"eos.c0", 4570},
                   {"eos.s", 1.49},
                   {"eos.gamma0", 1.93}});
}

std::vector<MaterialSpec> allModels()
{
  return {steelElastic("linear"),
          steelElastic("mie_gruneisen"),
          steelJ2("linear"),
          steelJ2("mie_gruneisen"),
          steel4340(),
          limestone(),
          tnt()};
}

TEST(MetalUpdate, ElasticLinearIsHypoelasticWithTrapezoidalWork)
{
  const MaterialParams p = makeMaterialParams(steelElastic("linear"));
  const Real G = p.shear, K = p.bulk;
  std::mt19937 gen(7);
  std::uniform_real_distribution<Real> u(-1, 1);
  for (int trial = 0; trial < 200; ++trial)
  {
    MaterialStep st;
    for (int k = 0; k < 6; ++k)
      st.D[k] = 1e3 * u(gen);
    st.dt = 1e-7;
    st.rho_old = p.density * (1 + 0.01 * u(gen));
    st.rho_new = st.rho_old * (1 - st.dt * (st.D[0] + st.D[1] + st.D[2]));
    st.q = 1e6 * (1 + u(gen));
    st.time = 0;
    st.length = 1e-3;
    Real stress[6], old[6], hist[kHistorySize] = {};
    for (int k = 0; k < 6; ++k)
      old[k] = stress[k] = 1e8 * u(gen);
    const Real e0 = 100 * (1 + u(gen));
    Real e = e0, eps = 0;
    const Real c = updateMaterial(p, st, stress, e, eps, hist);
    // closed form: d sigma = dt (K trD I + 2 G dev D); ~10 roundings on terms of |sigma|
    // <= 6e8 Pa, so 1e-14 relative to that scale is ~20 ulp
    const Real trD = st.D[0] + st.D[1] + st.D[2];
    for (int k = 0; k < 6; ++k)
    {
      const Real dev = k < 3 ? st.D[k] - trD / 3 : st.D[k];
      const Real expect = old[k] + st.dt * (K * trD * (k < 3 ? 1 : 0) + 2 * G * dev);
      EXPECT_NEAR(stress[k], expect, 1e-14 * 6e8) << "trial " << trial << " k " << k;
    }
    // e - e0 = dt / rho_mid (sigma_mid : D - q trD), the same work written with the full
    // stresses; the increment is ~10 J/kg on e0 ~1e2, so 1e-13 e0 = 1e-11 J/kg is ~1000 ulp of
    // e and 1e-12 of the increment
    Real mid[6];
    for (int k = 0; k < 6; ++k)
      mid[k] = 0.5 * (old[k] + stress[k]);
    const Real rho_mid = 0.5 * (st.rho_old + st.rho_new);
    const Real work = st.dt / rho_mid * (contract(mid, st.D) - st.q * trD);
    EXPECT_NEAR(e - e0, work, 1e-13 * e0) << "trial " << trial;
    EXPECT_NEAR(c, std::sqrt((K + 4.0 / 3.0 * G) / st.rho_new), 1e-12 * c);
    EXPECT_EQ(eps, 0.0);
  }
}

// The element kernel skips the history slots (load and store) of the models that declare
// none; so such a model must neither write them nor let them change its results. The models
// that declare history must really use it (else the fact is stale and costs 128 B a cycle).
TEST(MetalUpdate, HistoryFactMatchesWhatEachModelDoes)
{
  for (const MaterialSpec &spec : allModels())
  {
    const MaterialParams p = makeMaterialParams(spec);
    SCOPED_TRACE(spec.model + " / " + spec.eos);
    // two runs from the same state, one with the model's own initial history and one with
    // the slots overwritten by a sentinel; uniaxial compression then shear, past yield
    const Real centroid[3] = {0, 0, 0};
    MaterialPoint a(p, centroid), b(p, centroid);
    for (int k = 0; k < kHistorySize; ++k)
      b.history[k] = 0.375 + k;
    Real hist_a0[kHistorySize], hist_b0[kHistorySize];
    std::memcpy(hist_a0, a.history, sizeof hist_a0);
    std::memcpy(hist_b0, b.history, sizeof hist_b0);
    bool differs = false;
    for (int n = 0; n < 40; ++n)
    {
      const Real D[6] = {n < 20 ? -2e3 : 0.0, 0, 0, n < 20 ? 0.0 : 3e3, 0, 0};
      a.step(D, 1e-6);
      b.step(D, 1e-6);
      differs = differs || !sameBits(a.history, hist_a0, kHistorySize) ||
                !sameBits(a.stress, b.stress, 6) || a.e != b.e || a.eps != b.eps || a.c != b.c;
      if (!modelUsesHistory(p.model))
      {
        ASSERT_TRUE(sameBits(a.history, hist_a0, kHistorySize)) << "step " << n;
        ASSERT_TRUE(sameBits(b.history, hist_b0, kHistorySize)) << "step " << n;
        ASSERT_TRUE(sameBits(a.stress, b.stress, 6)) << "step " << n;
        ASSERT_EQ(a.e, b.e);
        ASSERT_EQ(a.eps, b.eps);
        ASSERT_EQ(a.c, b.c);
      }
    }
    if (modelUsesHistory(p.model))
      EXPECT_TRUE(differs) << "declares history but neither writes nor reads it";
    else if (p.model == MaterialModel::ElasticPlastic)
      EXPECT_GT(a.eps, 0.0); // the path did yield, so the return map ran
  }
}

} // namespace
} // namespace scpdyn::test
