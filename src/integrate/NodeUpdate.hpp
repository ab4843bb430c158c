#pragma once
/// \file NodeUpdate.hpp
/// \brief Step 5 (zero forces) and step 12 (update nodes) of the cycle; the step on one node
/// is NodeIntegrator (integrate/NodeIntegrator.hpp).
#include "bc/BoundaryConditions.hpp"
#include "integrate/NodeIntegrator.hpp"
#include "integrate/NodeSweep.hpp"

namespace scpdyn
{

/// \brief True if the deck puts loads into f_ext: gravity, nodal forces or face pressure (the
/// same on every rank). Without them f_ext keeps its initial zero, and steps 5 and 12 neither
/// write nor read it, nor the impulse of a node without a velocity constraint: 128 of the ~316
/// bytes a node moves in the two steps.
bool hasExternalLoads(const BoundaryConditions &bc, const Real gravity[3]);

/// \brief Step 5: f_int = 0, and f_ext = m g if `loads` (hasExternalLoads()).
void zeroForces(const NodeFields &nodes, const Real gravity[3], bool loads = true);

/// \brief The NodeIntegrator of step 12 with time step dt, the velocity constraints' values
/// (BoundaryConditions::velocity_current) and the next gravity g (or none).
NodeIntegrator nodeIntegrator(const NodeFields &nodes, const RealView &velocity_values, Real dt,
                              const IndexView &owned, const Real *g);

/// \brief Step 12: integrate velocities and positions; returns kinetic energies, external
/// work and momentum. With `owned` (per node, 1 = this rank owns it) the sums cover the owned
/// nodes only, so a node shared between ranks is counted once over the ranks; every node
/// is updated either way. Without `loads` (hasExternalLoads()) f_ext is taken as zero unread,
/// with the same bits. With `next_gravity`, the same sweep then does the next cycle's step 5
/// (zeroForces(nodes, next_gravity, loads)) on each node once its forces are used: the forces
/// are already in cache, and step 5's own pass over f_int (and f_ext) is saved. With `runs`
/// (NodeSweep::late_runs) only the nodes of those runs (maybe none), else all of them. With
/// `damping` (the settling stage, docs/theory.md 2.4) the free components are damped, their
/// damping impulse kept in NodeFields::damping_impulse (allocated) and its work summed in
/// NodeSums::damping_work; `loads` is then taken as true (a settling stage has gravity).
NodeSums updateNodes(const NodeFields &nodes, const BoundaryConditions &bc, Real dt, int dim,
                     const IndexView &owned = IndexView(), bool loads = true,
                     const Real *next_gravity = nullptr,
                     const DeviceView<Index *[2]> *runs = nullptr,
                     const MassDamping *damping = nullptr);

/// \brief The sums of the early nodes of the last step 6 (NodeSweep::block_sums).
NodeSums sweepSums(const NodeSweep &sweep);

/// \brief Kinetic energy and momentum of the current velocities (owned nodes only when
/// `owned` is given).
NodeSums nodeSums(const NodeFields &nodes, const IndexView &owned = IndexView());

} // namespace scpdyn
