/// \file DeckParser.cpp
/// \brief YAML deck -> typed, validated Deck. Every key of docs/input.md is read here; the
/// schema's "which keys may appear where" lives in the key lists passed to YamlValue::map.
#include "input/DeckSections.hpp"
#include "input/YamlReader.hpp"
#include "material/MaterialSpec.hpp"

#include <yaml-cpp/depthguard.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace scpdyn
{

const char *deckName(MeshType t)
{
  return t == MeshType::Block ? "block" : t == MeshType::BrickWall ? "brick_wall" : "gmsh";
}
const char *deckName(ConditionType t)
{
  return t == ConditionType::Velocity ? "velocity"
         : t == ConditionType::Force  ? "force"
                                      : "pressure";
}
const char *deckName(GaugeKind k)
{
  return k == GaugeKind::Node ? "node" : k == GaugeKind::Element ? "element" : "joint";
}
const char *deckName(HourglassForm f)
{
  return f == HourglassForm::Viscous ? "viscous" : "stiffness";
}
const char *deckName(ScatterMode s) { return s == ScatterMode::Gather ? "gather" : "atomic"; }
const char *deckName(NodeUpdateMode m) { return m == NodeUpdateMode::Fused ? "fused" : "separate"; }
const char *deckName(ElementType t)
{
  return t == ElementType::Line2   ? "line2"
         : t == ElementType::Quad4 ? "quad4"
         : t == ElementType::Hex8  ? "hex8"
                                   : "tet4";
}
const char *deckName(BrickBond b) { return b == BrickBond::English ? "english" : "running"; }

namespace input_impl
{

bool isPositive(Real x) { return x > 0; }
bool isNonNegative(Real x) { return x >= 0; }

Real readReal(const YamlMap &m, const std::string &key, Real fallback, bool (*ok)(Real),
              const char *expected)
{
  if (!m.has(key))
    return fallback;
  const YamlValue v = m[key];
  const Real x = v.real();
  if (ok && !ok(x))
    v.fail(std::string("must be ") + expected + ", got " + v.text());
  return x;
}

Real requireReal(const YamlMap &m, const std::string &key, bool (*ok)(Real), const char *expected)
{
  if (!m.has(key))
    m.missing(key);
  return readReal(m, key, 0, ok, expected);
}

void claimName(std::map<std::string, int> &seen, const YamlValue &v, const std::string &name)
{
  const auto it = seen.find(name);
  if (it != seen.end())
    v.fail("duplicate name '" + name + "' (already used on line " + std::to_string(it->second) +
           ")");
  seen[name] = v.line();
}

void checkReference(const YamlValue &v, const std::string &name, const std::string &what,
                    const std::map<std::string, int> &defined)
{
  if (defined.count(name))
    return;
  std::vector<std::string> names;
  for (const auto &kv : defined)
    names.push_back(kv.first);
  if (names.empty())
    v.fail("unknown " + what + " '" + name + "' (none is defined)");
  v.fail("unknown " + what + " '" + name + "'" + suggestion(name, names));
}

void restrictKeys(const YamlMap &m, const std::vector<std::string> &allowed,
                  const std::string &context)
{
  for (const auto &e : m.entries())
    if (std::find(allowed.begin(), allowed.end(), e.key) == allowed.end())
      m[e.key].fail("unknown key '" + e.key + "' for " + context + suggestion(e.key, allowed));
}

} // namespace input_impl

namespace
{
using namespace input_impl;
namespace fs = std::filesystem;

void parseTime(const YamlMap &root, Deck &deck)
{
  if (!root.has("time"))
    root.missing("time");
  const YamlMap t =
      root["time"].map({"end", "courant", "dt_max", "max_cycles", "max_estimated_cycles"});
  deck.end_time = requireReal(t, "end", isPositive, "> 0");
  deck.courant = readReal(
      t, "courant", deck.courant, [](Real s) { return s > 0 && s <= 1; }, "in (0, 1]");
  deck.dt_max = readReal(t, "dt_max", deck.dt_max, isPositive, "> 0");
  if (t.has("max_cycles"))
  {
    deck.max_cycles = t["max_cycles"].integer();
    if (deck.max_cycles <= 0)
      t["max_cycles"].fail("must be an integer > 0, got " + t["max_cycles"].text());
  }
  deck.max_estimated_cycles =
      readReal(t, "max_estimated_cycles", deck.max_estimated_cycles, isPositive, "> 0");
}

void parseNumerics(const YamlMap &root, Deck &deck)
{
  if (!root.has("numerics"))
    return;
  const YamlMap n = root["numerics"].map({"hourglass", "bulk_viscosity", "scatter", "node_update"});
  if (n.has("hourglass"))
  {
    const YamlMap h = n["hourglass"].map({"type", "coefficient"});
    deck.hourglass_type = readChoice(h, "type", {HourglassForm::Viscous, HourglassForm::Stiffness},
                                     deck.hourglass_type);
    deck.hourglass_coefficient =
        readReal(h, "coefficient", deck.hourglass_coefficient, isNonNegative, ">= 0");
  }
  if (n.has("bulk_viscosity"))
  {
    const YamlMap q = n["bulk_viscosity"].map({"linear", "quadratic"});
    deck.bulk_viscosity_linear =
        readReal(q, "linear", deck.bulk_viscosity_linear, isNonNegative, ">= 0");
    deck.bulk_viscosity_quadratic =
        readReal(q, "quadratic", deck.bulk_viscosity_quadratic, isNonNegative, ">= 0");
  }
  deck.scatter = readChoice(n, "scatter", {ScatterMode::Atomic, ScatterMode::Gather}, deck.scatter);
  deck.node_update = readChoice(n, "node_update", {NodeUpdateMode::Fused, NodeUpdateMode::Separate},
                                deck.node_update);
}

void parseOutput(const YamlMap &root, Deck &deck, const std::string &stem)
{
  deck.output_dir = "out/" + stem;
  if (!root.has("output"))
    return;
  const YamlMap o =
      root["output"].map({"directory", "field_interval", "history_interval", "progress_interval",
                          "max_output_bytes", "restart_interval", "restart_keep"});
  deck.output_dir = o.string("directory", deck.output_dir);
  deck.field_interval = readReal(o, "field_interval", 0, isNonNegative, ">= 0");
  deck.history_interval = readReal(o, "history_interval", 0, isNonNegative, ">= 0");
  deck.progress_interval =
      readReal(o, "progress_interval", deck.progress_interval, isPositive, "> 0");
  deck.max_output_bytes = readReal(o, "max_output_bytes", deck.max_output_bytes, isPositive, "> 0");
  deck.restart_interval = readReal(o, "restart_interval", 0, isNonNegative, ">= 0");
  if (o.has("restart_keep"))
  {
    const long keep = o["restart_keep"].integer();
    if (keep < 1 || keep > 1000000)
      o["restart_keep"].fail("must be an integer >= 1, got " + o["restart_keep"].text());
    deck.restart_keep = int(keep);
  }
}

std::map<std::string, int> parseFunctions(const YamlMap &root, Deck &deck)
{
  std::map<std::string, int> names;
  if (!root.has("functions"))
    return names;
  for (const YamlValue &item : root["functions"].list())
  {
    const YamlMap f = item.map({"name", "points"});
    TimeFunction fn;
    fn.name = f["name"].string();
    claimName(names, f["name"], fn.name);
    if (!f.has("points"))
      f.missing("points");
    const auto points = f["points"].list(1);
    for (std::size_t i = 0; i < points.size(); ++i)
    {
      const auto pair = points[i].list();
      if (pair.size() != 2)
        points[i].fail("expected a [t, value] pair, got " + std::to_string(pair.size()) +
                       " entries");
      const Real t = pair[0].real(), v = pair[1].real();
      if (i > 0 && !(t > fn.t.back()))
        pair[0].fail("times must increase strictly: t = " + pair[0].text() +
                     " follows t = " + formatReal(fn.t.back()));
      fn.t.push_back(t);
      fn.value.push_back(v);
    }
    deck.functions.push_back(fn);
  }
  return names;
}

std::map<std::string, int> parseMaterials(const YamlMap &root, Deck &deck)
{
  std::map<std::string, int> names;
  if (!root.has("materials"))
    root.missing("materials");
  const auto items = root["materials"].list(1);
  for (std::size_t i = 0; i < items.size(); ++i)
  {
    // Model keys are open here; validateMaterialSpec knows which ones each model takes.
    const YamlMap m = items[i].openMap();
    MaterialSpec spec;
    spec.index = static_cast<int>(i);
    spec.line = items[i].line();
    spec.name = m["name"].string();
    claimName(names, m["name"], spec.name);
    for (const auto &e : m.entries())
    {
      const YamlValue v = m[e.key];
      spec.lines[e.key] = e.line;
      if (e.key == "name")
        continue;
      if (e.key == "model")
        spec.model = v.string();
      else if (e.key == "eos")
      {
        const YamlMap eos = v.openMap();
        for (const auto &ee : eos.entries())
        {
          const YamlValue ev = eos[ee.key];
          spec.lines["eos." + ee.key] = ee.line;
          if (ee.key == "type")
            spec.eos = ev.string();
          else
            spec.values["eos." + ee.key] = ev.real();
        }
      }
      else if (e.key == "erosion")
      {
        const YamlMap erosion = v.openMap();
        for (const auto &ee : erosion.entries())
        {
          spec.lines["erosion." + ee.key] = ee.line;
          spec.values["erosion." + ee.key] = erosion[ee.key].real();
        }
      }
      else
        spec.values[e.key] = v.real();
    }
    validateMaterialSpec(spec);
    deck.materials.push_back(spec);
  }
  return names;
}

} // namespace

Deck parseDeckString(const std::string &yaml_text, const std::string &path)
{
  std::vector<YAML::Node> docs;
  try
  {
    docs = YAML::LoadAll(yaml_text);
  }
  catch (const YAML::Exception &e)
  {
    const std::string line =
        e.mark.is_null() ? "" : " (line " + std::to_string(e.mark.line + 1) + ")";
    // yaml-cpp stops at 500 nested levels; what reaches here is then its "bad file"
    const bool deep = dynamic_cast<const YAML::DeepRecursion *>(&e) != nullptr ||
                      dynamic_cast<const YAML::BadFile *>(&e) != nullptr;
    throw InputError(path + ": <document>" + line + ": " +
                     (deep ? std::string("lists or maps nested deeper than the YAML reader's "
                                         "limit of 500 levels")
                           : "YAML syntax error: " + e.msg));
  }
  try
  {
    if (docs.size() > 1)
      YamlValue(docs[1], "", docs[1].Mark().line + 1)
          .fail("found a second YAML document; a deck is one document");
    if (docs.empty() || docs[0].IsNull())
      YamlValue(YAML::Node(), "", 1)
          .fail("the deck is empty; expected a mapping with at least dimension, time, "
                "materials and parts");
    Deck deck;
    deck.path = path;
    const std::string stem = fs::path(path).stem().string();
    fs::path dir = fs::path(path).parent_path();
    if (dir.empty())
      dir = ".";

    const YamlMap root =
        YamlValue(docs[0], "", docs[0].Mark().line + 1)
            .map({"title", "dimension", "geometry", "time", "numerics", "gravity", "settling",
                  "output", "materials", "parts", "node_sets", "face_sets", "functions",
                  "boundary_conditions", "initial_conditions", "gauges", "contact"});
    deck.title = root.string("title", stem);
    if (!root.has("dimension"))
      root.missing("dimension");
    const long dim = root["dimension"].integer();
    if (dim < 1 || dim > 3)
      root["dimension"].fail("must be 1, 2 or 3, got " + root["dimension"].text());
    deck.dimension = static_cast<int>(dim);
    if (root.has("geometry"))
    {
      if (deck.dimension != 2)
        root["geometry"].fail("only applies to dimension 2 (this deck has dimension " +
                              std::to_string(deck.dimension) + ")");
      deck.geometry = root["geometry"].choice({"plane_strain", "axisymmetric"}) == "axisymmetric"
                          ? Geometry2D::Axisymmetric
                          : Geometry2D::PlaneStrain;
    }
    parseTime(root, deck);
    parseNumerics(root, deck);
    parseOutput(root, deck, stem);

    DeckNames names;
    names.functions = parseFunctions(root, deck);
    parseGravity(root, deck, names);
    parseSettling(root, deck);
    names.materials = parseMaterials(root, deck);
    parseParts(root, deck, names, dir);
    parseSetsAndConditions(root, deck, names);
    parseGauges(root, deck);
    parseContact(root, deck, names);
    return deck;
  }
  catch (const InputError &e)
  {
    throw InputError(path + ": " + e.what());
  }
  catch (const YAML::Exception &e)
  {
    throw InputError(path + ": <document>: " + e.what());
  }
}

Deck parseDeck(const std::string &path)
{
  std::error_code ec;
  if (!fs::exists(path, ec))
    throw InputError(path + ": <document>: cannot read the deck: no such file");
  if (!fs::is_regular_file(path, ec))
    throw InputError(path + ": <document>: cannot read the deck: not a regular file");
  std::ifstream in(path);
  if (!in)
    throw InputError(path + ": <document>: cannot open the deck for reading");
  std::ostringstream text;
  text << in.rdbuf();
  return parseDeckString(text.str(), path);
}

} // namespace scpdyn
