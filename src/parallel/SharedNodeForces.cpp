#include "parallel/SharedNodeForces.hpp"

namespace scpdyn
{

namespace
{

/// to(k) = from(k) at every shared node k.
void copyShared(const IndexView &shared, const VectorView &from, const VectorView &to)
{
  Kokkos::parallel_for(
      "scpdyn::comm::copyShared", Kokkos::RangePolicy<ExecSpace>(0, Index(shared.extent(0))),
      KOKKOS_LAMBDA(const Index s) {
        const Index k = shared(s);
        for (int d = 0; d < 3; ++d)
          to(k, d) = from(k, d);
      });
}

} // namespace

void sumSharedPartials(NodeHalo &halo, const IndexView &shared, const VectorView &partial,
                       const VectorView &scratch, const VectorView &total)
{
  copyShared(shared, partial, scratch);
  halo.sum(scratch);
  copyShared(shared, scratch, total);
}

void sumSharedLoads(NodeHalo &halo, const IndexView &shared, const VectorView &partial,
                    const NodeFields &nodes, const Real gravity[3])
{
  halo.sum(partial);
  auto f = nodes.f_ext;
  auto mass = nodes.mass;
  const Real g0 = gravity[0], g1 = gravity[1], g2 = gravity[2];
  Kokkos::parallel_for(
      "scpdyn::comm::addLoadTotals", Kokkos::RangePolicy<ExecSpace>(0, Index(shared.extent(0))),
      KOKKOS_LAMBDA(const Index s) {
        const Index k = shared(s);
        const Real m = mass(k);
        f(k, 0) = m * g0 + partial(k, 0);
        f(k, 1) = m * g1 + partial(k, 1);
        f(k, 2) = m * g2 + partial(k, 2);
      });
}

} // namespace scpdyn
