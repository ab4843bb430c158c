/// \file DeckSections.cpp
/// \brief Deck sections that refer to each other: parts (meshes, materials), node/face sets,
/// boundary conditions and gauges.
#include "input/DeckSections.hpp"

#include <algorithm>
#include <cmath>

namespace scpdyn
{
namespace input_impl
{
namespace
{
namespace fs = std::filesystem;

const ElementType kDefaultElement[] = {ElementType::Quad4, ElementType::Line2, ElementType::Quad4,
                                       ElementType::Hex8};

std::array<Real, 3> positiveVector(const YamlMap &m, const std::string &key, int dim)
{
  const YamlValue v = m[key];
  const std::array<Real, 3> x = v.realVector(dim);
  const auto items = v.list();
  for (int i = 0; i < dim; ++i)
    if (!(x[i] > 0))
      items[i].fail("must be > 0, got " + items[i].text());
  return x;
}

/// \brief The English bond's rules (docs/input.md, parts[].mesh): a 3D wall two stretchers
/// thick whose headers span it, so a brick is two widths long; its offsets are its own.
void checkEnglishBond(const YamlMap &m, const MeshSpec &mesh, int dim)
{
  if (dim != 3)
    m["bond"].fail("bond 'english' needs a 3D wall (header courses span the thickness), but the "
                   "deck has dimension " +
                   std::to_string(dim));
  const int s = mesh.stagger_axis, r = 1 - s;
  if (mesh.count[size_t(r)] != 2)
    m["count"].fail("bond 'english' needs exactly 2 rows through the thickness (count along " +
                    std::string(r == 0 ? "x" : "y") + "), got " +
                    std::to_string(mesh.count[size_t(r)]));
  const Real L = mesh.brick_size[size_t(s)], W = mesh.brick_size[size_t(r)];
  if (!(std::fabs(L - 2 * W) <= 1e-9 * L))
    m["brick_size"].fail("bond 'english' needs a brick length (" + formatReal(L) +
                         " m) of twice its width (" + formatReal(W) +
                         " m), so a header spans the two stretchers");
  if (m.has("stagger"))
    m["stagger"].fail("bond 'english' sets its own joint offsets (quarter-brick closers in the "
                      "header courses); remove stagger");
}

MeshSpec parseMesh(const YamlValue &value, int dim, const fs::path &deck_dir)
{
  const YamlMap m = value.map({"type", "element", "elements", "origin", "size", "brick_size",
                               "count", "stagger", "stagger_axis", "bond", "file"});
  MeshSpec mesh;
  mesh.type = readChoice(m, "type", {MeshType::Block, MeshType::BrickWall, MeshType::Gmsh},
                         MeshType::Block);
  if (mesh.type == MeshType::Gmsh)
  {
    restrictKeys(m, {"type", "file"}, "mesh type 'gmsh'");
    const YamlValue f = m["file"];
    const fs::path file = fs::absolute(deck_dir / f.string()).lexically_normal();
    std::error_code ec;
    if (!fs::is_regular_file(file, ec))
      f.fail("gmsh file '" + f.string() + "' not found (looked for " + file.string() + ")");
    mesh.file = file.string();
    return mesh;
  }
  if (mesh.type == MeshType::Block)
    restrictKeys(m, {"type", "element", "elements", "origin", "size"}, "mesh type 'block'");
  else
    restrictKeys(m,
                 {"type", "element", "elements", "origin", "brick_size", "count", "stagger",
                  "stagger_axis", "bond"},
                 "mesh type 'brick_wall'");

  mesh.element = readChoice(
      m, "element", {ElementType::Line2, ElementType::Quad4, ElementType::Hex8, ElementType::Tet4},
      kDefaultElement[dim]);
  if (dimensionOf(mesh.element) != dim)
    m["element"].fail(std::string("element '") + deckName(mesh.element) + "' is " +
                      std::to_string(dimensionOf(mesh.element)) +
                      "-dimensional but the deck has dimension " + std::to_string(dim) +
                      " (expected " + (dim == 3 ? "hex8 or tet4" : deckName(kDefaultElement[dim])) +
                      ")");
  if (m.has("origin"))
    mesh.origin = m["origin"].realVector(dim);
  if (mesh.type == MeshType::Block)
  {
    mesh.elements = m["elements"].intVector(dim, 1, 1);
    mesh.size = positiveVector(m, "size", dim);
    return mesh;
  }
  if (m.has("elements"))
    mesh.elements = m["elements"].intVector(dim, 1, 1);
  mesh.brick_size = positiveVector(m, "brick_size", dim);
  mesh.count = m["count"].intVector(dim, 1, 1);
  mesh.stagger = readReal(
      m, "stagger", mesh.stagger, [](Real s) { return s >= 0 && s < 1; }, "in [0, 1)");
  if (m.has("stagger_axis"))
  {
    // courses shift along x or y; in 1D there is only x
    const std::string a = m["stagger_axis"].choice(dim == 1 ? std::vector<std::string>{"x"}
                                                            : std::vector<std::string>{"x", "y"});
    mesh.stagger_axis = a == "x" ? 0 : 1;
  }
  mesh.bond = readChoice(m, "bond", {BrickBond::Running, BrickBond::English}, BrickBond::Running);
  if (mesh.bond == BrickBond::English)
    checkEnglishBond(m, mesh, dim);
  return mesh;
}

void parseSets(const YamlMap &root, const std::string &key, int dim, const DeckNames &names,
               std::map<std::string, int> &seen, std::vector<SetSpec> &sets)
{
  if (!root.has(key))
    return;
  for (const YamlValue &item : root[key].list())
  {
    const YamlMap m = item.map({"name", "part", "box"});
    SetSpec set;
    set.name = m["name"].string();
    claimName(seen, m["name"], set.name);
    if (!m.has("part") && !m.has("box"))
      item.fail("give part, box or both (both: the part's " +
                std::string(key == "node_sets" ? "nodes" : "faces") + " in the box)");
    if (m.has("part"))
    {
      set.part = m["part"].string();
      checkPartReference(m["part"], set.part, names);
    }
    if (m.has("box"))
    {
      const YamlMap box = m["box"].map({"min", "max"});
      set.has_box = true;
      set.box_min = box["min"].realVector(dim);
      set.box_max = box["max"].realVector(dim);
      const auto max_items = box["max"].list();
      for (int i = 0; i < dim; ++i)
        if (set.box_max[i] < set.box_min[i])
          max_items[i].fail("box max " + max_items[i].text() + " is below min " +
                            formatReal(set.box_min[i]) + " (expected min <= max)");
    }
    sets.push_back(set);
  }
}

void parseCondition(const YamlValue &item, int dim, const DeckNames &names, bool check_sets,
                    BoundaryConditionSpec &bc)
{
  const YamlMap m = item.openMap();
  bc.type =
      choiceOf(m["type"], {ConditionType::Velocity, ConditionType::Force, ConditionType::Pressure});
  const std::string set_key = bc.type == ConditionType::Pressure ? "face_set" : "node_set";
  if (bc.type == ConditionType::Velocity)
    restrictKeys(m, {"type", "node_set", "component", "value", "function"},
                 "boundary condition type 'velocity'");
  else
    restrictKeys(m, {"type", set_key, "value", "function"},
                 std::string("boundary condition type '") + deckName(bc.type) + "'");

  bc.set = m[set_key].string();
  bc.set_line = m[set_key].line();
  if (check_sets) // with gmsh meshes, sets may also come from the mesh file: the driver checks
    checkReference(m[set_key], bc.set, set_key == "face_set" ? "face set" : "node set",
                   set_key == "face_set" ? names.face_sets : names.node_sets);
  if (bc.type == ConditionType::Velocity)
  {
    const std::string c = m["component"].choice({"x", "y", "z"});
    bc.component = c == "x" ? 0 : c == "y" ? 1 : 2;
    if (bc.component >= dim)
      m["component"].fail("component '" + c + "' does not exist in dimension " +
                          std::to_string(dim) + " (expected " + (dim == 1 ? "x" : "x or y") + ")");
  }
  if (bc.type == ConditionType::Force)
    bc.vector = m["value"].realVector(dim);
  else
    bc.value = requireReal(m, "value", nullptr, "");
  if (m.has("function"))
  {
    bc.function = m["function"].string();
    checkReference(m["function"], bc.function, "function", names.functions);
  }
}

} // namespace

void checkPartReference(const YamlValue &v, const std::string &part, const DeckNames &names)
{
  // a sub-part the meshing makes ('wall.0.1' of a brick wall, 'm.impactor' of a gmsh file) is
  // checked once the meshes exist; here its deck part must exist
  const size_t dot = part.find('.');
  if (part.back() != '*' && dot != std::string::npos && dot > 0 &&
      names.parts.count(part.substr(0, dot)))
    return;
  if (part.back() != '*')
  {
    checkReference(v, part, "part", names.parts);
    return;
  }
  const std::string prefix = part.substr(0, part.size() - 1);
  if (std::none_of(names.parts.begin(), names.parts.end(),
                   [&](const auto &kv) { return kv.first.rfind(prefix, 0) == 0; }))
    v.fail("no part name starts with '" + prefix + "'");
}

namespace
{
/// \brief `translate` and `rotate` of a part (docs/input.md, parts).
PartPlacement parsePlacement(const YamlMap &part, int dim)
{
  PartPlacement pl;
  if (part.has("translate"))
    pl.translate = part["translate"].realVector(dim);
  if (!part.has("rotate"))
    return pl;
  const YamlValue value = part["rotate"];
  if (dim == 1)
    value.fail("a 1D part cannot rotate");
  const YamlMap r = value.map({"angle", "axis", "point"});
  pl.angle = r["angle"].real();
  if (r.has("point"))
    pl.point = r["point"].realVector(dim);
  if (dim == 2)
  {
    if (r.has("axis"))
      r["axis"].fail("2D parts rotate in the x-y plane, about z: no axis to give");
    return pl;
  }
  const YamlValue a = r["axis"];
  const std::array<Real, 3> v = a.realVector(3);
  const Real norm = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (!(norm > 0))
    a.fail("the rotation axis must not be zero");
  for (int k = 0; k < 3; ++k)
    pl.axis[size_t(k)] = v[size_t(k)] / norm;
  return pl;
}
} // namespace

void parseParts(const YamlMap &root, Deck &deck, DeckNames &names, const fs::path &deck_dir)
{
  if (!root.has("parts"))
    root.missing("parts");
  for (const YamlValue &item : root["parts"].list(1))
  {
    const YamlMap m = item.map({"name", "material", "mesh", "initial_velocity", "merge_nodes",
                                "translate", "rotate", "release_time"});
    PartSpec part;
    part.name = m["name"].string();
    claimName(names.parts, m["name"], part.name);
    part.material = m["material"].string();
    checkReference(m["material"], part.material, "material", names.materials);
    part.mesh = parseMesh(m["mesh"], deck.dimension, deck_dir);
    if (m.has("initial_velocity"))
      part.initial_velocity = m["initial_velocity"].realVector(deck.dimension);
    part.merge_nodes = m.boolean("merge_nodes", false);
    part.placement = parsePlacement(m, deck.dimension);
    if (m.has("release_time"))
    {
      const YamlValue r = m["release_time"];
      part.release_time = r.real();
      if (!(part.release_time >= 0 && part.release_time < deck.end_time))
        r.fail("must be in [0, time.end = " + formatReal(deck.end_time) + "), got " + r.text());
    }
    deck.parts.push_back(part);
  }
}

void parseGravity(const YamlMap &root, Deck &deck, const DeckNames &names)
{
  if (!root.has("gravity"))
    return;
  const YamlValue g = root["gravity"];
  if (g.node().IsSequence())
  {
    deck.gravity = g.realVector(deck.dimension);
    return;
  }
  const YamlMap m = g.map({"value", "function"});
  if (!m.has("value"))
    m.missing("value");
  deck.gravity = m["value"].realVector(deck.dimension);
  if (m.has("function"))
  {
    deck.gravity_function = m["function"].string();
    checkReference(m["function"], deck.gravity_function, "function", names.functions);
  }
}

void parseSettling(const YamlMap &root, Deck &deck)
{
  if (!root.has("settling"))
    return;
  const YamlValue item = root["settling"];
  const YamlMap m = item.map({"end", "damping"});
  if (!m.has("end"))
    m.missing("end");
  const YamlValue end = m["end"];
  deck.settling.end = end.real();
  if (!(deck.settling.end > 0 && deck.settling.end < deck.end_time))
    end.fail("must be in (0, time.end = " + formatReal(deck.end_time) + "), got " + end.text());
  if (deck.gravity[0] == 0 && deck.gravity[1] == 0 && deck.gravity[2] == 0)
    item.fail("a settling stage needs gravity: the deck has none (give gravity: [...])");
  // the default brings every underdamped mode down by kSettlingDecay in velocity by `end`
  // (docs/theory.md 2.4)
  deck.settling.damping = readReal(m, "damping", 2 * std::log(kSettlingDecay) / deck.settling.end,
                                   isNonNegative, ">= 0");
}

void parseInitialConditions(const YamlMap &root, Deck &deck, const DeckNames &names,
                            bool check_sets)
{
  if (!root.has("initial_conditions"))
    return;
  const int dim = deck.dimension;
  for (const YamlValue &item : root["initial_conditions"].list())
  {
    const YamlMap m = item.map({"node_set", "velocity", "velocity_gradient", "about"});
    InitialVelocitySpec iv;
    if (!m.has("node_set"))
      m.missing("node_set");
    iv.node_set = m["node_set"].string();
    iv.set_line = m["node_set"].line();
    if (check_sets)
      checkReference(m["node_set"], iv.node_set, "node set", names.node_sets);
    if (!m.has("velocity") && !m.has("velocity_gradient"))
      item.fail("give velocity, velocity_gradient or both");
    if (m.has("velocity"))
      iv.velocity = m["velocity"].realVector(dim);
    if (m.has("velocity_gradient"))
    {
      const std::vector<YamlValue> rows = m["velocity_gradient"].list();
      if (int(rows.size()) != dim)
        m["velocity_gradient"].fail("needs " + std::to_string(dim) + " rows of " +
                                    std::to_string(dim) + " (dv_i/dx_j), got " +
                                    std::to_string(rows.size()) + " rows");
      for (int i = 0; i < dim; ++i)
        iv.gradient[size_t(i)] = rows[size_t(i)].realVector(dim);
    }
    if (m.has("about"))
      iv.about = m["about"].realVector(dim);
    deck.initial_velocities.push_back(iv);
  }
}

void parseSetsAndConditions(const YamlMap &root, Deck &deck, DeckNames &names)
{
  parseSets(root, "node_sets", deck.dimension, names, names.node_sets, deck.node_sets);
  parseSets(root, "face_sets", deck.dimension, names, names.face_sets, deck.face_sets);
  const bool check_sets = std::none_of(deck.parts.begin(), deck.parts.end(), [](const PartSpec &p) {
    return p.mesh.type == MeshType::Gmsh;
  });
  parseInitialConditions(root, deck, names, check_sets);
  if (!root.has("boundary_conditions"))
    return;
  for (const YamlValue &item : root["boundary_conditions"].list())
  {
    BoundaryConditionSpec bc;
    parseCondition(item, deck.dimension, names, check_sets, bc);
    deck.boundary_conditions.push_back(bc);
  }
}

void parseGauges(const YamlMap &root, Deck &deck)
{
  if (!root.has("gauges"))
    return;
  std::map<std::string, int> seen;
  for (const YamlValue &item : root["gauges"].list())
  {
    const YamlMap m =
        item.map({"name", "node", "element", "point", "kind", "radius", "quantities"});
    GaugeSpec g;
    g.name = m["name"].string();
    claimName(seen, m["name"], g.name);
    const std::string where = m.exactlyOne({"node", "element", "point"});
    if (where == "point")
    {
      g.has_point = true;
      g.point = m["point"].realVector(deck.dimension);
      g.kind = readChoice(m, "kind", {GaugeKind::Node, GaugeKind::Element, GaugeKind::Joint},
                          GaugeKind::Node);
    }
    else
    {
      if (m.has("kind"))
        m["kind"].fail("only used with 'point' (a gauge given by '" + where + "' is a " + where +
                       " gauge)");
      g.kind = where == "node" ? GaugeKind::Node : GaugeKind::Element;
      const long id = m[where].integer();
      if (id < 0)
        m[where].fail("must be an id >= 0, got " + m[where].text());
      g.id = static_cast<Index>(id);
    }
    if (g.kind == GaugeKind::Joint)
    {
      if (!root.has("contact"))
        m["kind"].fail("a joint gauge needs a 'contact' section (it reads the common planes)");
      g.radius = readReal(m, "radius", 0, isPositive, "> 0");
    }
    else if (m.has("radius"))
      m["radius"].fail("only used by joint gauges (kind: joint)");
    const auto &mine = gaugeQuantities(g.kind);
    std::vector<std::string> other;
    for (GaugeKind kind : {GaugeKind::Node, GaugeKind::Element, GaugeKind::Joint})
      if (&gaugeQuantities(kind) != &mine)
        other.insert(other.end(), gaugeQuantities(kind).begin(), gaugeQuantities(kind).end());
    for (const YamlValue &q : m["quantities"].list(1))
    {
      const std::string name = q.string();
      if (std::find(other.begin(), other.end(), name) != other.end())
        q.fail("'" + name + "' is not a " + deckName(g.kind) + " quantity (" + deckName(g.kind) +
               " quantities: " + joined(mine) + ")");
      q.choice(mine);
      if (std::find(g.quantities.begin(), g.quantities.end(), name) != g.quantities.end())
        q.fail("quantity '" + name + "' is listed twice");
      g.quantities.push_back(name);
    }
    deck.gauges.push_back(g);
  }
}

} // namespace input_impl
} // namespace scpdyn
