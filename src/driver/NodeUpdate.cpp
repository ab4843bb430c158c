#include "driver/NodeUpdate.hpp"

namespace scpdyn
{

bool hasExternalLoads(const BoundaryConditions &bc, const Real gravity[3])
{
  return gravity[0] != 0 || gravity[1] != 0 || gravity[2] != 0 || !bc.force_value.empty() ||
         !bc.pressure_value.empty();
}

namespace
{

/// Step 5 on node n: f_int = 0, and with loads f_ext = m g (without, f_ext keeps its zero).
/// zeroForces() runs it over the nodes, and step 12 with a next gravity after its update.
struct ForceReset
{
  VectorView f_int, f_ext;
  RealView mass;
  Real g[3];

  ForceReset(const NodeFields &nodes, const Real gravity[3])
      : f_int(nodes.f_int), f_ext(nodes.f_ext), mass(nodes.mass),
        g{gravity[0], gravity[1], gravity[2]}
  {
  }

  KOKKOS_INLINE_FUNCTION void operator()(const Index n, const bool loads) const
  {
    for (int i = 0; i < 3; ++i)
      f_int(n, i) = 0;
    if (!loads)
      return;
    const Real m = mass(n);
    for (int i = 0; i < 3; ++i)
      f_ext(n, i) = m * g[i];
  }
};

} // namespace

void zeroForces(const NodeFields &nodes, const Real gravity[3], const bool loads)
{
  const ForceReset reset(nodes, gravity);
  Kokkos::parallel_for(
      "zeroForces", Kokkos::RangePolicy<ExecSpace>(0, nodes.count),
      KOKKOS_LAMBDA(const Index n) { reset(n, loads); });
}

namespace
{

/// Nodes per work item of step 12 on the host. The sums of a chunk run in local variables,
/// which no store to x, v or the impulse can alias: with the sums in the reduction's own
/// NodeSums, every one of their 9 additions a node went through memory after each such store
/// (a chain of store-to-load forwards, ~40 % of the step). The additions keep their order.
#if defined(KOKKOS_ENABLE_CUDA) || defined(KOKKOS_ENABLE_HIP) || defined(KOKKOS_ENABLE_SYCL)
constexpr Index kNodeChunk = 1;
#else
constexpr Index kNodeChunk = 256;
#endif

/// updateNodes() in dimension Dim; without Loads, f_ext is +0 (not read) and a node component
/// without a velocity constraint has impulse 0 and previous impulse 0, so its external work
/// term (+-0) is skipped: adding +-0 to the sum, which starts at +0, never changes its bits.
/// With Clear, each node's forces are then set for the next cycle by ForceReset (gravity g).
template <int Dim, bool Loads, bool Clear>
NodeSums integrateNodes(const NodeFields &nodes, const BoundaryConditions &bcs, Real dt,
                        const IndexView &owned, const Real *g)
{
  const bool all = owned.extent(0) == 0;
  auto x = nodes.x;
  auto v = nodes.v;
  auto f_int = nodes.f_int;
  auto f_ext = nodes.f_ext;
  auto mass = nodes.mass;
  auto bc = nodes.bc;
  auto vbc = bcs.velocity_current;
  auto prev_impulse = nodes.external_impulse;
  const Real half_dt = 0.5 * dt;
  const Index count = nodes.count;
  const Real no_gravity[3] = {0, 0, 0};
  const ForceReset reset(nodes, Clear ? g : no_gravity);
  NodeSums sums;
  Kokkos::parallel_reduce(
      "updateNodes", Kokkos::RangePolicy<ExecSpace>(0, (count + kNodeChunk - 1) / kNodeChunk),
      KOKKOS_LAMBDA(const Index chunk, NodeSums &s) {
        Real external_work = s.external_work, kinetic = s.kinetic, kinetic_mid = s.kinetic_mid;
        Real momentum[Dim];
        for (int i = 0; i < Dim; ++i)
          momentum[i] = s.momentum[i];
        const Index end = count - chunk * kNodeChunk < kNodeChunk ? count : (chunk + 1) * kNodeChunk;
        for (Index n = chunk * kNodeChunk; n < end; ++n)
        {
          const Real m = mass(n);
          const bool counted = all || owned(n);
          for (int i = 0; i < Dim; ++i)
          {
            const Real v_old = v(n, i);
            const Real fe = Loads ? f_ext(n, i) : Real(0);
            const Real f = f_int(n, i) + fe;
            Real v_new = v_old + dt * f / m;
            Real work_force = fe;
            const int k = bc(n, i);
            if (k >= 0)
            {
              v_new = vbc(k);
              // the constraint's reaction does the work that the velocity change needs
              work_force += m * (v_new - v_old) / dt - f;
            }
            // Work on the leapfrog's own terms: 1/2 m v^n.v^{n+1} changes from n-1/2 to n+1/2
            // by 1/2 v^n.(F^{n+1/2} dt_n + F^{n-1/2} dt_{n-1}); booking external work the same
            // way (the element energy does, by its trapezoidal stress) closes the balance to
            // O(dt^2).
            if (Loads || k >= 0)
            {
              const Real impulse = work_force * dt;
              if (counted)
                external_work += 0.5 * v_old * (impulse + prev_impulse(n, i));
              prev_impulse(n, i) = impulse;
            }
            if (counted)
            {
              kinetic += 0.5 * m * v_new * v_new;
              kinetic_mid += 0.5 * m * v_old * v_new;
              momentum[i] += m * v_new;
            }
            x(n, i) += half_dt * (v_old + v_new);
            v(n, i) = v_new;
          }
          if (Clear)
            reset(n, Loads);
        }
        s.external_work = external_work;
        s.kinetic = kinetic;
        s.kinetic_mid = kinetic_mid;
        for (int i = 0; i < Dim; ++i)
          s.momentum[i] = momentum[i];
      },
      Kokkos::Sum<NodeSums>(sums));
  return sums;
}

template <int Dim>
NodeSums integrateNodes(const NodeFields &nodes, const BoundaryConditions &bcs, Real dt,
                        const IndexView &owned, bool loads, const Real *g)
{
  if (g)
    return loads ? integrateNodes<Dim, true, true>(nodes, bcs, dt, owned, g)
                 : integrateNodes<Dim, false, true>(nodes, bcs, dt, owned, g);
  return loads ? integrateNodes<Dim, true, false>(nodes, bcs, dt, owned, g)
               : integrateNodes<Dim, false, false>(nodes, bcs, dt, owned, g);
}

} // namespace

NodeSums updateNodes(const NodeFields &nodes, const BoundaryConditions &bcs, Real dt, int dim,
                     const IndexView &owned, const bool loads, const Real *next_gravity)
{
  if (dim == 1)
    return integrateNodes<1>(nodes, bcs, dt, owned, loads, next_gravity);
  if (dim == 2)
    return integrateNodes<2>(nodes, bcs, dt, owned, loads, next_gravity);
  return integrateNodes<3>(nodes, bcs, dt, owned, loads, next_gravity);
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
