// Shared-node sum (src/parallel/NodeHalo): equals the serial assembly, bit for bit when the
// reference adds the ranks' partial sums in ascending rank order; every copy of a shared node
// holds the same bits on every rank; repeated exchanges allocate nothing.
#include "parallel/LocalDomain.hpp"
#include "parallel/NodeHalo.hpp"
#include "parallel/ParallelTestUtil.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace scpdyn::test
{
namespace
{

/// Element "mass" shared equally by its nodes: non-dyadic, so the order of additions shows.
double scalarContribution(Index e, int npe) { return 1.0 / (3.0 + e) / npe; }
/// A vector field that depends on element, corner and component, both signs.
double vectorContribution(Index e, int a, int i)
{
  return std::sin(0.7 * e + 1.9 * a + 0.3 * i) * (1 + e % 5);
}

/// Per-node sums (3 vector components + scalar) accumulated in ascending element order, as a
/// rank does it locally, over the elements accepted by `take(global element)`, into nodes
/// `node_of(global node)`. the elements accepted by `take(global element)`, into nodes `node_of(global)`.
template <class Take, class NodeOf>
std::vector<std::array<double, 4>> assemble(const HostMesh &g, size_t num_nodes, Take take,
                                            NodeOf node_of)
{
  std::vector<std::array<double, 4>> v(num_nodes, {0, 0, 0, 0});
  Index e = 0;
  for (const HostPart &p : g.parts)
  {
    const int npe = nodesPerElement(p.type);
    for (Index k = 0; k < p.numElements(); ++k, ++e)
      if (take(e))
        for (int a = 0; a < npe; ++a)
        {
          auto &x = v[size_t(node_of(p.connectivity[size_t(k * npe + a)]))];
          for (int i = 0; i < 3; ++i)
            x[size_t(i)] += vectorContribution(e, a, i);
          x[3] += scalarContribution(e, npe);
        }
  }
  return v;
}

int allocations = 0;
void countAllocation(const Kokkos_Profiling_SpaceHandle, const char *, const void *, const uint64_t)
{
  ++allocations;
}

} // namespace

TEST(NodeHalo, SumEqualsRankOrderedSerialAssemblyOnEveryCopy)
{
  const int me = mpiRank(), size = mpiSize();
  const double u = std::ldexp(1.0, -53); // unit round-off
  for (const DecomposedCase &c : decomposedCases())
  {
    const HostMesh &g = c.mesh;
    const LocalDomain d = buildLocalDomain(g, c.rank, me);
    NodeHalo halo(d);
    const size_t nl = size_t(d.mesh.numNodes()), ng = size_t(g.numNodes());

    // this rank's partial sums on its local nodes, through the local numbering
    const auto local = assemble(
        g, nl, [&](Index e) { return c.rank[size_t(e)] == me; },
        [&](Index n) { return d.localNode(n); });
    VectorView f("f", nl);
    RealView m("m", nl);
    auto hf = Kokkos::create_mirror_view(f);
    auto hm = Kokkos::create_mirror_view(m);
    for (size_t n = 0; n < nl; ++n)
    {
      for (int i = 0; i < 3; ++i)
        hf(n, i) = local[n][size_t(i)];
      hm(n) = local[n][3];
    }
    Kokkos::deep_copy(f, hf);
    Kokkos::deep_copy(m, hm);
    const VectorView f0("f0", nl);
    const RealView m0("m0", nl);
    Kokkos::deep_copy(f0, f);
    Kokkos::deep_copy(m0, m);

    // split phase, both kinds in flight at once
    halo.beginSum(f);
    EXPECT_THROW(halo.beginSum(f), std::logic_error); // a second begin before the end
    halo.beginSum(m);
    halo.endSum(m);
    halo.endSum(f);
    EXPECT_THROW(halo.endSum(f), std::logic_error);
    Kokkos::deep_copy(hf, f);
    Kokkos::deep_copy(hm, m);

    // references from the global mesh: every rank's partials, the holders of each node
    std::vector<std::vector<std::array<double, 4>>> partial;
    for (int r = 0; r < size; ++r)
      partial.push_back(assemble(
          g, ng, [&](Index e) { return c.rank[size_t(e)] == r; }, [](Index n) { return n; }));
    const auto serial = assemble(
        g, ng, [](Index) { return true; }, [](Index n) { return n; });
    // per node: sum of |terms| per component and number of terms (for the round-off bound),
    // and the ranks holding it, all from the global mesh
    std::vector<std::array<double, 4>> magnitude(ng, {0, 0, 0, 0});
    std::vector<int> terms(ng, 0);
    std::vector<std::set<int>> holders(ng);
    {
      Index e = 0;
      for (const HostPart &p : g.parts)
      {
        const int npe = nodesPerElement(p.type);
        for (Index q = 0; q < p.numElements(); ++q, ++e)
          for (int a = 0; a < npe; ++a)
          {
            const size_t n = size_t(p.connectivity[size_t(q * npe + a)]);
            for (int i = 0; i < 3; ++i)
              magnitude[n][size_t(i)] += std::abs(vectorContribution(e, a, i));
            magnitude[n][3] += scalarContribution(e, npe);
            ++terms[n];
            holders[n].insert(c.rank[size_t(e)]);
          }
      }
    }

    int not_bitwise = 0, over_bound = 0, order_matters = 0;
    for (size_t n = 0; n < nl; ++n)
    {
      const size_t gn = size_t(d.global_node[n]);
      const double got[4] = {hf(n, 0), hf(n, 1), hf(n, 2), hm(n)};
      for (int i = 0; i < 4; ++i)
      {
        double ref = partial[size_t(*holders[gn].begin())][gn][size_t(i)];
        if (holders[gn].size() > 1)
        {
          ref = 0;
          for (int r : holders[gn])
            ref += partial[size_t(r)][gn][size_t(i)];
        }
        not_bitwise += bits(got[i]) != bits(ref);
        order_matters += bits(ref) != bits(serial[gn][size_t(i)]);
        // two summation orders of k terms differ by <= 2 (k - 1) u sum|terms|
        over_bound += std::abs(got[i] - serial[gn][size_t(i)]) >
                      2 * (terms[gn] - 1) * u * magnitude[gn][size_t(i)];
      }
    }
    EXPECT_EQ(not_bitwise, 0) << c.name;
    EXPECT_EQ(over_bound, 0) << c.name;

    // every copy of every shared node: the same bits on all ranks
    struct Copy
    {
      Index global;
      int rank;
      double v[4];
    };
    std::vector<Copy> mine;
    for (Index s = 0; s < d.shared.size(); ++s)
    {
      const Index n = d.shared.local[size_t(s)];
      mine.push_back({d.shared.global[size_t(s)], me, {hf(n, 0), hf(n, 1), hf(n, 2), hm(n)}});
    }
    const std::vector<Copy> all = allGatherV(mine);
    std::map<Index, std::vector<Copy>> by_node;
    for (const Copy &cp : all)
      by_node[cp.global].push_back(cp);
    int differing = 0, copies_ok = 0;
    for (const auto &kv : by_node)
    {
      EXPECT_EQ(kv.second.size(), holders[size_t(kv.first)].size())
          << c.name << " node " << kv.first;
      for (const Copy &cp : kv.second)
        for (int i = 0; i < 4; ++i)
          differing += bits(cp.v[i]) != bits(kv.second.front().v[i]);
      copies_ok += kv.second.size() > 1;
    }
    EXPECT_EQ(differing, 0) << c.name;
    EXPECT_EQ(copies_ok, int(by_node.size()));

    // repeated cycles: same result, same buffers, no allocation, bytes counted
    const Real *buffers[4] = {halo.vectorSendData(), halo.vectorRecvData(), halo.scalarSendData(),
                              halo.scalarRecvData()};
    const std::uint64_t bytes_before = halo.bytesSent();
    const VectorView f1("f1", nl);
    Kokkos::deep_copy(f1, f);
    allocations = 0;
    Kokkos::Tools::Experimental::set_allocate_data_callback(&countAllocation);
    { // the probe shows the counter works, so zero below means zero
      Kokkos::View<double *> probe("probe", 4);
    }
    const int probe_allocations = allocations;
    allocations = 0;
    const int cycles = 5;
    for (int k = 0; k < cycles; ++k)
    {
      Kokkos::deep_copy(f, f0);
      Kokkos::deep_copy(m, m0);
      halo.beginSum(f);
      halo.endSum(f);
      halo.sum(m);
    }
    Kokkos::fence();
    const int cycle_allocations = allocations;
    Kokkos::Tools::Experimental::set_allocate_data_callback(nullptr);
    EXPECT_GT(probe_allocations, 0);
    EXPECT_EQ(cycle_allocations, 0) << c.name;
    EXPECT_EQ(halo.vectorSendData(), buffers[0]);
    EXPECT_EQ(halo.vectorRecvData(), buffers[1]);
    EXPECT_EQ(halo.scalarSendData(), buffers[2]);
    EXPECT_EQ(halo.scalarRecvData(), buffers[3]);
    EXPECT_EQ(halo.bytesSent() - bytes_before,
              std::uint64_t(cycles) * (halo.bytesPerVectorSum() + halo.bytesPerScalarSum()));
    auto hf1 = Kokkos::create_mirror_view_and_copy(HostSpace(), f1);
    Kokkos::deep_copy(hf, f);
    int changed = 0;
    for (size_t n = 0; n < nl; ++n)
      for (int i = 0; i < 3; ++i)
        changed += bits(hf(n, i)) != bits(hf1(n, i));
    EXPECT_EQ(changed, 0) << c.name;

    // numbers for the report: shared nodes, neighbours, bytes per vector sum per rank
    const long long shared_total = allReduceSum((long long)d.shared.size());
    const double bytes_max = allReduceMax(double(halo.bytesPerVectorSum()));
    const double neighbours_max = allReduceMax(double(halo.numNeighbours()));
    SCPDYN_ROOT_PRINT(
        "[halo] np %d %s: %d nodes, shared copies %lld, max neighbours %.0f, max bytes"
        "/vector sum/rank %.0f, totals differing from serial order %d (rank 0)\n",
        size, c.name.c_str(), int(ng), shared_total, neighbours_max, bytes_max, order_matters);
  }
}

} // namespace scpdyn::test
