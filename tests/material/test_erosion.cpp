// The erosion criterion (material/Erosion.hpp), called directly: each limit on its own, limits
// that are off, inversion, and the limits a deck's erosion keys give (MaterialLibrary.cpp).
#include "MaterialTestUtil.hpp"

#include "material/Erosion.hpp"

#include <gtest/gtest.h>

namespace scpdyn::test
{
namespace
{

ErosionLimits limits(Real eps, Real damage, Real vmin, Real vmax, Real dt)
{
  ErosionLimits l;
  l.plastic_strain = eps;
  l.damage = damage;
  l.volumetric_strain_min = vmin;
  l.volumetric_strain_max = vmax;
  l.time_step = dt;
  l.active = true;
  return l;
}

TEST(Erosion, EachLimitOnItsOwn)
{
  const Real dt = 1e-7; // a stable step above every floor below
  const ErosionLimits eps = limits(0.2, 0, 0, 0, 0);
  EXPECT_FALSE(erosionLimitPassed(eps, 0.19, 0, 0, dt));
  EXPECT_TRUE(erosionLimitPassed(eps, 0.2, 0, 0, dt));
  const ErosionLimits d = limits(0, 0.9, 0, 0, 0);
  EXPECT_FALSE(erosionLimitPassed(d, 5.0, 0.89, 0, dt)); // plastic strain is off here
  EXPECT_TRUE(erosionLimitPassed(d, 0, 0.9, 0, dt));
  const ErosionLimits v = limits(0, 0, -0.5, 0.3, 0);
  EXPECT_FALSE(erosionLimitPassed(v, 0, 1, -0.49, dt)); // damage is off here
  EXPECT_TRUE(erosionLimitPassed(v, 0, 0, -0.5, dt));
  EXPECT_FALSE(erosionLimitPassed(v, 0, 0, 0.29, dt));
  EXPECT_TRUE(erosionLimitPassed(v, 0, 0, 0.3, dt));
  const ErosionLimits t = limits(0, 0, 0, 0, 1e-8);
  EXPECT_FALSE(erosionLimitPassed(t, 0, 0, 0, 1.1e-8));
  EXPECT_TRUE(erosionLimitPassed(t, 0, 0, 0, 0.9e-8));
}

TEST(Erosion, InvertedErodesOnlyAnErodingMaterial)
{
  EXPECT_TRUE(erosionLimitPassed(limits(0.2, 0, 0, 0, 0), 0, 0, 0, -1));
  EXPECT_FALSE(erosionLimitPassed(ErosionLimits(), 10, 1, -0.9, -1)); // no erosion: stops the run
}

TEST(Erosion, DeckKeysGiveTheLimitsAndVolumetricStrainIsFromTheMass)
{
  MaterialSpec spec = makeSpec("elastic_plastic", "linear",
                               {{"density", 8000},
                                {"youngs_modulus", 2e11},
                                {"poisson_ratio", 0.3},
                                {"yield_stress", 4e8},
                                {"erosion.plastic_strain", 0.5},
                                {"erosion.volumetric_strain_max", 0.25}});
  const MaterialParams p = makeMaterialParams(spec);
  EXPECT_TRUE(p.erosion.active);
  EXPECT_EQ(p.erosion.plastic_strain, 0.5);
  EXPECT_EQ(p.erosion.volumetric_strain_max, 0.25);
  EXPECT_EQ(p.erosion.damage, 0);
  // 8 kg at 8000 kg/m^3 fill V0 = 1e-3 m^3; in 1.25e-3 m^3 the strain is 0.25 (to round-off)
  EXPECT_NEAR(volumetricStrain(p, 8.0, 1.25e-3), 0.25, 1e-15);
  EXPECT_EQ(erosionDamage(p, nullptr), 0); // no damage outside the geomaterial
  spec.values.erase("erosion.plastic_strain");
  spec.values.erase("erosion.volumetric_strain_max");
  EXPECT_FALSE(makeMaterialParams(spec).erosion.active);
}

} // namespace
} // namespace scpdyn::test
