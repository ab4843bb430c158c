#pragma once
/// \file BoundaryConditions.hpp
/// \brief Steps 10 and 11: face loads (pressure) and node loads (force), plus the values of
/// the velocity constraints that step 12 imposes. Values times their time functions are
/// evaluated on the host once per cycle and copied to small device arrays.
#include "core/Fields.hpp"
#include "input/Deck.hpp"
#include "integrate/LateNodes.hpp"

namespace scpdyn
{

struct BoundaryConditions
{
  // velocity constraints: NodeFields::bc holds, per node component, an index into these
  std::vector<Real> velocity_value;
  std::vector<int> velocity_function;
  RealView velocity_current;

  // nodal forces: one entry per (node, BC)
  IndexView force_node;
  IndexView force_bc;
  std::vector<std::array<Real, 3>> force_value;
  std::vector<int> force_function;
  DeviceView<Real *[3]> force_current;

  // pressure faces: nodes (up to 4), node count, BC index. In 1D the second node slot holds
  // the element's other node, which fixes the outward direction.
  ConnView pressure_face;
  IndexView pressure_face_nodes;
  IndexView pressure_bc;
  std::vector<Real> pressure_value;
  std::vector<int> pressure_function;
  RealView pressure_current;

  std::vector<TimeFunction> functions;
};

/// \brief Velocity constraint values at time t (the end of the step).
void updateVelocityValues(BoundaryConditions &bc, Real t);
/// \brief Force and pressure values at time t (the half step).
void updateLoadValues(BoundaryConditions &bc, Real t);

/// \brief Step 10: pressure on faces at the half-step geometry x + dt/2 v, into f_ext.
/// Plane strain per metre, axisymmetric per radian (consistent r-weighted loads).
void applyFaceLoads(const BoundaryConditions &bc, const NodeFields &nodes, Real dt, int dim,
                    Geometry2D geometry);
/// \brief Step 11: nodal forces into f_ext.
void applyNodeForces(const BoundaryConditions &bc, const NodeFields &nodes);

/// \brief Steps 10 and 11 act on nodes after step 6: the nodes of the pressure faces (in 1D
/// the element's other node too) and of the nodal forces (integrate/LateNodes.hpp). The
/// velocity constraints are imposed inside step 12 and need no declaration.
void declareLateNodes(const BoundaryConditions &bc, LateNodes &late);

} // namespace scpdyn
