/// \file DeckWriter.cpp
/// \brief The resolved deck: every field of the Deck, defaults included, in the structure of
/// docs/input.md, so that parsing it gives back the same Deck (tests/input checks this).
#include "input/Deck.hpp"
#include "input/YamlReader.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace scpdyn
{
namespace
{

// Reals go out as their shortest exact decimal text (a plain scalar), so that they read back
// bit for bit; strings are always double-quoted, so a title like "2" or "yes" stays a string.
YAML::Emitter &real(YAML::Emitter &out, Real x) { return out << formatReal(x); }
YAML::Emitter &text(YAML::Emitter &out, const std::string &s)
{
  return out << YAML::DoubleQuoted << s;
}

// An empty list reads better as "key: []" than as a block list with no items.
void beginList(YAML::Emitter &out, const char *key, bool empty)
{
  out << YAML::Key << key << YAML::Value;
  if (empty)
    out << YAML::Flow;
  out << YAML::BeginSeq;
}

template <class T>
void vector(YAML::Emitter &out, const char *key, const std::array<T, 3> &v, int n)
{
  if (key) // else an item of a list
    out << YAML::Key << key << YAML::Value;
  out << YAML::Flow << YAML::BeginSeq;
  for (int i = 0; i < n; ++i)
  {
    if constexpr (std::is_integral_v<T>)
      out << v[i];
    else
      real(out, v[i]);
  }
  out << YAML::EndSeq;
}

void writeMesh(YAML::Emitter &out, const MeshSpec &m, int dim)
{
  out << YAML::Key << "mesh" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "type" << YAML::Value << deckName(m.type);
  if (m.type == MeshType::Gmsh)
  {
    out << YAML::Key << "file" << YAML::Value;
    text(out, m.file);
    out << YAML::EndMap;
    return;
  }
  out << YAML::Key << "element" << YAML::Value << deckName(m.element);
  vector(out, "elements", m.elements, dim);
  vector(out, "origin", m.origin, dim);
  if (m.type == MeshType::Block)
    vector(out, "size", m.size, dim);
  else
  {
    vector(out, "brick_size", m.brick_size, dim);
    vector(out, "count", m.count, dim);
    if (m.bond == BrickBond::Running) // the default: decks without the key read back the same
    {
      out << YAML::Key << "stagger" << YAML::Value;
      real(out, m.stagger);
    }
    out << YAML::Key << "stagger_axis" << YAML::Value << (m.stagger_axis == 0 ? "x" : "y");
    if (m.bond != BrickBond::Running)
      out << YAML::Key << "bond" << YAML::Value << deckName(m.bond);
  }
  out << YAML::EndMap;
}

void writeSets(YAML::Emitter &out, const char *key, const std::vector<SetSpec> &sets, int dim)
{
  beginList(out, key, sets.empty());
  for (const auto &s : sets)
  {
    out << YAML::BeginMap << YAML::Key << "name" << YAML::Value;
    text(out, s.name);
    if (!s.part.empty())
    {
      out << YAML::Key << "part" << YAML::Value;
      text(out, s.part);
    }
    if (s.has_box)
    {
      out << YAML::Key << "box" << YAML::Value << YAML::BeginMap;
      vector(out, "min", s.box_min, dim);
      vector(out, "max", s.box_max, dim);
      out << YAML::EndMap;
    }
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
}

void writeMaterial(YAML::Emitter &out, const MaterialSpec &m)
{
  out << YAML::BeginMap << YAML::Key << "name" << YAML::Value;
  text(out, m.name);
  out << YAML::Key << "model" << YAML::Value;
  text(out, m.model);
  out << YAML::Key << "eos" << YAML::Value << YAML::BeginMap << YAML::Key << "type" << YAML::Value;
  text(out, m.eos);
  for (const auto &kv : m.values)
    if (kv.first.rfind("eos.", 0) == 0)
      real(out << YAML::Key << kv.first.substr(4) << YAML::Value, kv.second);
  out << YAML::EndMap;
  const auto prefixed = [](const std::string &key, const char *prefix) {
    return key.rfind(prefix, 0) == 0;
  };
  bool erosion = false;
  for (const auto &kv : m.values)
    erosion = erosion || prefixed(kv.first, "erosion.");
  if (erosion)
  {
    out << YAML::Key << "erosion" << YAML::Value << YAML::BeginMap;
    for (const auto &kv : m.values)
      if (prefixed(kv.first, "erosion."))
        real(out << YAML::Key << kv.first.substr(8) << YAML::Value, kv.second);
    out << YAML::EndMap;
  }
  for (const auto &kv : m.values)
    if (!prefixed(kv.first, "eos.") && !prefixed(kv.first, "erosion."))
      real(out << YAML::Key << kv.first << YAML::Value, kv.second);
  out << YAML::EndMap;
}

void writeCondition(YAML::Emitter &out, const BoundaryConditionSpec &bc, int dim)
{
  out << YAML::BeginMap << YAML::Key << "type" << YAML::Value << deckName(bc.type);
  out << YAML::Key << (bc.type == ConditionType::Pressure ? "face_set" : "node_set") << YAML::Value;
  text(out, bc.set);
  if (bc.type == ConditionType::Velocity)
    out << YAML::Key << "component" << YAML::Value << std::string(1, "xyz"[bc.component]);
  if (bc.type == ConditionType::Force)
    vector(out, "value", bc.vector, dim);
  else
    real(out << YAML::Key << "value" << YAML::Value, bc.value);
  if (!bc.function.empty())
    text(out << YAML::Key << "function" << YAML::Value, bc.function);
  out << YAML::EndMap;
}

void writeGauge(YAML::Emitter &out, const GaugeSpec &g, int dim)
{
  out << YAML::BeginMap << YAML::Key << "name" << YAML::Value;
  text(out, g.name);
  if (g.has_point)
  {
    vector(out, "point", g.point, dim);
    out << YAML::Key << "kind" << YAML::Value << deckName(g.kind);
    if (g.kind == GaugeKind::Joint && g.radius > 0)
      real(out << YAML::Key << "radius" << YAML::Value, g.radius);
  }
  else
    out << YAML::Key << deckName(g.kind) << YAML::Value << g.id;
  out << YAML::Key << "quantities" << YAML::Value << YAML::Flow << g.quantities;
  out << YAML::EndMap;
}

void writeContact(YAML::Emitter &out, const ContactSpec &c)
{
  if (c.surfaces.empty()) // no key: no contact (the section needs at least one surface)
    return;
  out << YAML::Key << "contact" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "search_interval" << YAML::Value;
  if (c.search_interval == 0)
    out << "once";
  else
    out << c.search_interval;
  out << YAML::Key << "constraint_passes" << YAML::Value << c.constraint_passes;
  if (c.search_gap_motion)
    out << YAML::Key << "search_gap" << YAML::Value << "motion";
  else if (c.search_gap > 0) // no key: the largest contact-face size
    real(out << YAML::Key << "search_gap" << YAML::Value, c.search_gap);
  beginList(out, "surfaces", c.surfaces.empty());
  for (const SurfaceSpec &s : c.surfaces)
  {
    out << YAML::BeginMap << YAML::Key << "name" << YAML::Value;
    text(out, s.name);
    if (!s.part.empty())
      text(out << YAML::Key << "part" << YAML::Value, s.part);
    else
      text(out << YAML::Key << "face_set" << YAML::Value, s.face_set);
    out << YAML::Key << "option" << YAML::Value << s.option;
    const std::pair<const char *, Real> values[] = {
        {"a", s.a},       {"E0", s.E0},     {"G", s.G},
        {"C", s.C},       {"phi0", s.phi0}, {"phi1", s.phi1},
        {"usp0", s.usp0}, {"psi0", s.psi0}, {"sigma_cr", s.sigma_cr}};
    for (const auto &kv : values)
      real(out << YAML::Key << kv.first << YAML::Value, kv.second);
    for (const auto &kv : {std::make_pair("Emax", s.Emax), std::make_pair("sigma_t", s.sigma_t)})
    {
      out << YAML::Key << kv.first << YAML::Value;
      if (kv.second < 0)
        out << "auto";
      else
        real(out, kv.second);
    }
    out << YAML::Key << "C_safe" << YAML::Value;
    if (std::isinf(s.C_safe))
      out << "off";
    else
      real(out, s.C_safe);
    out << YAML::Key << "dt_form" << YAML::Value << s.dt_form;
    out << YAML::Key << "dilation_update" << YAML::Value << s.dilation_update;
    out << YAML::Key << "distribution" << YAML::Value << s.distribution;
    out << YAML::Key << "velocity" << YAML::Value << s.velocity;
    out << YAML::Key << "traction_history" << YAML::Value << s.traction_history;
    out << YAML::Key << "implicit_shear" << YAML::Value << s.implicit_shear;
    out << YAML::Key << "brittle_tension" << YAML::Value << s.brittle_tension;
    if (s.option == "slide_line" || s.option == "sleepy")
    {
      out << YAML::Key << "mu_static" << YAML::Value;
      real(out, s.mu_static);
      out << YAML::Key << "mu_kinetic" << YAML::Value;
      real(out, s.mu_kinetic < 0 ? s.mu_static : s.mu_kinetic);
      out << YAML::Key << "mu_decay" << YAML::Value;
      real(out, s.mu_decay);
    }
    if (s.option == "sleepy")
    {
      out << YAML::Key << "failure_measure" << YAML::Value << s.failure_measure;
      out << YAML::Key << "failure_threshold" << YAML::Value;
      real(out, s.failure_threshold);
      out << YAML::Key << "failure_sides" << YAML::Value << s.failure_sides;
    }
    out << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap;
}

} // namespace

std::string resolvedDeckText(const Deck &deck)
{
  const int dim = deck.dimension;
  YAML::Emitter out;
  out << YAML::Comment("resolved deck of " + deck.path + ": every default filled in");
  out << YAML::BeginMap;
  text(out << YAML::Key << "title" << YAML::Value, deck.title);
  out << YAML::Key << "dimension" << YAML::Value << dim;
  if (dim == 2)
    out << YAML::Key << "geometry" << YAML::Value
        << (deck.geometry == Geometry2D::Axisymmetric ? "axisymmetric" : "plane_strain");

  out << YAML::Key << "time" << YAML::Value << YAML::BeginMap;
  real(out << YAML::Key << "end" << YAML::Value, deck.end_time);
  real(out << YAML::Key << "courant" << YAML::Value, deck.courant);
  real(out << YAML::Key << "dt_max" << YAML::Value, deck.dt_max);
  if (deck.max_cycles > 0) // no key: no cycle limit
    out << YAML::Key << "max_cycles" << YAML::Value << deck.max_cycles;
  real(out << YAML::Key << "max_estimated_cycles" << YAML::Value, deck.max_estimated_cycles);
  out << YAML::EndMap;

  out << YAML::Key << "numerics" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "hourglass" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "type" << YAML::Value << deckName(deck.hourglass_type);
  real(out << YAML::Key << "coefficient" << YAML::Value, deck.hourglass_coefficient);
  out << YAML::EndMap << YAML::Key << "bulk_viscosity" << YAML::Value << YAML::BeginMap;
  real(out << YAML::Key << "linear" << YAML::Value, deck.bulk_viscosity_linear);
  real(out << YAML::Key << "quadratic" << YAML::Value, deck.bulk_viscosity_quadratic);
  out << YAML::EndMap << YAML::Key << "scatter" << YAML::Value << deckName(deck.scatter);
  out << YAML::Key << "node_update" << YAML::Value << deckName(deck.node_update) << YAML::EndMap;

  if (deck.gravity_function.empty())
    vector(out, "gravity", deck.gravity, dim);
  else
  {
    out << YAML::Key << "gravity" << YAML::Value << YAML::BeginMap;
    vector(out, "value", deck.gravity, dim);
    text(out << YAML::Key << "function" << YAML::Value, deck.gravity_function);
    out << YAML::EndMap;
  }
  if (deck.settling.active()) // no key: no settling stage
  {
    out << YAML::Key << "settling" << YAML::Value << YAML::BeginMap;
    real(out << YAML::Key << "end" << YAML::Value, deck.settling.end);
    real(out << YAML::Key << "damping" << YAML::Value, deck.settling.damping);
    out << YAML::EndMap;
  }
  out << YAML::Key << "output" << YAML::Value << YAML::BeginMap;
  text(out << YAML::Key << "directory" << YAML::Value, deck.output_dir);
  real(out << YAML::Key << "field_interval" << YAML::Value, deck.field_interval);
  real(out << YAML::Key << "history_interval" << YAML::Value, deck.history_interval);
  real(out << YAML::Key << "progress_interval" << YAML::Value, deck.progress_interval);
  real(out << YAML::Key << "max_output_bytes" << YAML::Value, deck.max_output_bytes);
  real(out << YAML::Key << "restart_interval" << YAML::Value, deck.restart_interval);
  out << YAML::Key << "restart_keep" << YAML::Value << deck.restart_keep;
  out << YAML::EndMap;

  beginList(out, "functions", deck.functions.empty());
  for (const auto &f : deck.functions)
  {
    out << YAML::BeginMap << YAML::Key << "name" << YAML::Value;
    text(out, f.name);
    out << YAML::Key << "points" << YAML::Value << YAML::BeginSeq;
    for (std::size_t i = 0; i < f.t.size(); ++i)
    {
      out << YAML::Flow << YAML::BeginSeq;
      real(real(out, f.t[i]), f.value[i]) << YAML::EndSeq;
    }
    out << YAML::EndSeq << YAML::EndMap;
  }
  out << YAML::EndSeq;
  beginList(out, "materials", deck.materials.empty());
  for (const auto &m : deck.materials)
    writeMaterial(out, m);
  out << YAML::EndSeq;
  beginList(out, "parts", deck.parts.empty());
  for (const auto &p : deck.parts)
  {
    out << YAML::BeginMap << YAML::Key << "name" << YAML::Value;
    text(out, p.name);
    text(out << YAML::Key << "material" << YAML::Value, p.material);
    writeMesh(out, p.mesh, dim);
    vector(out, "initial_velocity", p.initial_velocity, dim);
    out << YAML::Key << "merge_nodes" << YAML::Value << p.merge_nodes;
    if (p.release_time > 0) // no key: free from the start
      real(out << YAML::Key << "release_time" << YAML::Value, p.release_time);
    const auto &t = p.placement.translate;
    if (t[0] != 0 || t[1] != 0 || t[2] != 0)
      vector(out, "translate", t, dim);
    if (p.placement.angle != 0 && dim > 1)
    {
      out << YAML::Key << "rotate" << YAML::Value << YAML::BeginMap << YAML::Key << "angle"
          << YAML::Value;
      real(out, p.placement.angle);
      if (dim == 3)
        vector(out, "axis", p.placement.axis, 3);
      vector(out, "point", p.placement.point, dim);
      out << YAML::EndMap;
    }
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
  writeSets(out, "node_sets", deck.node_sets, dim);
  writeSets(out, "face_sets", deck.face_sets, dim);
  beginList(out, "boundary_conditions", deck.boundary_conditions.empty());
  for (const auto &bc : deck.boundary_conditions)
    writeCondition(out, bc, dim);
  out << YAML::EndSeq;
  beginList(out, "initial_conditions", deck.initial_velocities.empty());
  for (const auto &iv : deck.initial_velocities)
  {
    out << YAML::BeginMap << YAML::Key << "node_set" << YAML::Value;
    text(out, iv.node_set);
    vector(out, "velocity", iv.velocity, dim);
    out << YAML::Key << "velocity_gradient" << YAML::Value << YAML::BeginSeq;
    for (int i = 0; i < dim; ++i)
      vector(out, nullptr, iv.gradient[size_t(i)], dim);
    out << YAML::EndSeq;
    vector(out, "about", iv.about, dim);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
  beginList(out, "gauges", deck.gauges.empty());
  for (const auto &g : deck.gauges)
    writeGauge(out, g, dim);
  out << YAML::EndSeq;
  writeContact(out, deck.contact);
  out << YAML::EndMap;
  if (!out.good())
    throw std::runtime_error("writeResolvedDeck: YAML emitter error: " + out.GetLastError());
  return std::string(out.c_str()) + "\n";
}

void writeResolvedDeck(const Deck &deck, const std::string &file)
{
  const std::string text = resolvedDeckText(deck);
  const std::filesystem::path target(file);
  if (target.has_parent_path())
    std::filesystem::create_directories(target.parent_path());
  std::ofstream os(file);
  os << text;
  if (!os)
    throw std::runtime_error("writeResolvedDeck: cannot write " + file);
}

} // namespace scpdyn
