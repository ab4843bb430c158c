#include "driver/NodeUpdate.hpp"

namespace scpdyn
{

void zeroForces(const NodeFields &nodes, const Real gravity[3])
{
  auto f_int = nodes.f_int;
  auto f_ext = nodes.f_ext;
  auto mass = nodes.mass;
  const Real g0 = gravity[0], g1 = gravity[1], g2 = gravity[2];
  Kokkos::parallel_for(
      "zeroForces", Kokkos::RangePolicy<ExecSpace>(0, nodes.count),
      KOKKOS_LAMBDA(const Index n) {
        for (int i = 0; i < 3; ++i)
          f_int(n, i) = 0;
        const Real m = mass(n);
        f_ext(n, 0) = m * g0;
        f_ext(n, 1) = m * g1;
        f_ext(n, 2) = m * g2;
      });
}

NodeSums updateNodes(const NodeFields &nodes, const BoundaryConditions &bcs, Real dt, int dim,
                     const IndexView &owned)
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
  NodeSums sums;
  Kokkos::parallel_reduce(
      "updateNodes", Kokkos::RangePolicy<ExecSpace>(0, nodes.count),
      KOKKOS_LAMBDA(const Index n, NodeSums &s) {
        const Real m = mass(n);
        for (int i = 0; i < dim; ++i)
        {
          const Real v_old = v(n, i);
          const Real f = f_int(n, i) + f_ext(n, i);
          Real v_new = v_old + dt * f / m;
          Real work_force = f_ext(n, i);
          const int k = bc(n, i);
          if (k >= 0)
          {
            v_new = vbc(k);
            // the constraint's reaction does the work that the velocity change needs
            work_force += m * (v_new - v_old) / dt - f;
          }
          // Work on the leapfrog's own terms: 1/2 m v^n.v^{n+1} changes from n-1/2 to n+1/2 by
          // 1/2 v^n.(F^{n+1/2} dt_n + F^{n-1/2} dt_{n-1}); booking external work the same way
          // (the element energy does, by its trapezoidal stress) closes the balance to O(dt^2).
          const Real impulse = work_force * dt;
          if (all || owned(n))
          {
            s.external_work += 0.5 * v_old * (impulse + prev_impulse(n, i));
            s.kinetic += 0.5 * m * v_new * v_new;
            s.kinetic_mid += 0.5 * m * v_old * v_new;
            s.momentum[i] += m * v_new;
          }
          prev_impulse(n, i) = impulse;
          x(n, i) += half_dt * (v_old + v_new);
          v(n, i) = v_new;
        }
      },
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
