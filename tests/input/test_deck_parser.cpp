// Deck parsing: a full deck fills every Deck field as written, a minimal deck gets the documented
// defaults, the resolved deck parses back to the same Deck, and the error messages carry the
// deck path, key path, line and a suggestion for typos. Values are compared exactly: the parser
// and the resolved writer both go through exact decimal text, so nothing may be lost.
#include "TestUtil.hpp"
#include "input/Deck.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace
{
namespace fs = std::filesystem;
using namespace scpdyn;

const std::string kWork = std::string(SCPDYN_TEST_WORKDIR) + "/input";

// A 3D deck that sets every key of the schema to a non-default value.
const char *kFullDeck = R"(title: full test deck
dimension: 3
time: {end: 1.0e-3, courant: 0.8, dt_max: 1.0e-6, max_cycles: 5000, max_estimated_cycles: 2.0e7}
numerics:
  hourglass: {type: viscous, coefficient: 0.1}
  bulk_viscosity: {linear: 0.1, quadratic: 1.2}
  scatter: gather
  node_update: separate
gravity: {value: [0, 0, -9.81], function: ramp}
output: {directory: results/full, field_interval: 1.0e-4, history_interval: 1.0e-6,
         progress_interval: 5, max_output_bytes: 1.0e8}
functions:
  - name: ramp
    points: [[0, 0], [1.0e-4, 1], [1, 1]]
materials:
  - name: steel
    model: elastic_plastic
    density: 7850
    youngs_modulus: 2.0e11
    poisson_ratio: 0.3
    yield_stress: 3.5e8
    hardening_modulus: 1.0e9
  - name: granite
    eos: {type: mie_gruneisen, c0: 3700, s: 1.3, gamma0: 1.0}
    density: 2650
    shear_modulus: 2.2e10
parts:
  - name: plate
    material: steel
    mesh: {type: block, element: hex8, elements: [10, 10, 2], origin: [0, 0, -0.02],
           size: [1, 1, 0.02]}
  - name: wall
    material: granite
    mesh: {type: brick_wall, element: tet4, elements: [2, 1, 1], origin: [0.1, 0, 0],
           brick_size: [0.2, 0.1, 0.1], count: [4, 1, 3], stagger: 0.25,
           stagger_axis: y}
    merge_nodes: yes
  - name: projectile
    material: steel
    mesh: {type: gmsh, file: meshes/../meshes/ball.msh}
    initial_velocity: [0, 0, -250]
node_sets:
  - {name: base, box: {min: [-1, -1, -0.02], max: [2, 2, -0.02]}}
  - {name: wall_nodes, part: wall}
  - {name: wall_low, part: wall, box: {min: [-1, -1, -1], max: [2, 2, 0.1]}}
face_sets:
  - {name: top, part: "pl*"}
initial_conditions:
  - {node_set: wall_nodes, velocity: [1, 2, 3]}
  - {node_set: wall_low, velocity_gradient: [[0, -5, 0], [5, 0, 0], [0, 0, 0]], about: [0.5, 0, 0]}
boundary_conditions:
  - {type: velocity, node_set: base, component: z, value: 0}
  - {type: force, node_set: wall_nodes, value: [1, 0, -2], function: ramp}
  - {type: pressure, face_set: top, value: 1.0e6, function: ramp}
  - {type: velocity, node_set: from_gmsh, component: x, value: 0.5}
gauges:
  - {name: centre, node: 12, quantities: [vz, dz]}
  - {name: e5, element: 5, quantities: [sxx, pressure]}
  - {name: probe, point: [0.5, 0.5, -0.01], kind: element, quantities: [plastic_strain]}
  - {name: probe_n, point: [0.5, 0.5, 0], quantities: [z]}
)";

// The smallest valid 2D deck: everything else takes its default.
const char *kMinimalDeck = R"(dimension: 2
time: {end: 2.5e-4}
materials:
  - {name: rock, density: 2600, youngs_modulus: 5.0e10, poisson_ratio: 0.25}
