#pragma once
/// \file InternalForce.hpp
/// \brief Step 6 of the cycle: element solvers. For every element: half-step kinematics,
/// velocity gradient, objective stress rotation, material update, internal + hourglass
/// forces scattered to the nodes, and the element's stable time step.
#include "core/Fields.hpp"
#include "element/Hourglass.hpp"

namespace scpdyn
{

/// \brief Per-cycle controls of the element kernels.
struct ElementControls
{
  Real dt = 0;        ///< this cycle's time step [s]
  Real half_time = 0; ///< t^n + dt/2 [s]
  Geometry2D geometry = Geometry2D::PlaneStrain;
  HourglassType hourglass = HourglassType::Viscous;
  Real hourglass_coefficient = 0.05;
  Real q_linear = 0.06;
  Real q_quadratic = 1.5;
  bool gather = false; ///< write corner forces (deterministic) instead of atomic scatter
};

/// \brief Run the element solvers of all groups; forces go to nodes.f_int (atomic) or to
/// corners.corner_force (gather; then call gatherCornerForces). Returns the smallest stable
/// element time step h / c before the Courant factor; a negative value
/// -(e+1) reports an inverted element e.
Real computeElementForces(const std::vector<ElementGroup> &groups, const ElementControls &ctl,
                          const NodeFields &nodes, const ElementFields &elems,
                          const DeviceView<MaterialParams *> &materials, const NodeCorners &corners);

/// \brief f_int(n) = sum of the corner forces of node n, in a fixed order.
void gatherCornerForces(const NodeFields &nodes, const NodeCorners &corners);

/// \brief Stable element time step of the initial state (no strain rate), before the
/// Courant factor; also initialises sound speeds and volumes.
Real initialElementTimeStep(const std::vector<ElementGroup> &groups, Geometry2D geometry,
                            const NodeFields &nodes, const ElementFields &elems,
                            const DeviceView<MaterialParams *> &materials);

} // namespace scpdyn
