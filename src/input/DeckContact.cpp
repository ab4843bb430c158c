/// \file DeckContact.cpp
/// \brief The `contact` section of the deck: search controls and the contact surfaces with their
/// face-based contact conditions (docs/input.md). Joint parameters are read in the units of the
/// paper's Table 1 (mm, GPa, degrees) and stored as written; the contact room converts to SI.
#include "input/DeckSections.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace scpdyn
{
namespace input_impl
{
namespace
{

const std::vector<std::string> kSurfaceKeys = {"name",
                                               "part",
                                               "face_set",
                                               "option",
                                               "a",
                                               "E0",
                                               "G",
                                               "C",
                                               "phi0",
                                               "phi1",
                                               "usp0",
                                               "psi0",
                                               "sigma_cr",
                                               "Emax",
                                               "sigma_t",
                                               "C_safe",
                                               "dt_form",
                                               "dilation_update",
                                               "distribution",
                                               "velocity",
                                               "traction_history",
                                               "implicit_shear",
                                               "brittle_tension",
                                               "mu_static",
                                               "mu_kinetic",
                                               "mu_decay",
                                               "failure_measure",
                                               "failure_threshold",
                                               "failure_sides"};

/// A Table 1 stress or modulus in GPa; values that only make sense in Pa get a unit hint.
Real readGPa(const YamlMap &m, const std::string &key, Real fallback, bool positive)
{
  if (!m.has(key))
    return fallback;
  const YamlValue v = m[key];
  const Real x = v.real();
  if (positive ? !(x > 0) : !(x >= 0))
    v.fail(std::string("must be ") + (positive ? "> 0" : ">= 0") + " (GPa), got " + v.text());
  if (x > 1e4)
    v.fail("is in GPa (units of the paper's Table 1), got " + v.text() +
           " GPa; did you give it in Pa?");
  return x;
}

Real readAngle(const YamlMap &m, const std::string &key, Real fallback)
{
  return readReal(
      m, key, fallback, [](Real x) { return x >= 0 && x < 90; }, "in [0, 90) (degrees)");
}

/// `auto` (a derived default, stored as -1) or a value in GPa.
Real readAutoGPa(const YamlMap &m, const std::string &key)
{
  if (!m.has(key) || m[key].text() == "auto")
    return -1;
  return readGPa(m, key, -1, false);
}

/// Coulomb friction of a slide line (LS-DYNA's FS, FD, DC), and of a sleepy surface once it
/// fails: the joint options have their own friction (phi0, phi1), the sticky option none.
void parseFriction(const YamlMap &m, SurfaceSpec &s)
{
  for (const char *key : {"mu_static", "mu_kinetic", "mu_decay"})
    if (m.has(key) && s.option != "slide_line" && s.option != "sleepy")
      m[key].fail("friction coefficients belong to the slide_line and sleepy options; option '" +
                  s.option + "' " +
                  (s.option == "sticky" ? "does not slip"
                                        : "has the joint law's friction angles phi0 and phi1"));
  auto coefficient = [](Real x) { return x >= 0 && x <= 10; };
  s.mu_static = readReal(m, "mu_static", s.mu_static, coefficient, "in [0, 10]");
  s.mu_kinetic = readReal(m, "mu_kinetic", s.mu_kinetic, coefficient, "in [0, 10]");
  if (m.has("mu_kinetic") && s.mu_kinetic > s.mu_static)
    m["mu_kinetic"].fail("must not exceed mu_static = " + formatReal(s.mu_static) + ", got " +
                         m["mu_kinetic"].text());
  s.mu_decay = readReal(m, "mu_decay", s.mu_decay, isNonNegative, ">= 0 (s/m)");
}

/// The switch of a sleepy surface (tied until the elements behind its faces fail): which
/// measure, its threshold, and whether either or both elements must reach it.
void parseFailure(const YamlMap &m, SurfaceSpec &s, const Deck &deck)
{
  for (const char *key : {"failure_measure", "failure_threshold", "failure_sides"})
    if (m.has(key) && s.option != "sleepy")
      m[key].fail("belongs to the sleepy option (tied until the material fails), not to option '" +
                  s.option + "'");
  if (s.option != "sleepy")
    return;
  if (!m.has("failure_measure"))
    m.missing("failure_measure");
  if (!m.has("failure_threshold"))
    m.missing("failure_threshold");
  s.failure_measure = m.choice("failure_measure", {"plastic_strain", "damage", "time"}, "");
  s.failure_threshold = readReal(m, "failure_threshold", s.failure_threshold, isNonNegative,
                                 s.failure_measure == "time" ? ">= 0 (s)" : ">= 0");
  s.failure_sides = m.choice("failure_sides", {"either", "both"}, s.failure_sides);
  const bool has_damage =
      std::any_of(deck.materials.begin(), deck.materials.end(),
                  [](const MaterialSpec &x) { return x.model == "geomaterial"; });
  if (s.failure_measure == "damage" && !has_damage)
    m["failure_measure"].fail("damage is a measure of the geomaterial model, and no material of "
                              "the deck is one; use plastic_strain, or time");
}

SurfaceSpec parseSurface(const YamlValue &item, const Deck &deck, const DeckNames &names,
                         bool check_sets, std::map<std::string, int> &seen)
{
  const YamlMap m = item.map(kSurfaceKeys);
  SurfaceSpec s;
  s.name = m["name"].string();
  claimName(seen, m["name"], s.name);
  if (m.exactlyOne({"part", "face_set"}) == "part")
  {
    s.part = m["part"].string();
    checkPartReference(m["part"], s.part, names);
  }
  else
  {
    s.face_set = m["face_set"].string();
    if (check_sets)
      checkReference(m["face_set"], s.face_set, "face set", names.face_sets);
  }
  s.option =
      m.choice("option", {"slide_line", "sticky", "sleepy", "explicit", "implicit"}, s.option);
  if (m.has("a"))
  {
    s.a = readReal(m, "a", s.a, isPositive, "> 0 (mm)");
    if (s.a > 1000)
      m["a"].fail("is in mm (units of the paper's Table 1), got " + m["a"].text() +
                  " mm; did you give it in m?");
  }
  s.E0 = readGPa(m, "E0", s.E0, true);
  s.G = readGPa(m, "G", s.G, true);
  s.C = readGPa(m, "C", s.C, false);
  s.phi0 = readAngle(m, "phi0", s.phi0);
  s.phi1 = readAngle(m, "phi1", s.phi1);
  s.psi0 = readAngle(m, "psi0", s.psi0);
  s.usp0 = readReal(m, "usp0", s.usp0, isNonNegative, ">= 0 (apertures)");
  s.sigma_cr = readGPa(m, "sigma_cr", s.sigma_cr, false);
  s.Emax = readAutoGPa(m, "Emax");
  if (s.Emax >= 0 && !(s.Emax > s.E0))
    m["Emax"].fail("must exceed E0 = " + formatReal(s.E0) + " GPa, got " + m["Emax"].text());
  s.sigma_t = readAutoGPa(m, "sigma_t");
  if (m.has("C_safe"))
  {
    const YamlValue v = m["C_safe"];
    if (v.text() == "off")
      s.C_safe = std::numeric_limits<Real>::infinity();
    else
    {
      s.C_safe = v.real();
      if (!(s.C_safe > 0))
        v.fail("must be > 0 or 'off', got " + v.text());
    }
  }
  s.dt_form = m.choice("dt_form", {"mass_spring", "paper"}, s.dt_form);
  s.dilation_update = m.choice("dilation_update", {"consistent", "explicit"}, s.dilation_update);
  s.distribution = m.choice("distribution", {"penetration", "poc"}, s.distribution);
  s.velocity = m.choice("velocity", {"weighted", "average"}, s.velocity);
  s.traction_history = m.boolean("traction_history", s.traction_history);
  s.implicit_shear = m.boolean("implicit_shear", s.implicit_shear);
  s.brittle_tension = m.boolean("brittle_tension", s.brittle_tension);
  parseFriction(m, s);
  parseFailure(m, s, deck);
  return s;
}

} // namespace

void parseContact(const YamlMap &root, Deck &deck, const DeckNames &names)
{
  if (!root.has("contact"))
    return;
  const YamlMap c =
      root["contact"].map({"search_interval", "constraint_passes", "search_gap", "surfaces"});
  ContactSpec &spec = deck.contact;
  if (c.has("search_interval"))
  {
    const YamlValue v = c["search_interval"];
    if (v.text() == "once")
      spec.search_interval = 0;
    else
    {
      if (!v.node().IsScalar() || v.text().find_first_not_of("0123456789+-") != std::string::npos)
        v.fail("must be 'once' or an integer >= 1 (cycles), got " + v.text());
      spec.search_interval = v.integer();
      if (spec.search_interval < 1)
        v.fail("must be 'once' or an integer >= 1 (cycles), got " + v.text());
    }
  }
  if (c.has("constraint_passes"))
  {
    const long n = c["constraint_passes"].integer();
    if (n < 1 || n > 1000)
      c["constraint_passes"].fail("must be an integer in [1, 1000], got " +
                                  c["constraint_passes"].text());
    spec.constraint_passes = int(n);
  }
  if (c.has("search_gap"))
  {
    const YamlValue v = c["search_gap"];
    char *end = nullptr;
    const std::string t = v.text();
    const double x = std::strtod(t.c_str(), &end);
    if (t == "motion")
      spec.search_gap_motion = true;
    else if (!v.node().IsScalar() || t.empty() || *end != '\0' || !isPositive(x))
      v.fail("must be a gap > 0 (m) or 'motion', got " + t);
    else
      spec.search_gap = x;
  }
  if (!c.has("surfaces"))
    c.missing("surfaces");
  const bool check_sets = std::none_of(deck.parts.begin(), deck.parts.end(), [](const PartSpec &p) {
    return p.mesh.type == MeshType::Gmsh;
  });
  std::map<std::string, int> seen;
  for (const YamlValue &item : c["surfaces"].list(1))
    spec.surfaces.push_back(parseSurface(item, deck, names, check_sets, seen));
}

} // namespace input_impl
} // namespace scpdyn