parts:
  - name: block
    material: rock
    mesh: {elements: [4, 2], size: [1, 0.5]}
node_sets: [{name: bottom, part: block}]
face_sets: [{name: top, box: {min: [0, 0.5], max: [1, 0.5]}}]
boundary_conditions:
  - {type: velocity, node_set: bottom, component: y, value: -1}
  - {type: pressure, face_set: top, value: 1.0e5}
)";

Deck parseFull()
{
  fs::create_directories(kWork + "/meshes");
  std::ofstream(kWork + "/meshes/ball.msh") << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
  return parseDeckString(kFullDeck, kWork + "/full.yaml");
}

std::string errorOf(const std::string &yaml, const std::string &path = "deck.yaml")
{
  try
  {
    parseDeckString(yaml, path);
  }
  catch (const InputError &e)
  {
    return e.what();
  }
  return "(no error)";
}

using test::readText;

void expectSameDeck(const Deck &a, const Deck &b)
{
  EXPECT_EQ(a.title, b.title);
  EXPECT_EQ(a.dimension, b.dimension);
  EXPECT_EQ(a.geometry, b.geometry);
  EXPECT_EQ(a.end_time, b.end_time);
  EXPECT_EQ(a.courant, b.courant);
  EXPECT_EQ(a.dt_max, b.dt_max);
  EXPECT_EQ(a.max_cycles, b.max_cycles);
  EXPECT_EQ(a.max_estimated_cycles, b.max_estimated_cycles);
  EXPECT_EQ(a.hourglass_coefficient, b.hourglass_coefficient);
  EXPECT_EQ(a.hourglass_type, b.hourglass_type);
  EXPECT_EQ(a.bulk_viscosity_linear, b.bulk_viscosity_linear);
  EXPECT_EQ(a.bulk_viscosity_quadratic, b.bulk_viscosity_quadratic);
  EXPECT_EQ(a.scatter, b.scatter);
  EXPECT_EQ(a.node_update, b.node_update);
  EXPECT_EQ(a.gravity, b.gravity);
  EXPECT_EQ(a.output_dir, b.output_dir);
  EXPECT_EQ(a.field_interval, b.field_interval);
  EXPECT_EQ(a.history_interval, b.history_interval);
  EXPECT_EQ(a.progress_interval, b.progress_interval);
  EXPECT_EQ(a.max_output_bytes, b.max_output_bytes);
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (std::size_t i = 0; i < a.materials.size(); ++i)
  {
    EXPECT_EQ(a.materials[i].name, b.materials[i].name);
    EXPECT_EQ(a.materials[i].model, b.materials[i].model);
    EXPECT_EQ(a.materials[i].eos, b.materials[i].eos);
    EXPECT_EQ(a.materials[i].values, b.materials[i].values);
    EXPECT_EQ(a.materials[i].index, b.materials[i].index);
  }
  ASSERT_EQ(a.parts.size(), b.parts.size());
  for (std::size_t i = 0; i < a.parts.size(); ++i)
  {
    const PartSpec &p = a.parts[i], &q = b.parts[i];
    EXPECT_EQ(p.name, q.name);
    EXPECT_EQ(p.material, q.material);
    EXPECT_EQ(p.initial_velocity, q.initial_velocity);
    EXPECT_EQ(p.merge_nodes, q.merge_nodes);
    EXPECT_EQ(p.mesh.type, q.mesh.type);
    EXPECT_EQ(p.mesh.element, q.mesh.element);
    EXPECT_EQ(p.mesh.elements, q.mesh.elements);
    EXPECT_EQ(p.mesh.origin, q.mesh.origin);
    EXPECT_EQ(p.mesh.size, q.mesh.size);
    EXPECT_EQ(p.mesh.brick_size, q.mesh.brick_size);
    EXPECT_EQ(p.mesh.count, q.mesh.count);
    EXPECT_EQ(p.mesh.stagger, q.mesh.stagger);
    EXPECT_EQ(p.mesh.stagger_axis, q.mesh.stagger_axis);
    EXPECT_EQ(p.mesh.file, q.mesh.file);
  }
  for (auto sets :
       {std::make_pair(&a.node_sets, &b.node_sets), std::make_pair(&a.face_sets, &b.face_sets)})
  {
    ASSERT_EQ(sets.first->size(), sets.second->size());
    for (std::size_t i = 0; i < sets.first->size(); ++i)
    {
      const SetSpec &s = (*sets.first)[i], &t = (*sets.second)[i];
      EXPECT_EQ(s.name, t.name);
      EXPECT_EQ(s.part, t.part);
      EXPECT_EQ(s.has_box, t.has_box);
      EXPECT_EQ(s.box_min, t.box_min);
      EXPECT_EQ(s.box_max, t.box_max);
    }
  }
  ASSERT_EQ(a.functions.size(), b.functions.size());
  for (std::size_t i = 0; i < a.functions.size(); ++i)
  {
    EXPECT_EQ(a.functions[i].name, b.functions[i].name);
    EXPECT_EQ(a.functions[i].t, b.functions[i].t);
    EXPECT_EQ(a.functions[i].value, b.functions[i].value);
  }
  EXPECT_EQ(a.gravity_function, b.gravity_function);
  ASSERT_EQ(a.initial_velocities.size(), b.initial_velocities.size());
  for (std::size_t i = 0; i < a.initial_velocities.size(); ++i)
  {
    EXPECT_EQ(a.initial_velocities[i].node_set, b.initial_velocities[i].node_set);
    EXPECT_EQ(a.initial_velocities[i].velocity, b.initial_velocities[i].velocity);
    EXPECT_EQ(a.initial_velocities[i].gradient, b.initial_velocities[i].gradient);
    EXPECT_EQ(a.initial_velocities[i].about, b.initial_velocities[i].about);
  }
  ASSERT_EQ(a.boundary_conditions.size(), b.boundary_conditions.size());
  for (std::size_t i = 0; i < a.boundary_conditions.size(); ++i)
  {
    const auto &c = a.boundary_conditions[i], &d = b.boundary_conditions[i];
    EXPECT_EQ(c.type, d.type);
    EXPECT_EQ(c.set, d.set);
    EXPECT_EQ(c.component, d.component);
    EXPECT_EQ(c.value, d.value);
    EXPECT_EQ(c.vector, d.vector);
    EXPECT_EQ(c.function, d.function);
  }
  ASSERT_EQ(a.gauges.size(), b.gauges.size());
  for (std::size_t i = 0; i < a.gauges.size(); ++i)
  {
    const auto &g = a.gauges[i], &h = b.gauges[i];
    EXPECT_EQ(g.name, h.name);
    EXPECT_EQ(g.kind, h.kind);
    EXPECT_EQ(g.id, h.id);
    EXPECT_EQ(g.has_point, h.has_point);
    EXPECT_EQ(g.point, h.point);
    EXPECT_EQ(g.quantities, h.quantities);
  }
}

