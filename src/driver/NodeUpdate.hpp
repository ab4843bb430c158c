#pragma once
/// \file NodeUpdate.hpp
/// \brief Step 5 (zero forces) and step 12 (update nodes) of the cycle.
///
/// Drift-kick-drift leapfrog (scp-method.md 2.3): the element step used x^{n+1/2} =
/// x^n + dt/2 v^n; here v^{n+1} = v^n + dt F/M, velocity constraints imposed, and
/// x^{n+1} = x^n + dt/2 (v^n + v^{n+1}).
#include "bc/BoundaryConditions.hpp"
#include "core/Fields.hpp"

namespace scpdyn
{

/// \brief Sums over nodes of one update (reduced in one pass).
struct NodeSums
{
  Real kinetic = 0;     ///< 1/2 sum m |v^{n+1}|^2
  Real kinetic_mid = 0; ///< 1/2 sum m v^n . v^{n+1} (the leapfrog's conserved kinetic part)
  Real external_work = 0; ///< work of f_ext and constraint reactions over the step, f.v^n dt
  Real momentum[3] = {0, 0, 0};

  KOKKOS_INLINE_FUNCTION NodeSums &operator+=(const NodeSums &o)
  {
    kinetic += o.kinetic;
    kinetic_mid += o.kinetic_mid;
    external_work += o.external_work;
    for (int i = 0; i < 3; ++i)
      momentum[i] += o.momentum[i];
    return *this;
  }
  KOKKOS_INLINE_FUNCTION void operator+=(const volatile NodeSums &o) volatile
  {
    kinetic += o.kinetic;
    kinetic_mid += o.kinetic_mid;
    external_work += o.external_work;
    for (int i = 0; i < 3; ++i)
      momentum[i] += o.momentum[i];
  }
};

/// \brief True if the deck puts loads into f_ext: gravity, nodal forces or face pressure (the
/// same on every rank). Without them f_ext keeps its initial zero, and steps 5 and 12 neither
/// write nor read it, nor the impulse of a node without a velocity constraint: 128 of the ~316
/// bytes a node moves in the two steps (perf/README.md, change 17).
bool hasExternalLoads(const BoundaryConditions &bc, const Real gravity[3]);

/// \brief Step 5: f_int = 0, and f_ext = m g if `loads` (hasExternalLoads()).
void zeroForces(const NodeFields &nodes, const Real gravity[3], bool loads = true);

/// \brief Step 12: integrate velocities and positions; returns kinetic energies, external
/// work and momentum. With `owned` (per node, 1 = this rank owns it) the sums cover the owned
/// nodes only, so a node shared between ranks is counted once over the ranks; every node
/// is updated either way. Without `loads` (hasExternalLoads()) f_ext is taken as zero unread,
/// with the same bits. With `next_gravity`, the same sweep then does the next cycle's step 5
/// (zeroForces(nodes, next_gravity, loads)) on each node once its forces are used: the forces
/// are already in cache, and step 5's own pass over f_int (and f_ext) is saved.
NodeSums updateNodes(const NodeFields &nodes, const BoundaryConditions &bc, Real dt, int dim,
                     const IndexView &owned = IndexView(), bool loads = true,
                     const Real *next_gravity = nullptr);

/// \brief Kinetic energy and momentum of the current velocities (owned nodes only when
/// `owned` is given).
NodeSums nodeSums(const NodeFields &nodes, const IndexView &owned = IndexView());

} // namespace scpdyn

namespace Kokkos
{
template <>
struct reduction_identity<scpdyn::NodeSums>
{
  KOKKOS_FORCEINLINE_FUNCTION static scpdyn::NodeSums sum() { return scpdyn::NodeSums(); }
};
} // namespace Kokkos
