// Shared-node sums in the serial order (src/parallel/OrderedNodeSum): every copy of a shared
// node holds the bits of the serial assembly (all elements in ascending order, one by one from
// zero), not merely the same bits on every rank; a start value is kept; repeated keys are
// refused.
#include "parallel/LocalDomain.hpp"
#include "parallel/OrderedNodeSum.hpp"
#include "parallel/ParallelTestUtil.hpp"

#include <cmath>
#include <stdexcept>

namespace scpdyn::test
{
namespace
{

/// A term per element corner and component, both signs, with cancellation: non-dyadic, so
/// the order of additions shows in the last bits.
double term(Index e, int a, int i) { return std::sin(0.7 * e + 1.9 * a + 0.3 * i) * (1 + e % 5); }

/// The serial sums: every element in ascending global order, corner by corner, from `start`.
std::vector<std::array<double, 3>> serialSums(const HostMesh &g, double start)
{
  std::vector<std::array<double, 3>> v(size_t(g.numNodes()), {start, start, start});
  Index e = 0;
  for (const HostPart &p : g.parts)
  {
    const int npe = nodesPerElement(p.type);
    for (Index k = 0; k < p.numElements(); ++k, ++e)
      for (int a = 0; a < npe; ++a)
        for (int i = 0; i < 3; ++i)
          v[size_t(p.connectivity[size_t(k * npe + a)])][size_t(i)] += term(e, a, i);
  }
  return v;
}

/// This rank's terms: the corners of its elements at its shared nodes, keyed (global element,
/// corner), their values in `values` (3 per slot).
std::vector<std::vector<NodeTerm>> cornerTerms(const LocalDomain &d, std::vector<double> &values)
{
  std::vector<Index> shared_of(d.global_node.size(), -1);
  for (Index s = 0; s < d.shared.size(); ++s)
    shared_of[size_t(d.shared.local[size_t(s)])] = s;
  std::vector<std::vector<NodeTerm>> terms(size_t(d.shared.size()));
  Index e = 0;
  for (const HostPart &p : d.mesh.parts)
  {
    const int npe = nodesPerElement(p.type);
    for (Index k = 0; k < p.numElements(); ++k, ++e)
      for (int a = 0; a < npe; ++a)
      {
        const Index s = shared_of[size_t(p.connectivity[size_t(k * npe + a)])];
        if (s < 0)
          continue;
        const Index ge = d.global_element[size_t(e)];
        terms[size_t(s)].push_back({TermKey{ge, a, 0}, Index(values.size() / 3)});
        for (int i = 0; i < 3; ++i)
          values.push_back(term(ge, a, i));
      }
  }
  return terms;
}

} // namespace

TEST(OrderedNodeSum, SharedNodesGetTheSerialBitsOnEveryCopy)
{
  if (mpiSize() == 1)
    GTEST_SKIP() << "one rank shares no nodes";
  const int me = mpiRank();
  long checked = 0;
  for (const DecomposedCase &c : decomposedCases())
  {
    const LocalDomain d = buildLocalDomain(c.mesh, c.rank, me);
    std::vector<double> values;
    const auto terms = cornerTerms(d, values);
    OrderedNodeSum plan(MPI_COMM_WORLD, d.shared, terms);
    const size_t nl = d.global_node.size(), slots = values.size() / 3;
    VectorView v("values", slots), out("out", nl);
    auto hv = Kokkos::create_mirror_view(v);
    for (size_t k = 0; k < slots; ++k)
      for (int i = 0; i < 3; ++i)
        hv(k, i) = values[3 * k + size_t(i)];
    Kokkos::deep_copy(v, hv);
    Kokkos::deep_copy(out, 7.0); // a node other ranks do not hold keeps its value
    plan.sum(v, out);
    auto ho = Kokkos::create_mirror(HostSpace(), out); // a copy, not an alias of `out`
    Kokkos::deep_copy(ho, out);
    std::vector<double> host(3 * nl, 7.0);
    plan.sumHost(values, 3, host);
    const auto serial = serialSums(c.mesh, 0.0);
    // from a start value: the same on every copy, then the terms
    Kokkos::deep_copy(out, 0.25);
    plan.sum(v, out, false);
    auto hs = Kokkos::create_mirror_view_and_copy(HostSpace(), out);
    const auto started = serialSums(c.mesh, 0.25);
    std::vector<char> is_shared(nl, 0);
    for (Index n : d.shared.local)
      is_shared[size_t(n)] = 1;
    int wrong = 0, touched = 0;
    for (size_t n = 0; n < nl; ++n)
      for (int i = 0; i < 3; ++i)
      {
        const auto &ref = serial[size_t(d.global_node[n])];
        if (!is_shared[n])
        {
          touched += ho(n, i) != 7.0 || host[3 * n + size_t(i)] != 7.0;
          continue;
        }
        ++checked;
        wrong += bits(ho(n, i)) != bits(ref[size_t(i)]);
        wrong += bits(host[3 * n + size_t(i)]) != bits(ref[size_t(i)]);
        wrong += bits(hs(n, i)) != bits(started[size_t(d.global_node[n])][size_t(i)]);
      }
    EXPECT_EQ(wrong, 0) << c.name << ": shared-node sums that are not the serial bits";
    EXPECT_EQ(touched, 0) << c.name << ": nodes no other rank holds were written";
  }
  // every case has shared nodes on more than one rank, so something was compared
  EXPECT_GT(allReduceSum((long long)checked, MPI_COMM_WORLD), 0);
}

TEST(OrderedNodeSum, PartialSumsOverRanksWouldNotBeTheSerialBits)
{
  // the guard above can fail: the ranks' partial sums added in rank order (NodeHalo) differ
  // from the serial bits at some shared node of these cases
  if (mpiSize() == 1)
    GTEST_SKIP() << "one rank has no partial sums";
  const int me = mpiRank(), size = mpiSize();
  long differ = 0;
  for (const DecomposedCase &c : decomposedCases())
  {
    const auto serial = serialSums(c.mesh, 0.0);
    std::vector<std::vector<std::array<double, 3>>> partial(
        size_t(size), std::vector<std::array<double, 3>>(serial.size(), {0, 0, 0}));
    Index e = 0;
    for (const HostPart &p : c.mesh.parts)
    {
      const int npe = nodesPerElement(p.type);
      for (Index k = 0; k < p.numElements(); ++k, ++e)
        for (int a = 0; a < npe; ++a)
          for (int i = 0; i < 3; ++i)
            partial[size_t(c.rank[size_t(e)])][size_t(p.connectivity[size_t(k * npe + a)])]
                   [size_t(i)] += term(e, a, i);
    }
    for (size_t n = 0; n < serial.size(); ++n)
      for (int i = 0; i < 3; ++i)
      {
        double t = 0;
        for (int r = 0; r < size; ++r)
          t += partial[size_t(r)][n][size_t(i)];
        differ += bits(t) != bits(serial[n][size_t(i)]);
      }
  }
  if (me == 0)
    EXPECT_GT(differ, 0);
}

TEST(OrderedNodeSum, RepeatedKeysAreRefused)
{
  const int me = mpiRank();
  for (const DecomposedCase &c : decomposedCases())
  {
    const LocalDomain d = buildLocalDomain(c.mesh, c.rank, me);
    std::vector<double> values;
    auto terms = cornerTerms(d, values);
    bool any = false;
    for (auto &t : terms)
      for (NodeTerm &x : t)
      {
        x.key = TermKey{0, 0, 0}; // every term of every rank: one key
        any = true;
      }
    if (any)
      EXPECT_THROW(OrderedNodeSum(MPI_COMM_WORLD, d.shared, terms), std::runtime_error) << c.name;
    else
      EXPECT_NO_THROW(OrderedNodeSum(MPI_COMM_WORLD, d.shared, terms)) << c.name;
  }
}

} // namespace scpdyn::test
