#include "parallel/SharedNodeForces.hpp"

namespace scpdyn
{

void sumSharedPartials(NodeHalo &halo, const IndexView &shared, const VectorView &partial,
                       const VectorView &scratch, const VectorView &total)
{
  const Index ns = Index(shared.extent(0));
  Kokkos::parallel_for(
      "scpdyn::comm::packPartials", Kokkos::RangePolicy<ExecSpace>(0, ns),
      KOKKOS_LAMBDA(const Index s) {
        const Index k = shared(s);
        for (int d = 0; d < 3; ++d)
          scratch(k, d) = partial(k, d);
      });
  halo.sum(scratch);
  Kokkos::parallel_for(
      "scpdyn::comm::setTotals", Kokkos::RangePolicy<ExecSpace>(0, ns),
      KOKKOS_LAMBDA(const Index s) {
        const Index k = shared(s);
        for (int d = 0; d < 3; ++d)
          total(k, d) = scratch(k, d);
      });
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
