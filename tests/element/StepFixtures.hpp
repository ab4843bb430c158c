#pragma once
// Shared by the tests of step 6 run on a solver's state: a 3D deck with row, general and tail
// packs and two element groups, and copies of the state a step changes.
#include "driver/Solver.hpp"
#include "element/ElementForces.hpp"

#include <type_traits>

namespace scpdyn::test
{

// Two hex parts whose element counts are not multiples of a pack (tail packs; part a's rows of
// 9 hexes hold row packs, part b's rows of 4 do not) and a tet part (a second element group),
// different materials, moving against each other, gravity, and a velocity constraint.
inline const char *kThreePartsDeck = R"(title: three parts
dimension: 3
time: {end: 1.0, courant: 0.5}
numerics: {scatter: gather}
gravity: [0.0, -9.81, 3.0]
materials:
  - {name: steel, model: elastic, density: 7850, youngs_modulus: 200.0e9, poisson_ratio: 0.3}
  - {name: soft, model: elastic_plastic, density: 2700, youngs_modulus: 70.0e9, poisson_ratio: 0.33,
     yield_stress: 1.0e6, hardening_modulus: 1.0e8}
parts:
  - name: a
    material: steel
    mesh: {type: block, element: hex8, elements: [9, 5, 3], size: [0.9, 0.5, 0.3]}
    initial_velocity: [-50.0, 20.0, 0.0]
  - name: b
    material: soft
    mesh: {type: block, element: hex8, elements: [4, 3, 5], size: [0.4, 0.3, 0.5], origin: [1, 0, 0]}
    initial_velocity: [30.0, 0.0, -40.0]
  - name: c
    material: steel
    mesh: {type: block, element: tet4, elements: [3, 2, 2], size: [0.3, 0.2, 0.2], origin: [0, 1, 0]}
    initial_velocity: [0.0, -60.0, 10.0]
node_sets:
  - {name: wall, box: {min: [0, 0, 0], max: [0, 0.5, 0.3]}}
boundary_conditions:
  - {type: velocity, node_set: wall, component: x, value: 0.0}
)";

/// A new View with v's extents and values.
template <class V>
V copyOf(const V &v)
{
  V copy(v.label() + "_copy", v.extent(0));
  Kokkos::deep_copy(copy, v);
  return copy;
}

/// el with copies of every View that step 6 writes.
inline ElementFields copyElementState(const ElementFields &el)
{
  ElementFields copy = el;
  copy.stress = copyOf(el.stress);
  copy.energy = copyOf(el.energy);
  copy.plastic_strain = copyOf(el.plastic_strain);
  copy.volume = copyOf(el.volume);
  copy.q = copyOf(el.q);
  copy.sound_speed = copyOf(el.sound_speed);
  copy.hourglass_energy = copyOf(el.hourglass_energy);
  copy.history = copyOf(el.history);
  copy.hourglass = copyOf(el.hourglass);
  return copy;
}

/// nodes with copies of every View that steps 6 and 12 write.
inline NodeFields copyNodeState(const NodeFields &nodes)
{
  NodeFields copy = nodes;
  copy.x = copyOf(nodes.x);
  copy.v = copyOf(nodes.v);
  copy.f_int = copyOf(nodes.f_int);
  copy.f_ext = copyOf(nodes.f_ext);
  copy.external_impulse = copyOf(nodes.external_impulse);
  return copy;
}

/// The solver's element controls for its next step, as the corner gather's.
inline ElementControls gatherControls(const Solver &s)
{
  ElementControls ctl = s.elementControls();
  ctl.gather = true;
  return ctl;
}

} // namespace scpdyn::test
