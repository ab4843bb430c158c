#pragma once
/// \file PartRelease.hpp
/// \brief parts[].release_time (docs/theory.md 2.4): the nodes of such a part are held, each
/// free component pointing at a velocity constraint of value 0 of its own release time, so
/// step 12 keeps them at rest; the cycle that reaches the release time frees them and gives
/// them their initial velocity (the part's and the deck's initial_conditions, taken at set-up).
#include "bc/BoundaryConditions.hpp"
#include "integrate/NodeIntegrator.hpp"

#include <vector>

namespace scpdyn
{

struct PartRelease
{
  /// The held components of one release time.
  struct Group
  {
    Real time = 0;              ///< [s]
    int slot = -1;              ///< its constraint (a BoundaryConditions::velocity_value)
    std::vector<Index> node;    ///< local node of each held component
    std::vector<int> component; ///< its component
    std::vector<Real> velocity; ///< its velocity from the release on [m/s]
    bool released = false;
    /// Not yet released, and its time reached at time t.
    bool due(const Real t) const { return !released && !(t < time); }
  };
  std::vector<Group> groups;
};

/// \brief Set-up: holds every local node n with hold_time[n] > 0 (the latest release time of
/// the parts of its elements) until that time: each component below `dim` without a velocity
/// BC of the deck gets a new velocity constraint of value 0, one per release time. Call after
/// the contact set-up (a held face is not rigid for the contact: it moves once released) and
/// before the node sweep's (a held node is late).
PartRelease holdNodes(const std::vector<Real> &hold_time, int dim, const NodeFields &nodes,
                      BoundaryConditions &bc);

/// \brief Set-up: the velocity each held component takes at its release, from the initial
/// velocities `v` (host, per local node, before the constraints override them).
template <class HostVectors>
void setReleaseVelocities(PartRelease &release, const HostVectors &v)
{
  for (PartRelease::Group &g : release.groups)
    for (size_t k = 0; k < g.node.size(); ++k)
      g.velocity[k] = v(g.node[k], g.component[k]);
}

/// \brief The end of a cycle at time t: every group not yet released whose time is <= t is
/// freed (its components' constraint removed, their velocity set, their last external impulse
/// zero: the held node did not move). Returns the kinetic energy and momentum the released
/// components gained (kinetic = kinetic_mid = external_work), over the owned nodes (`owned`
/// empty: every node), this rank's.
NodeSums releaseDue(PartRelease &release, Real t, const NodeFields &nodes, const IndexView &owned);

/// \brief A restart at time t: the groups released by then are freed, without touching the
/// velocities (the file's).
void markReleased(PartRelease &release, Real t, const NodeFields &nodes);

} // namespace scpdyn