TEST(DeckParser, FullDeckFillsEveryField)
{
  const Deck d = parseFull();
  EXPECT_EQ(d.title, "full test deck");
  EXPECT_EQ(d.dimension, 3);
  EXPECT_EQ(d.end_time, 1.0e-3);
  EXPECT_EQ(d.courant, 0.8);
  EXPECT_EQ(d.dt_max, 1.0e-6);
  EXPECT_EQ(d.max_cycles, 5000);
  EXPECT_EQ(d.max_estimated_cycles, 2.0e7);
  EXPECT_EQ(d.hourglass_type, HourglassForm::Viscous);
  EXPECT_EQ(d.hourglass_coefficient, 0.1);
  EXPECT_EQ(d.bulk_viscosity_linear, 0.1);
  EXPECT_EQ(d.bulk_viscosity_quadratic, 1.2);
  EXPECT_EQ(d.scatter, ScatterMode::Gather);
  EXPECT_EQ(d.node_update, NodeUpdateMode::Separate);
  EXPECT_EQ(d.gravity, (std::array<Real, 3>{{0, 0, -9.81}}));
  EXPECT_EQ(d.output_dir, "results/full");
  EXPECT_EQ(d.field_interval, 1.0e-4);
  EXPECT_EQ(d.history_interval, 1.0e-6);
  EXPECT_EQ(d.max_output_bytes, 1.0e8);
  EXPECT_EQ(d.progress_interval, 5.0);

  ASSERT_EQ(d.functions.size(), 1u);
  EXPECT_EQ(d.functions[0].t, (std::vector<Real>{0, 1.0e-4, 1}));
  EXPECT_EQ(d.functions[0].value, (std::vector<Real>{0, 1, 1}));

  ASSERT_EQ(d.materials.size(), 2u);
  const MaterialSpec &steel = d.materials[0], &granite = d.materials[1];
  EXPECT_EQ(steel.model, "elastic_plastic");
  EXPECT_EQ(steel.eos, "linear");
  EXPECT_EQ(steel.values.size(), 5u);
  EXPECT_EQ(steel.values.at("yield_stress"), 3.5e8);
  EXPECT_EQ(steel.lines.at("density"), 18);
  EXPECT_EQ(steel.line, 16);
  EXPECT_EQ(granite.index, 1);
  EXPECT_EQ(granite.model, "elastic");
  EXPECT_EQ(granite.eos, "mie_gruneisen");
  EXPECT_EQ(granite.values.at("eos.c0"), 3700.0);
  EXPECT_EQ(granite.values.at("shear_modulus"), 2.2e10);
  EXPECT_EQ(granite.lines.at("eos.gamma0"), 24);

  ASSERT_EQ(d.parts.size(), 3u);
  EXPECT_EQ(d.parts[0].mesh.element, ElementType::Hex8);
  EXPECT_EQ(d.parts[0].mesh.elements, (std::array<int, 3>{{10, 10, 2}}));
  EXPECT_EQ(d.parts[0].mesh.origin, (std::array<Real, 3>{{0, 0, -0.02}}));
  EXPECT_EQ(d.parts[0].mesh.size, (std::array<Real, 3>{{1, 1, 0.02}}));
  EXPECT_FALSE(d.parts[0].merge_nodes);
  const MeshSpec &wall = d.parts[1].mesh;
  EXPECT_EQ(wall.type, MeshType::BrickWall);
  EXPECT_EQ(wall.element, ElementType::Tet4);
  EXPECT_EQ(wall.brick_size, (std::array<Real, 3>{{0.2, 0.1, 0.1}}));
  EXPECT_EQ(wall.count, (std::array<int, 3>{{4, 1, 3}}));
  EXPECT_EQ(wall.stagger, 0.25);
  EXPECT_EQ(wall.stagger_axis, 1);
  EXPECT_TRUE(d.parts[1].merge_nodes);
  // gmsh paths are made absolute and normalised against the deck's directory
  EXPECT_EQ(d.parts[2].mesh.file, fs::absolute(kWork + "/meshes/ball.msh").string());
  EXPECT_EQ(d.parts[2].initial_velocity, (std::array<Real, 3>{{0, 0, -250}}));

  ASSERT_EQ(d.node_sets.size(), 3u);
  EXPECT_TRUE(d.node_sets[0].has_box);
  EXPECT_EQ(d.node_sets[0].box_max, (std::array<Real, 3>{{2, 2, -0.02}}));
  EXPECT_EQ(d.node_sets[1].part, "wall");
  EXPECT_EQ(d.node_sets[2].part, "wall");
  EXPECT_TRUE(d.node_sets[2].has_box);
  EXPECT_EQ(d.gravity_function, "ramp");
  ASSERT_EQ(d.initial_velocities.size(), 2u);
  EXPECT_EQ(d.initial_velocities[1].gradient[1][0], 5.0);
  EXPECT_EQ(d.initial_velocities[1].about[0], 0.5);
  EXPECT_EQ(d.face_sets[0].part, "pl*");

  ASSERT_EQ(d.boundary_conditions.size(), 4u);
  EXPECT_EQ(d.boundary_conditions[0].component, 2);
  EXPECT_EQ(d.boundary_conditions[1].vector, (std::array<Real, 3>{{1, 0, -2}}));
  EXPECT_EQ(d.boundary_conditions[1].function, "ramp");
  EXPECT_EQ(d.boundary_conditions[2].set, "top");
  EXPECT_EQ(d.boundary_conditions[2].value, 1.0e6);
  // a set name not in node_sets is accepted when a gmsh mesh may define it
  EXPECT_EQ(d.boundary_conditions[3].set, "from_gmsh");
  EXPECT_EQ(d.boundary_conditions[3].component, 0);

  ASSERT_EQ(d.gauges.size(), 4u);
  EXPECT_EQ(d.gauges[0].kind, GaugeKind::Node);
  EXPECT_EQ(d.gauges[0].id, 12);
  EXPECT_EQ(d.gauges[1].kind, GaugeKind::Element);
  EXPECT_EQ(d.gauges[1].quantities, (std::vector<std::string>{"sxx", "pressure"}));
  EXPECT_TRUE(d.gauges[2].has_point);
  EXPECT_EQ(d.gauges[2].kind, GaugeKind::Element);
  EXPECT_EQ(d.gauges[2].id, -1);
  EXPECT_EQ(d.gauges[3].kind, GaugeKind::Node);
}

