#include "material/MaterialLibrary.hpp"
#include "core/RealText.hpp"

#include "material/Geomaterial.hpp"
#include "material/JohnsonCook.hpp"
#include "material/Jwl.hpp"

#include <cmath>
#include <set>
#include <sstream>

namespace scpdyn
{
namespace
{

struct KeyRule
{
  const char *key;
  bool required;
  double default_value;
};

constexpr double kNone = 0; // default of keys whose absence means "feature off"

// Keys of each model and eos. Stiffness may be given as (youngs_modulus, poisson_ratio) or,
// for an EOS that supplies the bulk response, as shear_modulus alone; the geomaterial also
// takes (bulk_modulus, shear_modulus).
const std::vector<KeyRule> &modelKeys(const std::string &model)
{
  static const std::vector<KeyRule> elastic = {{"density", true, 0},
                                               {"youngs_modulus", false, 0},
                                               {"poisson_ratio", false, 0},
                                               {"shear_modulus", false, 0}};
  static const std::vector<KeyRule> plastic = {
      {"density", true, 0},        {"youngs_modulus", false, 0}, {"poisson_ratio", false, 0},
      {"shear_modulus", false, 0}, {"yield_stress", true, 0},    {"hardening_modulus", false, 0}};
  static const std::vector<KeyRule> jc = {{"density", true, 0},
                                          {"youngs_modulus", false, 0},
                                          {"poisson_ratio", false, 0},
                                          {"shear_modulus", false, 0},
                                          {"A", true, 0},
                                          {"B", true, 0},
                                          {"n", true, 0},
                                          {"C", false, 0},
                                          {"m", false, 1},
                                          {"melt_temperature", false, kNone},
                                          {"room_temperature", false, 294},
                                          {"reference_strain_rate", false, 1},
                                          {"specific_heat", false, kNone},
                                          {"taylor_quinney", false, 0.9}};
  static const std::vector<KeyRule> geo = {{"density", true, 0},
                                           {"youngs_modulus", false, 0},
                                           {"poisson_ratio", false, 0},
                                           {"shear_modulus", false, 0},
                                           {"bulk_modulus", false, 0},
                                           {"intact_strength", true, 0},
                                           {"intact_friction", true, 0},
                                           {"max_strength", true, 0},
                                           {"damaged_friction", true, 0},
                                           {"tensile_strength", true, 0},
                                           {"damage_strain", true, 0},
                                           {"dilatancy", false, 0},
                                           {"dilatancy_pressure", false, 1e300},
                                           {"porosity", false, 0},
                                           {"crush_pressure", false, 0},
                                           {"lock_pressure", false, 0},
                                           {"solid_bulk_modulus", false, 0},
                                           {"compaction_hardening", false, 0},
                                           {"fracture_energy", false, 0}};
  static const std::vector<KeyRule> he = {{"density", true, 0},
                                          {"D", false, 0},
                                          {"pcj", false, 0},
                                          {"ignition_x", false, 0},
                                          {"ignition_y", false, 0},
                                          {"ignition_z", false, 0},
                                          {"ignition_axis", false, -1},
                                          {"initiation_time", false, 0},
                                          {"burn_width", false, 1.5},
                                          {"beta_burn", false, 1}};
  static const std::vector<KeyRule> none;
  if (model == "elastic")
    return elastic;
  if (model == "elastic_plastic")
    return plastic;
  if (model == "johnson_cook")
    return jc;
  if (model == "geomaterial")
    return geo;
  if (model == "high_explosive")
    return he;
  return none;
}

const std::vector<KeyRule> &eosKeys(const std::string &eos)
{
  static const std::vector<KeyRule> linear = {};
  static const std::vector<KeyRule> mg = {
      {"eos.c0", true, 0}, {"eos.s", true, 0}, {"eos.gamma0", true, 0}, {"eos.a", false, 0}};
  static const std::vector<KeyRule> jwl = {{"eos.A", true, 0},     {"eos.B", true, 0},
                                           {"eos.R1", true, 0},    {"eos.R2", true, 0},
                                           {"eos.omega", true, 0}, {"eos.E0", true, 0}};
  return eos == "mie_gruneisen" ? mg : eos == "jwl" ? jwl : linear;
}

std::string where(const MaterialSpec &spec, const std::string &key)
{
  std::ostringstream os;
  os << "materials[" << spec.index << "]";
  if (!key.empty())
    os << "." << key;
  auto it = spec.lines.find(key);
  const int line = it != spec.lines.end() ? it->second : spec.line;
  if (line > 0)
    os << " (line " << line << ")";
  return os.str();
}

[[noreturn]] void fail(const MaterialSpec &spec, const std::string &key, const std::string &what)
{
  throw InputError(where(spec, key) + ": " + what);
}

bool has(const MaterialSpec &spec, const std::string &key) { return spec.values.count(key) > 0; }

// value of a key, or the default of its rule (fallback when the key has no rule)
double get(const MaterialSpec &spec, const std::string &key, double fallback)
{
  auto it = spec.values.find(key);
  if (it != spec.values.end())
    return it->second;
  for (const auto *rules : {&modelKeys(spec.model), &eosKeys(spec.eos)})
    for (const auto &r : *rules)
      if (key == r.key)
        return r.default_value;
  return fallback;
}

std::string num(double v)
{
  std::ostringstream os;
  os << v;
  return os.str();
}

void requirePositive(const MaterialSpec &spec, const std::string &key)
{
  if (!(get(spec, key, 0) > 0))
    fail(spec, key, "must be > 0 (got " + num(get(spec, key, 0)) + ")");
}

void requireNonNegative(const MaterialSpec &spec, const std::string &key)
{
  if (!(get(spec, key, 0) >= 0))
    fail(spec, key, "must be >= 0 (got " + num(get(spec, key, 0)) + ")");
}

// (youngs_modulus, poisson_ratio) or shear_modulus with a bulk-supplying EOS
void validateElasticKeys(const MaterialSpec &spec)
{
  const bool has_e = has(spec, "youngs_modulus"), has_nu = has(spec, "poisson_ratio");
  if (has_e != has_nu)
    fail(spec, has_e ? "poisson_ratio" : "youngs_modulus",
         "youngs_modulus and poisson_ratio go together");
  if (has_e && has(spec, "shear_modulus"))
    fail(spec, "shear_modulus", "give either shear_modulus or youngs_modulus + poisson_ratio");
  if (has_e)
  {
    if (get(spec, "youngs_modulus", 0) <= 0)
      fail(spec, "youngs_modulus", "must be > 0");
    const double nu = get(spec, "poisson_ratio", 0);
    if (!(nu > -1.0 && nu < 0.5))
      fail(spec, "poisson_ratio", "must be in (-1, 0.5) (got " + std::to_string(nu) + ")");
    return;
  }
  if (spec.model == "geomaterial")
  {
    if (!has(spec, "bulk_modulus") || !has(spec, "shear_modulus"))
      fail(spec, has(spec, "bulk_modulus") ? "shear_modulus" : "bulk_modulus",
           "required: youngs_modulus + poisson_ratio or bulk_modulus + shear_modulus");
    requirePositive(spec, "bulk_modulus");
    requirePositive(spec, "shear_modulus");
    return;
  }
  if (spec.eos == "linear")
    fail(spec, "youngs_modulus", "required with the linear eos (with poisson_ratio)");
  if (!has(spec, "shear_modulus"))
    fail(spec, "shear_modulus", "required: shear_modulus or youngs_modulus + poisson_ratio");
  if (get(spec, "shear_modulus", 0) < 0)
    fail(spec, "shear_modulus", "must be >= 0");
}

void validateJohnsonCook(const MaterialSpec &spec, const MaterialParams &p)
{
  if (!(p.shear > 0))
    fail(spec, has(spec, "shear_modulus") ? "shear_modulus" : "youngs_modulus",
         "the shear modulus must be > 0 for plasticity");
  requirePositive(spec, "A");
  requireNonNegative(spec, "B");
  requirePositive(spec, "n");
  requireNonNegative(spec, "C");
  requirePositive(spec, "reference_strain_rate");
  requireNonNegative(spec, "specific_heat");
  const double chi = get(spec, "taylor_quinney", 0);
  if (!(chi >= 0 && chi <= 1))
    fail(spec, "taylor_quinney", "must be in [0, 1] (got " + num(chi) + ")");
  if (has(spec, "melt_temperature"))
  {
    requirePositive(spec, "m");
    if (!(get(spec, "melt_temperature", 0) > get(spec, "room_temperature", 0)))
      fail(spec, "melt_temperature", "must exceed room_temperature");
    if (!has(spec, "specific_heat"))
      fail(spec, "specific_heat", "required with melt_temperature (adiabatic heating)");
  }
}

void validateGeomaterial(const MaterialSpec &spec, const MaterialParams &p)
{
  for (const char *k : {"intact_strength", "tensile_strength", "damage_strain"})
    requirePositive(spec, k);
  for (const char *k : {"intact_friction", "damaged_friction", "dilatancy", "compaction_hardening",
                        "fracture_energy"})
    requireNonNegative(spec, k);
  requirePositive(spec, "dilatancy_pressure");
  if (!(get(spec, "max_strength", 0) > get(spec, "intact_strength", 0)))
    fail(spec, "max_strength", "must exceed intact_strength");
  const double t0 = get(spec, "tensile_strength", 0);
  if (!(get(spec, "damage_strain", 0) > t0 / p.bulk))
    fail(spec, "damage_strain",
         "must exceed tensile_strength / bulk modulus = " + num(t0 / p.bulk) +
             " (a steeper softening than the elastic unloading snaps back)");
  const double phi = get(spec, "porosity", 0);
  if (!(phi >= 0 && phi < 1))
    fail(spec, "porosity", "must be in [0, 1) (got " + num(phi) + ")");
  if (phi == 0)
  {
    for (const char *k : {"crush_pressure", "lock_pressure", "solid_bulk_modulus"})
      if (has(spec, k))
        fail(spec, k, "only meaningful with porosity > 0");
    return;
  }
  for (const char *k : {"crush_pressure", "lock_pressure"})
    if (!has(spec, k))
      fail(spec, k, "required with porosity > 0");
  requireNonNegative(spec, "crush_pressure");
  if (!(get(spec, "lock_pressure", 0) > get(spec, "crush_pressure", 0)))
    fail(spec, "lock_pressure", "must exceed crush_pressure");
  if (has(spec, "solid_bulk_modulus") && !(get(spec, "solid_bulk_modulus", 0) >= p.bulk))
    fail(spec, "solid_bulk_modulus", "must be >= the (porous) bulk modulus " + num(p.bulk));
  // the crush residual must fall along the curve, or the compaction would stiffen faster than
  // it relieves the elastic strain (no unique return)
  const Real tl = p.model_params[kGeoThetaLock];
  for (int i = 0; i <= 20; ++i)
  {
    const Real x = tl * i / 20;
    const Real K = geoBulk(p, x), pc = geoCrushPressure(p, x);
    const Real slope = (p.model_params[kGeoKs] - p.bulk) / tl * pc / K - K -
                       (p.model_params[kGeoPlock] - p.model_params[kGeoPcrush]) / tl;
    if (slope >= 0)
      fail(spec, "solid_bulk_modulus",
           "too stiff for the crush curve (the compaction would raise the pressure it relieves)");
  }
}

JwlCjState validateHighExplosive(const MaterialSpec &spec, const MaterialParams &p)
{
  for (const char *k : {"eos.R1", "eos.R2", "eos.omega", "eos.E0"})
    requirePositive(spec, k);
  const JwlCjState cj = jwlChapmanJouguet(p.model_params, p.density);
  if (!cj.ok)
    fail(spec, "eos.E0",
         "the JWL constants (eos.A, eos.B, eos.R1, eos.R2, eos.omega, eos.E0) with this density "
         "give no Chapman-Jouguet state (the products Hugoniot has no point where the Rayleigh "
         "line is tangent with p > 0)");
  if (has(spec, "D"))
  {
    requirePositive(spec, "D");
    if (std::fabs(get(spec, "D", 0) / cj.D - 1) > 0.05)
      fail(spec, "D",
           "differs by more than 5 % from the JWL model's CJ detonation velocity " + num(cj.D) +
               " m/s (density or JWL constants inconsistent?)");
  }
  if (has(spec, "pcj"))
  {
    requirePositive(spec, "pcj");
    if (std::fabs(get(spec, "pcj", 0) / cj.p - 1) > 0.05)
      fail(spec, "pcj",
           "differs by more than 5 % from the JWL model's CJ pressure " + num(cj.p) + " Pa");
  }
  const double axis = get(spec, "ignition_axis", -1);
  if (!(axis == -1 || axis == 0 || axis == 1 || axis == 2))
    fail(spec, "ignition_axis", "must be -1 (point), 0, 1 or 2 (line along x, y or z)");
  requirePositive(spec, "burn_width");
  const double beta = get(spec, "beta_burn", 1);
  if (!(beta == 0 || beta == 1))
    fail(spec, "beta_burn", "must be 0 or 1");
  return cj;
}

// the erosion limits (docs/input.md): each one a measure the model has, in its range
void validateErosionKeys(const MaterialSpec &spec)
{
  auto check = [&](const char *key, bool ok, const char *range) {
    if (has(spec, key) && !ok)
      fail(spec, key,
           std::string("must be ") + range + " (got " + formatReal(get(spec, key, 0)) + ")");
  };
  check("erosion.plastic_strain", get(spec, "erosion.plastic_strain", 0) > 0, "> 0");
  const double d = get(spec, "erosion.damage", 0);
  check("erosion.damage", d > 0 && d <= 1, "in (0, 1]");
  const double vmin = get(spec, "erosion.volumetric_strain_min", 0);
  check("erosion.volumetric_strain_min", vmin > -1 && vmin < 0, "in (-1, 0)");
  check("erosion.volumetric_strain_max", get(spec, "erosion.volumetric_strain_max", 0) > 0, "> 0");
  check("erosion.time_step", get(spec, "erosion.time_step", 0) > 0, "> 0 s");
  const bool plastic = spec.model == "elastic_plastic" || spec.model == "johnson_cook" ||
                       spec.model == "geomaterial";
  if (has(spec, "erosion.plastic_strain") && !plastic)
    fail(spec, "erosion.plastic_strain", "model '" + spec.model + "' has no plastic strain");
  if (has(spec, "erosion.damage") && spec.model != "geomaterial")
    fail(spec, "erosion.damage", "only the geomaterial has damage (model '" + spec.model + "')");
}

// everything that needs no cross-key physics: names, combinations, presence, finiteness
void validateKeys(const MaterialSpec &spec)
{
  static const std::set<std::string> models = {"elastic", "elastic_plastic", "johnson_cook",
                                               "geomaterial", "high_explosive"};
  if (!models.count(spec.model))
    fail(
        spec, "model",
        "unknown model '" + spec.model +
            "' (expected elastic | elastic_plastic | johnson_cook | geomaterial | high_explosive)");
  if (spec.eos != "linear" && spec.eos != "mie_gruneisen" && spec.eos != "jwl")
    fail(spec, "eos.type",
         "unknown eos '" + spec.eos + "' (expected linear | mie_gruneisen | jwl)");
  if ((spec.model == "high_explosive") != (spec.eos == "jwl"))
    fail(spec, "eos.type", "model high_explosive goes with eos jwl, and eos jwl only with it");
  if (spec.model == "geomaterial" && spec.eos != "linear")
    fail(spec, "eos.type", "the geomaterial has its own compaction EOS; use eos linear");

  std::set<std::string> allowed = {"erosion.plastic_strain", "erosion.damage",
                                   "erosion.volumetric_strain_min", "erosion.volumetric_strain_max",
                                   "erosion.time_step"};
  for (const auto *rules : {&modelKeys(spec.model), &eosKeys(spec.eos)})
    for (const auto &r : *rules)
    {
      allowed.insert(r.key);
      if (r.required && !has(spec, r.key))
        fail(spec, r.key,
             "required key is missing for model '" + spec.model + "' / eos '" + spec.eos + "'");
    }
  for (const auto &kv : spec.values)
  {
    if (!allowed.count(kv.first))
      fail(spec, kv.first, "unknown key for model '" + spec.model + "' / eos '" + spec.eos + "'");
    if (!std::isfinite(kv.second))
      fail(spec, kv.first, "value is not a finite number");
  }
  if (get(spec, "density", 0) <= 0)
    fail(spec, "density", "must be > 0 (got " + formatReal(get(spec, "density", 0)) + ")");
  validateErosionKeys(spec);
  if (spec.model != "high_explosive")
    validateElasticKeys(spec);
  if (spec.model == "elastic_plastic")
  {
    if (get(spec, "yield_stress", 0) <= 0)
      fail(spec, "yield_stress", "must be > 0");
    if (get(spec, "hardening_modulus", 0) < 0)
      fail(spec, "hardening_modulus", "must be >= 0");
  }
  if (spec.eos == "mie_gruneisen")
  {
    if (get(spec, "eos.c0", 0) <= 0)
      fail(spec, "eos.c0", "must be > 0");
    if (get(spec, "eos.s", 0) < 0)
      fail(spec, "eos.s", "must be >= 0");
  }
}

// conversion without the model-physics checks (they need the converted parameters)
MaterialParams convert(const MaterialSpec &spec)
{
  MaterialParams p;
  p.model = spec.model == "elastic_plastic"  ? MaterialModel::ElasticPlastic
            : spec.model == "johnson_cook"   ? MaterialModel::JohnsonCook
            : spec.model == "geomaterial"    ? MaterialModel::Geomaterial
            : spec.model == "high_explosive" ? MaterialModel::HighExplosive
                                             : MaterialModel::Elastic;
  p.eos = spec.eos == "mie_gruneisen" ? EosModel::MieGruneisen
          : spec.eos == "jwl"         ? EosModel::Jwl
                                      : EosModel::Linear;
  p.density = get(spec, "density", 0);
  if (has(spec, "youngs_modulus"))
  {
    const double E = get(spec, "youngs_modulus", 0), nu = get(spec, "poisson_ratio", 0);
    p.bulk = E / (3 * (1 - 2 * nu));
    p.shear = E / (2 * (1 + nu));
  }
  else
  {
    p.shear = get(spec, "shear_modulus", 0);
    p.bulk = get(spec, "bulk_modulus", 0);
  }
  p.yield_stress = get(spec, "yield_stress", 0);
  p.hardening_modulus = get(spec, "hardening_modulus", 0);
  if (p.eos == EosModel::MieGruneisen)
  {
    p.mg_c0 = get(spec, "eos.c0", 0);
    p.mg_s = get(spec, "eos.s", 0);
    p.mg_gamma0 = get(spec, "eos.gamma0", 0);
    p.mg_a = get(spec, "eos.a", 0);
    // the EOS sets the bulk response: K0 = rho0 c0^2 (used for time-step estimates)
    p.bulk = p.density * p.mg_c0 * p.mg_c0;
  }
  ErosionLimits &er = p.erosion;
  er.plastic_strain = get(spec, "erosion.plastic_strain", 0);
  er.damage = get(spec, "erosion.damage", 0);
  er.volumetric_strain_min = get(spec, "erosion.volumetric_strain_min", 0);
  er.volumetric_strain_max = get(spec, "erosion.volumetric_strain_max", 0);
  er.time_step = get(spec, "erosion.time_step", 0);
  er.active = er.plastic_strain > 0 || er.damage > 0 || er.volumetric_strain_min < 0 ||
              er.volumetric_strain_max > 0 || er.time_step > 0;
  Real *m = p.model_params;
  auto set = [&](int slot, const char *key) { m[slot] = get(spec, key, 0); };
  switch (p.model)
  {
  case MaterialModel::JohnsonCook:
    set(kJcA, "A"), set(kJcB, "B"), set(kJcN, "n"), set(kJcC, "C"), set(kJcM, "m");
    set(kJcTmelt, "melt_temperature"), set(kJcTroom, "room_temperature");
    set(kJcRate0, "reference_strain_rate"), set(kJcCp, "specific_heat");
    set(kJcChi, "taylor_quinney");
    break;
  case MaterialModel::Geomaterial:
    set(kGeoPcrush, "crush_pressure"), set(kGeoPlock, "lock_pressure");
    m[kGeoKs] = has(spec, "solid_bulk_modulus") ? get(spec, "solid_bulk_modulus", 0) : p.bulk;
    m[kGeoThetaLock] = -std::log(1 - get(spec, "porosity", 0));
    set(kGeoY0, "intact_strength"), set(kGeoMuI, "intact_friction");
    set(kGeoYmax, "max_strength"), set(kGeoMuD, "damaged_friction");
    set(kGeoT0, "tensile_strength"), set(kGeoBeta, "dilatancy");
    set(kGeoPbd, "dilatancy_pressure"), set(kGeoEpsD, "damage_strain");
    set(kGeoHc, "compaction_hardening"), set(kGeoGf, "fracture_energy");
    break;
  case MaterialModel::HighExplosive:
    set(kJwlA, "eos.A"), set(kJwlB, "eos.B"), set(kJwlR1, "eos.R1"), set(kJwlR2, "eos.R2");
    set(kJwlOmega, "eos.omega"), set(kJwlE0, "eos.E0");
    set(kHeIgnX, "ignition_x"), set(kHeIgnY, "ignition_y"), set(kHeIgnZ, "ignition_z");
    set(kHeAxis, "ignition_axis"), set(kHeT0, "initiation_time");
    set(kHeBurnWidth, "burn_width"), set(kHeBetaBurn, "beta_burn");
    break;
  default:
    break;
  }
  return p;
}

} // namespace

void validateMaterialSpec(const MaterialSpec &spec) { makeMaterialParams(spec); }

MaterialParams makeMaterialParams(const MaterialSpec &spec)
{
  validateKeys(spec);
  MaterialParams p = convert(spec);
  if (p.model == MaterialModel::JohnsonCook)
    validateJohnsonCook(spec, p);
  else if (p.model == MaterialModel::Geomaterial)
    validateGeomaterial(spec, p);
  else if (p.model == MaterialModel::HighExplosive)
  {
    const JwlCjState cj = validateHighExplosive(spec, p);
    Real *m = p.model_params;
    m[kHeD] = has(spec, "D") ? get(spec, "D", 0) : cj.D;
    m[kHePcj] = has(spec, "pcj") ? get(spec, "pcj", 0) : cj.p;
    m[kHeVcj] = cj.V;
    // products carry no shear; D bounds their sound speed, so it sizes the first time step
    p.shear = 0;
    p.bulk = p.density * m[kHeD] * m[kHeD];
  }
  return p;
}

Real referenceSoundSpeed(const MaterialParams &p)
{
  return std::sqrt(pWaveModulus(p.bulk, p.shear) / p.density);
}

std::vector<std::string> historyNames(const MaterialParams &p)
{
  std::vector<std::string> names(kHistorySize);
  switch (p.model)
  {
  case MaterialModel::JohnsonCook:
    names[kJcHistTemperature] = "temperature";
    names[kJcHistRate] = "plastic_strain_rate";
    break;
  case MaterialModel::Geomaterial:
    names[kGeoHistDamage] = "damage";
    names[kGeoHistTensile] = "tensile_strength";
    names[kGeoHistThetaP] = "plastic_volumetric_strain";
    break;
  case MaterialModel::HighExplosive:
    names[kHeHistLightTime] = "lighting_time";
    names[kHeHistBurn] = "burn_fraction";
    break;
  default:
    break;
  }
  return names;
}

Real initialSpecificEnergy(const MaterialParams &p)
{
  return p.model == MaterialModel::HighExplosive ? p.model_params[kJwlE0] / p.density : Real(0);
}

} // namespace scpdyn
