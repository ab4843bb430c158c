#include "bc/PartRelease.hpp"

#include "core/HostCopy.hpp"

#include <map>

namespace scpdyn
{

PartRelease holdNodes(const std::vector<Real> &hold_time, const int dim, const NodeFields &nodes,
                      BoundaryConditions &bc)
{
  PartRelease release;
  std::map<Real, size_t> group_of;
  auto h_bc = Kokkos::create_mirror_view_and_copy(HostSpace(), nodes.bc);
  for (size_t n = 0; n < hold_time.size() && Index(n) < nodes.count; ++n)
  {
    const Real t = hold_time[n];
    if (!(t > 0))
      continue;
    auto it = group_of.find(t);
    if (it == group_of.end())
    {
      PartRelease::Group g;
      g.time = t;
      g.slot = int(bc.velocity_value.size());
      bc.velocity_value.push_back(0);
      bc.velocity_function.push_back(-1);
      it = group_of.emplace(t, release.groups.size()).first;
      release.groups.push_back(g);
    }
    PartRelease::Group &g = release.groups[it->second];
    for (int i = 0; i < dim; ++i)
      if (h_bc(Index(n), i) < 0)
      {
        h_bc(Index(n), i) = g.slot;
        g.node.push_back(Index(n));
        g.component.push_back(i);
      }
  }
  for (PartRelease::Group &g : release.groups)
    g.velocity.assign(g.node.size(), 0);
  if (!release.groups.empty())
  {
    Kokkos::deep_copy(nodes.bc, h_bc);
    bc.velocity_current = RealView("velocity_bc", bc.velocity_value.size());
  }
  return release;
}

namespace
{
/// Frees group g's components; with `set_velocity` gives them their velocity, zeroes their last
/// external impulse and returns what they gained.
NodeSums freeGroup(const PartRelease::Group &g, const NodeFields &nodes, const IndexView &owned,
                   const bool set_velocity)
{
  const IndexView node = toDevice(g.node, "release_node");
  const DeviceView<int *> component = toDevice(g.component, "release_component");
  const RealView velocity = toDevice(g.velocity, "release_velocity");
  auto bc = nodes.bc;
  auto v = nodes.v;
  auto impulse = nodes.external_impulse;
  auto mass = nodes.mass;
  const bool all = owned.extent(0) == 0;
  NodeSums sums;
  Kokkos::parallel_reduce(
      "scpdyn::release::freeGroup", Kokkos::RangePolicy<ExecSpace>(0, Index(g.node.size())),
      KOKKOS_LAMBDA(const Index k, NodeSums &s) {
        const Index n = node(k);
        const int i = component(k);
        bc(n, i) = -1;
        if (!set_velocity)
          return;
        const Real vk = velocity(k);
        v(n, i) = vk;
        if (impulse.extent(0) != 0)
          impulse(n, i) = 0;
        if (!all && !owned(n))
          return;
        const Real p = mass(n) * vk;
        s.kinetic += 0.5 * p * vk;
        s.momentum[i] += p;
      },
      Kokkos::Sum<NodeSums>(sums));
  sums.kinetic_mid = sums.external_work = sums.kinetic;
  return sums;
}
} // namespace

NodeSums releaseDue(PartRelease &release, const Real t, const NodeFields &nodes,
                    const IndexView &owned)
{
  NodeSums gained;
  for (PartRelease::Group &g : release.groups)
    if (g.due(t))
    {
      gained += freeGroup(g, nodes, owned, true);
      g.released = true;
    }
  return gained;
}

void markReleased(PartRelease &release, const Real t, const NodeFields &nodes)
{
  for (PartRelease::Group &g : release.groups)
    if (g.due(t))
    {
      freeGroup(g, nodes, IndexView(), false);
      g.released = true;
    }
}

} // namespace scpdyn
