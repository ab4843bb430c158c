#include "integrate/NodeUpdate.hpp"

namespace scpdyn
{

bool hasExternalLoads(const BoundaryConditions &bc, const Real gravity[3])
{
  return gravity[0] != 0 || gravity[1] != 0 || gravity[2] != 0 || !bc.force_value.empty() ||
         !bc.pressure_value.empty();
}

void zeroForces(const NodeFields &nodes, const Real gravity[3], const bool loads)
{
  const NodeIntegrator node = nodeIntegrator(nodes, RealView(), 0, IndexView(), gravity);
  Kokkos::parallel_for(
      "zeroForces", Kokkos::RangePolicy<ExecSpace>(0, nodes.count),
      KOKKOS_LAMBDA(const Index n) { node.resetForces(n, loads); });
}

NodeIntegrator nodeIntegrator(const NodeFields &nodes, const RealView &velocity_values,
                              const Real dt, const IndexView &owned, const Real *g)
{
  NodeIntegrator k;
  k.x = nodes.x;
  k.v = nodes.v;
  k.f_int = nodes.f_int;
  k.f_ext = nodes.f_ext;
  k.f_contact = nodes.f_contact;
  k.prev_impulse = nodes.external_impulse;
  k.reaction = nodes.reaction;
  k.damping_impulse = nodes.damping_impulse;
  k.mass = nodes.mass;
  k.bc = nodes.bc;
  k.vbc = velocity_values;
  k.owned = owned;
  k.dt = dt;
  k.half_dt = 0.5 * dt;
  for (int i = 0; g && i < 3; ++i)
    k.g[i] = g[i];
  return k;
}

namespace
{

/// Nodes per work item of step 12 on the host (each item's sums run in local variables:
/// NodeIntegrator::Sums).
#if defined(KOKKOS_ENABLE_CUDA) || defined(KOKKOS_ENABLE_HIP) || defined(KOKKOS_ENABLE_SYCL)
constexpr Index kNodeChunk = 1;
#else
constexpr Index kNodeChunk = 256;
#endif

/// updateNodes() in dimension Dim over all nodes, or over the given runs.
template <int Dim, bool Loads, bool Clear, bool Contact, bool Record, bool Damp = false>
NodeSums integrateAll(const NodeIntegrator &node, const Index count,
                      const DeviceView<Index *[2]> *given_runs)
{
  NodeSums sums;
  if (given_runs)
  {
    const DeviceView<Index *[2]> runs = *given_runs;
    Kokkos::parallel_reduce(
        "updateNodes", Kokkos::RangePolicy<ExecSpace>(0, Index(runs.extent(0))),
        KOKKOS_LAMBDA(const Index r, NodeSums &s) {
          node.run<Dim, Loads, Clear, Contact, Record, Damp>(runs(r, 0), runs(r, 1), s);
        },
        Kokkos::Sum<NodeSums>(sums));
    return sums;
  }
  Kokkos::parallel_reduce(
      "updateNodes", Kokkos::RangePolicy<ExecSpace>(0, (count + kNodeChunk - 1) / kNodeChunk),
      KOKKOS_LAMBDA(const Index chunk, NodeSums &s) {
        const Index begin = chunk * kNodeChunk;
        node.run<Dim, Loads, Clear, Contact, Record, Damp>(
            begin, count - begin < kNodeChunk ? count : begin + kNodeChunk, s);
      },
      Kokkos::Sum<NodeSums>(sums));
  return sums;
}

template <int Dim, bool Contact, bool Record>
NodeSums integrateWithContact(const NodeIntegrator &node, const Index count, const bool loads,
                              const bool clear, const DeviceView<Index *[2]> *runs)
{
  if (clear)
    return loads ? integrateAll<Dim, true, true, Contact, Record>(node, count, runs)
                 : integrateAll<Dim, false, true, Contact, Record>(node, count, runs);
  return loads ? integrateAll<Dim, true, false, Contact, Record>(node, count, runs)
               : integrateAll<Dim, false, false, Contact, Record>(node, count, runs);
}

/// The settling stage's step 12 (its own instantiations, so that the undamped step keeps its
/// code): gravity is always on, so always with loads.
template <int Dim, bool Contact, bool Record>
NodeSums integrateDamped(const NodeIntegrator &node, const Index count, const bool clear,
                         const DeviceView<Index *[2]> *runs)
{
  return clear ? integrateAll<Dim, true, true, Contact, Record, true>(node, count, runs)
               : integrateAll<Dim, true, false, Contact, Record, true>(node, count, runs);
}

template <int Dim>
NodeSums integrateNodes(const NodeIntegrator &node, const Index count, const bool loads,
                        const bool clear, const DeviceView<Index *[2]> *runs, const bool damp)
{
  // contact forces have their own field, read only where there is one; reactions are
  // recorded only where the deck has velocity constraints
  const bool contact = node.f_contact.extent(0) != 0, record = node.reaction.extent(0) != 0;
  if (damp)
  {
    if (contact)
      return record ? integrateDamped<Dim, true, true>(node, count, clear, runs)
                    : integrateDamped<Dim, true, false>(node, count, clear, runs);
    return record ? integrateDamped<Dim, false, true>(node, count, clear, runs)
                  : integrateDamped<Dim, false, false>(node, count, clear, runs);
  }
  if (contact)
    return record ? integrateWithContact<Dim, true, true>(node, count, loads, clear, runs)
                  : integrateWithContact<Dim, true, false>(node, count, loads, clear, runs);
  return record ? integrateWithContact<Dim, false, true>(node, count, loads, clear, runs)
                : integrateWithContact<Dim, false, false>(node, count, loads, clear, runs);
}

} // namespace

NodeSums updateNodes(const NodeFields &nodes, const BoundaryConditions &bcs, Real dt, int dim,
                     const IndexView &owned, const bool loads, const Real *next_gravity,
                     const DeviceView<Index *[2]> *runs, const MassDamping *damping)
{
  NodeIntegrator node = nodeIntegrator(nodes, bcs.velocity_current, dt, owned, next_gravity);
  const bool clear = next_gravity != nullptr, damp = damping != nullptr;
  if (damp)
    node.damping = *damping;
  if (dim == 1)
    return integrateNodes<1>(node, nodes.count, loads, clear, runs, damp);
  if (dim == 2)
    return integrateNodes<2>(node, nodes.count, loads, clear, runs, damp);
  return integrateNodes<3>(node, nodes.count, loads, clear, runs, damp);
}

NodeSums sweepSums(const NodeSweep &sweep)
{
  auto block_sums = sweep.block_sums;
  NodeSums sums;
  Kokkos::parallel_reduce(
      "sweepSums", Kokkos::RangePolicy<ExecSpace>(0, Index(block_sums.extent(0))),
      KOKKOS_LAMBDA(const Index b, NodeSums &s) { s += block_sums(b); },
      Kokkos::Sum<NodeSums>(sums));
  return sums;
}

NodeSums nodeSums(const NodeFields &nodes, const IndexView &owned)
{
  const bool all = owned.extent(0) == 0;
  auto v = nodes.v;
  auto mass = nodes.mass;
  NodeSums sums;
  Kokkos::parallel_reduce(
      "nodeSums", Kokkos::RangePolicy<ExecSpace>(0, nodes.count),
      KOKKOS_LAMBDA(const Index n, NodeSums &s) {
        if (!all && !owned(n))
          return;
        for (int i = 0; i < 3; ++i)
        {
          const Real p = mass(n) * v(n, i);
          s.kinetic += 0.5 * p * v(n, i);
          s.momentum[i] += p;
        }
      },
      Kokkos::Sum<NodeSums>(sums));
  sums.kinetic_mid = sums.kinetic;
  return sums;
}

} // namespace scpdyn
