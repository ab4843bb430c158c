// Deck side of the material models: the documented parameter sets validate and convert, bad
// values are rejected naming materials[i].<key> and the line, history slots are named.
#include "MaterialTestUtil.hpp"

#include <gtest/gtest.h>

namespace scpdyn::test
{
namespace
{

// Expect an InputError whose message names materials[0].<key> (line L) when L > 0.
void expectError(const MaterialSpec &s, const std::string &key)
{
  try
  {
    makeMaterialParams(s);
    ADD_FAILURE() << "no error for " << key;
  }
  catch (const InputError &e)
  {
    const std::string what = e.what();
    EXPECT_NE(what.find("materials[0]." + key), std::string::npos) << what;
    auto it = s.lines.find(key);
    if (it != s.lines.end())
    {
      EXPECT_NE(what.find("(line " + std::to_string(it->second) + ")"), std::string::npos) << what;
    }
  }
}

TEST(MaterialLibrary, DocumentedSetsConvert)
{
  const MaterialParams st = makeMaterialParams(steel4340());
  EXPECT_EQ(st.model, MaterialModel::JohnsonCook);
  EXPECT_EQ(st.model_params[kJcTroom], 294.0); // default room temperature
  EXPECT_EQ(st.model_params[kJcRate0], 1.0);   // default reference rate
  EXPECT_EQ(st.model_params[kJcChi], 0.9);     // default Taylor-Quinney fraction
  EXPECT_EQ(st.bulk, 7830.0 * 4578 * 4578);    // from the EOS: rho0 c0^2
  const MaterialParams ls = makeMaterialParams(limestone());
  // the paper's limestone: P-wave speed 4500 m/s at 2600 kg/m^3
  EXPECT_LT(relErr(referenceSoundSpeed(ls), 4500), 1e-12);
  EXPECT_LT(relErr(ls.model_params[kGeoThetaLock], -std::log(0.96)), 1e-15);
  const MaterialParams he = makeMaterialParams(tnt());
  EXPECT_EQ(he.shear, 0.0);
  EXPECT_EQ(referenceSoundSpeed(he), 6930.0); // D bounds the products' sound speed
  EXPECT_EQ(initialSpecificEnergy(he), 7.0e9 / 1630);
  EXPECT_EQ(initialSpecificEnergy(st), 0.0);
  EXPECT_EQ(he.model_params[kHeAxis], -1.0);     // point ignition by default
  EXPECT_EQ(he.model_params[kHeBurnWidth], 1.5); // LS-DYNA's ramp
  // D defaults to the model's CJ velocity
  MaterialSpec no_d = tnt();
  no_d.values.erase("D");
  const MaterialParams he2 = makeMaterialParams(no_d);
  EXPECT_LT(relErr(he2.model_params[kHeD], 6929.35), 1e-5);
}

TEST(MaterialLibrary, ExistingModelsUnchanged)
{
  const MaterialParams p = makeMaterialParams(makeSpec("elastic_plastic", "linear",
                                                       {{"density", 8930},
                                                        {"youngs_modulus", 117e9},
                                                        {"poisson_ratio", 0.35},
                                                        {"yield_stress", 400e6},
                                                        {"hardening_modulus", 100e6}}));
  EXPECT_EQ(p.model, MaterialModel::ElasticPlastic);
  EXPECT_EQ(p.bulk, 117e9 / (3 * (1 - 2 * 0.35)));
  EXPECT_EQ(p.shear, 117e9 / (2 * 1.35));
  EXPECT_EQ(p.yield_stress, 400e6);
  for (const std::string &n : historyNames(p))
    EXPECT_TRUE(n.empty());
}

TEST(MaterialLibrary, HistoryNames)
{
  auto names = historyNames(makeMaterialParams(limestone()));
  ASSERT_EQ(names.size(), static_cast<size_t>(kHistorySize));
  EXPECT_EQ(names[kGeoHistDamage], "damage");
  EXPECT_EQ(names[kGeoHistTensile], "tensile_strength");
  EXPECT_EQ(names[kGeoHistThetaP], "plastic_volumetric_strain");
  EXPECT_EQ(names[kGeoHistThetaC], "");
  names = historyNames(makeMaterialParams(tnt()));
  EXPECT_EQ(names[kHeHistBurn], "burn_fraction");
  EXPECT_EQ(names[kHeHistLightTime], "lighting_time");
  names = historyNames(makeMaterialParams(steel4340()));
  EXPECT_EQ(names[kJcHistTemperature], "temperature");
}

TEST(MaterialLibrary, BadParametersNameTheKey)
{
  auto with = [](MaterialSpec s, const char *key, double v) {
    s.values[key] = v;
    if (!s.lines.count(key))
      s.lines[key] = 99;
    return s;
  };
  auto without = [](MaterialSpec s, const char *key) {
    s.values.erase(key);
    return s;
  };
  // Johnson-Cook
  expectError(with(steel4340(), "A", -1e6), "A");
  expectError(with(steel4340(), "n", 0), "n");
  expectError(without(steel4340(), "B"), "B");
  expectError(with(steel4340(), "taylor_quinney", 1.5), "taylor_quinney");
  expectError(with(steel4340(), "melt_temperature", 200), "melt_temperature");
  expectError(without(steel4340(), "specific_heat"), "specific_heat");
  expectError(with(steel4340(), "shear_modulus", 0), "shear_modulus");
  expectError(with(steel4340(), "yield_stress", 1e8), "yield_stress"); // not a JC key
  // geomaterial
  expectError(with(limestone(), "youngs_modulus", -4e10), "youngs_modulus");
  expectError(with(limestone(), "lock_pressure", 100e6), "lock_pressure");
  expectError(with(limestone(), "porosity", 1.2), "porosity");
  expectError(with(limestone(), "max_strength", 10e6), "max_strength");
  expectError(with(limestone(), "damage_strain", 1e-4), "damage_strain"); // < T0/K snaps back
  expectError(with(limestone(), "solid_bulk_modulus", 10e9), "solid_bulk_modulus"); // < K0
  expectError(with(limestone(), "solid_bulk_modulus", 5e12), "solid_bulk_modulus"); // too stiff
  expectError(without(limestone(), "crush_pressure"), "crush_pressure");
  expectError(with(limestone(), "tensile_strength", -1), "tensile_strength");
  expectError(with(limestone(), "fracture_energy", -100), "fracture_energy");
  MaterialSpec mg = limestone();
  mg.eos = "mie_gruneisen";
  mg.lines["eos.type"] = 42;
  expectError(mg, "eos.type");
  // explosive
  expectError(with(tnt(), "eos.omega", -0.3), "eos.omega");
  expectError(with(tnt(), "eos.A", -2000e9), "eos.E0"); // p_H < 0: no CJ state
  expectError(with(tnt(), "D", 8000), "D");             // 15 % off the model's 6929 m/s
  expectError(with(tnt(), "pcj", 30e9), "pcj");         // 43 % off the model's 21.0 GPa
  expectError(with(tnt(), "ignition_axis", 3), "ignition_axis");
  expectError(with(tnt(), "burn_width", 0), "burn_width");
  expectError(with(tnt(), "youngs_modulus", 1e9), "youngs_modulus"); // no strength keys
  MaterialSpec elastic_jwl = tnt();
  elastic_jwl.model = "elastic";
  expectError(elastic_jwl, "eos.type");
  MaterialSpec unknown = tnt();
  unknown.model = "plasticine";
  expectError(unknown, "model");
}

} // namespace
} // namespace scpdyn::test