TEST(DeckParser, MinimalDeckGetsDocumentedDefaults)
{
  const Deck d = parseDeckString(kMinimalDeck, "decks/impact_2d.yaml");
  EXPECT_EQ(d.title, "impact_2d");
  EXPECT_EQ(d.path, "decks/impact_2d.yaml");
  EXPECT_EQ(d.geometry, Geometry2D::PlaneStrain);
  EXPECT_EQ(d.courant, 0.5);
  EXPECT_EQ(d.dt_max, 1e30);
  EXPECT_EQ(d.max_cycles, -1);
  EXPECT_EQ(d.max_estimated_cycles, 1e9);
  EXPECT_EQ(d.max_output_bytes, 50e9);
  EXPECT_EQ(d.hourglass_type, HourglassForm::Stiffness);
  EXPECT_EQ(d.hourglass_coefficient, 0.05);
  EXPECT_EQ(d.bulk_viscosity_linear, 0.06);
  EXPECT_EQ(d.bulk_viscosity_quadratic, 1.5);
  EXPECT_EQ(d.scatter, ScatterMode::Gather);
  EXPECT_EQ(d.node_update, NodeUpdateMode::Fused);
  EXPECT_EQ(d.gravity, (std::array<Real, 3>{{0, 0, 0}}));
  EXPECT_EQ(d.output_dir, "out/impact_2d");
  EXPECT_EQ(d.field_interval, 0.0);
  EXPECT_EQ(d.history_interval, 0.0);
  EXPECT_EQ(d.progress_interval, 2.0);
  EXPECT_EQ(d.materials[0].model, "elastic");
  EXPECT_EQ(d.materials[0].eos, "linear");
  const MeshSpec &m = d.parts[0].mesh;
  EXPECT_EQ(m.type, MeshType::Block);
  EXPECT_EQ(m.element, ElementType::Quad4);
  EXPECT_EQ(m.elements, (std::array<int, 3>{{4, 2, 1}}));
  EXPECT_EQ(m.size, (std::array<Real, 3>{{1, 0.5, 0}}));
  EXPECT_EQ(m.origin, (std::array<Real, 3>{{0, 0, 0}}));
  EXPECT_EQ(d.parts[0].initial_velocity, (std::array<Real, 3>{{0, 0, 0}}));
  EXPECT_EQ(d.boundary_conditions[0].component, 1);
  EXPECT_EQ(d.boundary_conditions[0].function, "");
}

