// Local domains (src/parallel/LocalDomain): together the ranks hold every element once and
// every node at least once, the local mesh maps back to the global one, and the shared nodes
// are exactly the nodes whose elements sit on several ranks.
#include "parallel/LocalDomain.hpp"
#include "parallel/ParallelTestUtil.hpp"
#include "parallel/Partitioner.hpp"

#include <algorithm>
#include <set>
#include <string>

namespace scpdyn::test
{

std::vector<DecomposedCase> decomposedCases()
{
  const int size = mpiSize();
  std::vector<DecomposedCase> cases;
  {
    DecomposedCase c{"quad 12x10, METIS", quadBlock(12, 10), {}};
    c.mesh.node_sets["left"] = nodesInBox(c.mesh, {0, 0, 0}, {0, 0.8, 0}, 1e-9);
    c.mesh.face_sets["bottom"] =
        facesInBox(extractExternalFaces(c.mesh), c.mesh, {0, 0, 0}, {1, 0, 0}, 1e-9);
    c.rank = partitionElements(c.mesh, extractExternalFaces(c.mesh), size);
    cases.push_back(c);
  }
  {
    // round robin: nodes held by up to 4 ranks (3 at np = 3), the hardest case for the sum
    DecomposedCase c{"quad 9x7, round robin", quadBlock(9, 7), {}};
    for (Index e = 0; e < c.mesh.numElements(); ++e)
      c.rank.push_back(int(e % size));
    cases.push_back(c);
  }
  {
    DecomposedCase c{"hex 6x5x4, round robin", hexBlock(6, 5, 4), {}};
    for (Index e = 0; e < c.mesh.numElements(); ++e)
      c.rank.push_back(int((e / 3) % size));
    cases.push_back(c);
  }
  {
    // bricks merged into one body (nodes shared across parts) plus a separate jointed block
    DecomposedCase c{"merged wall + block, METIS", HostMesh(), {}};
    appendBrickWall(c.mesh, "wall", ElementType::Quad4, {3, 2, 1}, {0, 0, 0}, {0.3, 0.1, 1},
                    {3, 3, 1}, 0.5);
    std::vector<int> all(c.mesh.parts.size());
    for (size_t p = 0; p < all.size(); ++p)
      all[p] = int(p);
    mergeCoincidentNodes(c.mesh, all, 1e-9);
    appendBlock(c.mesh, "top", ElementType::Quad4, {6, 2, 1}, {0, 0.3, 0}, {0.9, 0.1, 1});
    c.mesh.node_sets["top"] = nodesOfParts(c.mesh, {int(c.mesh.parts.size()) - 1});
    c.mesh.face_sets["wall"] = facesOfParts(extractExternalFaces(c.mesh), all);
    c.rank = partitionElements(c.mesh, extractExternalFaces(c.mesh), size);
    cases.push_back(c);
  }
  return cases;
}

TEST(LocalDomain, RanksTogetherHoldTheGlobalMesh)
{
  const int me = mpiRank();
  for (const DecomposedCase &c : decomposedCases())
  {
    const HostMesh &g = c.mesh;
    const LocalDomain d = buildLocalDomain(g, c.rank, me);
    const HostMesh &l = d.mesh;
    EXPECT_EQ(d.rank, me);
    ASSERT_EQ(l.parts.size(), g.parts.size()) << c.name;
    ASSERT_EQ(d.global_element.size(), size_t(l.numElements()));
    ASSERT_EQ(d.global_node.size(), size_t(l.numNodes()));
    EXPECT_TRUE(std::is_sorted(d.global_node.begin(), d.global_node.end()));
    EXPECT_TRUE(std::is_sorted(d.global_element.begin(), d.global_element.end()));

    // every global element on exactly one rank, every node on at least one
    std::vector<int> element_count(size_t(g.numElements()), 0), node_count(size_t(g.numNodes()), 0);
    for (Index e : d.global_element)
    {
      ++element_count[size_t(e)];
      EXPECT_EQ(c.rank[size_t(e)], me);
    }
    for (Index n : d.global_node)
      ++node_count[size_t(n)];
    element_count = sumOverRanks(element_count);
    node_count = sumOverRanks(node_count);
    EXPECT_TRUE(std::all_of(element_count.begin(), element_count.end(), [](int k) {
      return k == 1;
    })) << c.name;

    // reference from the global mesh: the ranks of the elements using each node
    std::vector<std::set<int>> holders(size_t(g.numNodes()));
    std::vector<Index> first(g.parts.size() + 1, 0);
    Index e = 0;
    for (size_t p = 0; p < g.parts.size(); ++p)
    {
      const HostPart &gp = g.parts[p], &lp = l.parts[p];
      first[p + 1] = first[p] + gp.numElements();
      EXPECT_EQ(gp.name, lp.name);
      EXPECT_EQ(gp.type, lp.type);
      const int npe = nodesPerElement(gp.type);
      for (Index k = 0; k < gp.numElements(); ++k, ++e)
        for (int a = 0; a < npe; ++a)
          holders[size_t(gp.connectivity[size_t(k * npe + a)])].insert(c.rank[size_t(e)]);
    }
    for (size_t n = 0; n < holders.size(); ++n)
      EXPECT_EQ(node_count[n], int(holders[n].size())) << c.name << " node " << n;

    // local connectivity and coordinates map back to the global mesh
    Index le = 0;
    for (size_t p = 0; p < l.parts.size(); ++p)
    {
      const HostPart &gp = g.parts[p], &lp = l.parts[p];
      const int npe = nodesPerElement(gp.type);
      for (Index k = 0; k < lp.numElements(); ++k, ++le)
      {
        const Index ge = d.global_element[size_t(le)] - first[p];
        if (ge < 0 || ge >= gp.numElements())
        {
          ADD_FAILURE() << c.name << ": local element " << le << " maps outside part " << p;
          continue;
        }
        for (int a = 0; a < npe; ++a)
          EXPECT_EQ(d.global_node[size_t(lp.connectivity[size_t(k * npe + a)])],
                    gp.connectivity[size_t(ge * npe + a)]);
      }
    }
    for (Index n = 0; n < l.numNodes(); ++n)
    {
      EXPECT_EQ(l.coords[size_t(n)], g.coords[size_t(d.global_node[size_t(n)])]);
      EXPECT_EQ(d.localNode(d.global_node[size_t(n)]), n);
    }

    // shared nodes: exactly the local nodes with several holders, with those holders
    std::vector<Index> expected;
    for (Index n : d.global_node)
      if (holders[size_t(n)].size() > 1)
        expected.push_back(n);
    EXPECT_EQ(d.shared.global, expected) << c.name;
    ASSERT_EQ(d.shared.rank_offsets.size(), d.shared.global.size() + 1);
    for (Index s = 0; s < d.shared.size(); ++s)
    {
      EXPECT_EQ(d.global_node[size_t(d.shared.local[size_t(s)])], d.shared.global[size_t(s)]);
      const std::vector<int> ranks(d.shared.ranks.begin() + d.shared.rank_offsets[size_t(s)],
                                   d.shared.ranks.begin() + d.shared.rank_offsets[size_t(s) + 1]);
      const std::set<int> &h = holders[size_t(d.shared.global[size_t(s)])];
      EXPECT_EQ(ranks, std::vector<int>(h.begin(), h.end()));
    }
    // one owner per node
    std::vector<int> owner_count(size_t(g.numNodes()), 0);
    const std::vector<char> owned = ownedNodes(d);
    for (Index n = 0; n < l.numNodes(); ++n)
      owner_count[size_t(d.global_node[size_t(n)])] += owned[size_t(n)];
    owner_count = sumOverRanks(owner_count);
    for (size_t n = 0; n < holders.size(); ++n)
      EXPECT_EQ(owner_count[n], holders[n].empty() ? 0 : 1) << c.name << " node " << n;

    long long shared_total = allReduceSum((long long)d.shared.size());
    if (mpiSize() == 1)
      EXPECT_EQ(shared_total, 0);
    else
      EXPECT_GT(shared_total, 0) << c.name;

    // sets: node sets restricted to local nodes (union = global set), face sets split exactly,
    // and the same for the external faces through localFaces
    for (const auto &set : g.node_sets)
    {
      std::vector<int> mark(size_t(g.numNodes()), 0);
      for (Index n : l.node_sets.at(set.first))
        mark[size_t(d.global_node[size_t(n)])] = 1;
      MPI_Allreduce(MPI_IN_PLACE, mark.data(), int(mark.size()), MPI_INT, MPI_MAX, MPI_COMM_WORLD);
      std::vector<int> expected_mark(mark.size(), 0);
      for (Index n : set.second)
        expected_mark[size_t(n)] = 1;
      EXPECT_EQ(mark, expected_mark) << c.name << " node set " << set.first;
    }
    const std::vector<HostFace> gfaces = extractExternalFaces(g);
    std::vector<std::pair<std::string, std::vector<HostFace>>> face_lists(g.face_sets.begin(),
                                                                          g.face_sets.end());
    face_lists.push_back({"<external>", gfaces});
    for (const auto &set : face_lists)
    {
      const std::vector<HostFace> local =
          set.first == "<external>" ? localFaces(gfaces, d) : l.face_sets.at(set.first);
      EXPECT_EQ(allReduceSum((long long)local.size()), (long long)set.second.size()) << set.first;
      for (const HostFace &f : local)
      {
        const Index ge = d.global_element[size_t(f.element)];
        // the global face of that element and local face, renumbered
        auto it = std::find_if(set.second.begin(), set.second.end(), [&](const HostFace &h) {
          return h.element == ge && h.local_face == f.local_face;
        });
        if (it == set.second.end())
        {
          ADD_FAILURE() << c.name << ": local face of element " << ge << " not in " << set.first;
          continue;
        }
        for (int i = 0; i < f.num_nodes; ++i)
          EXPECT_EQ(d.global_node[size_t(f.nodes[size_t(i)])], it->nodes[size_t(i)]);
      }
    }
  }
}

} // namespace scpdyn::test