TEST(DeckParser, ResolvedDeckRoundTrips)
{
  for (const bool full : {true, false})
  {
    SCOPED_TRACE(full ? "full deck" : "minimal deck");
    const Deck a = full ? parseFull() : parseDeckString(kMinimalDeck, kWork + "/minimal.yaml");
    const std::string first = kWork + (full ? "/resolved/full.yaml" : "/resolved/minimal.yaml");
    writeResolvedDeck(a, first);
    const Deck b = parseDeck(first);
    expectSameDeck(a, b);
    // resolving the resolved deck changes nothing but the source named in the header comment
    writeResolvedDeck(b, first + ".again");
    const std::string t1 = readText(first), t2 = readText(first + ".again");
    EXPECT_EQ(t1.substr(t1.find('\n')), t2.substr(t2.find('\n')));
  }
}

TEST(DeckParser, ResolvedDeckKeepsAwkwardValuesExact)
{
  Deck a = parseDeckString(kMinimalDeck, kWork + "/awkward.yaml");
  a.title = "yes";        // would read back as a boolean-looking plain scalar if not quoted
  a.end_time = 0.1 + 0.2; // needs 17 significant digits
  a.gravity = {{-1e-300, 3.0e8, 0}};
  a.parts[0].mesh.origin = {{-0.0, 1.0 / 3.0, 0}};
  a.functions.push_back({"f", {0, 1e-9}, {-2.5, 7}});
  a.boundary_conditions[0].function = "f";
  writeResolvedDeck(a, kWork + "/resolved/awkward.yaml");
  expectSameDeck(a, parseDeck(kWork + "/resolved/awkward.yaml"));
}

TEST(DeckParser, TypoSuggestsClosestKey)
{
  const std::string msg = errorOf("dimension: 2\ntime: {end: 1, courrant: 0.5}\n");
  EXPECT_EQ(msg, "deck.yaml: time.courrant (line 2): unknown key 'courrant'; did you mean "
                 "'courant'?");
  // far from every key: list them instead of guessing
  EXPECT_NE(errorOf("dimension: 2\ntime: {end: 1, speed: 0.5}\n")
                .find("(expected one of: end, courant, dt_max, max_cycles, max_estimated_cycles)"),
            std::string::npos);
}

TEST(DeckParser, SetNamesCheckedOnlyWithoutGmsh)
{
  std::string deck = kMinimalDeck;
  deck.replace(deck.find("node_set: bottom"), 16, "node_set: bottm");
  EXPECT_NE(errorOf(deck).find("boundary_conditions[0].node_set (line 12): unknown node set "
                               "'bottm'; did you mean 'bottom'?"),
            std::string::npos);
}

TEST(DeckParser, MissingAndEmptyFiles)
{
  try
  {
    parseDeck(kWork + "/no_such_deck.yaml");
    FAIL() << "missing deck accepted";
  }
  catch (const InputError &e)
  {
    EXPECT_NE(std::string(e.what()).find("no_such_deck.yaml: <document>: cannot read the deck"),
              std::string::npos);
  }
  EXPECT_NE(errorOf("   \n# only a comment\n")
                .find("deck.yaml: <document> (line 1): the deck "
                      "is empty"),
            std::string::npos);
  EXPECT_NE(errorOf("[1, 2]").find("<document> (line 1): expected a mapping"), std::string::npos);
}

TEST(DeckParser, DocumentationExampleParses)
{
  // the complete example at the top of docs/input.md must stay a valid deck
  const std::string doc = readText(std::string(SCPDYN_SOURCE_DIR) + "/docs/input.md");
  const auto begin = doc.find("```yaml\n");
  ASSERT_NE(begin, std::string::npos);
  const auto end = doc.find("```", begin + 8);
  const Deck d =
      parseDeckString(doc.substr(begin + 8, end - begin - 8), kWork + "/docs_example.yaml");
  EXPECT_EQ(d.title, "block_on_wall");
  ASSERT_EQ(d.parts.size(), 2u);
  EXPECT_EQ(d.parts[0].mesh.type, MeshType::BrickWall);
  EXPECT_EQ(d.materials[1].eos, "mie_gruneisen");
  EXPECT_EQ(d.boundary_conditions.size(), 3u);
  EXPECT_EQ(d.gauges.size(), 4u);
}

} // namespace
