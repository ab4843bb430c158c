// Ghost contact faces (steps 4 and 8): every remote face near a local face arrives, the rule is
// symmetric, and the owner -> ghost copy gives the owner's bits.
#include "ParallelTestUtil.hpp"

#include "parallel/GhostFaces.hpp"
#include "parallel/LocalDomain.hpp"
#include "parallel/Partitioner.hpp"

#include <algorithm>
#include <cmath>
#include <set>

using namespace scpdyn;
using namespace scpdyn::test;

namespace
{

std::array<Real, 3> centroid(const HostMesh &m, const HostFace &f)
{
  std::array<Real, 3> c = {0, 0, 0};
  for (int a = 0; a < f.num_nodes; ++a)
    for (int d = 0; d < 3; ++d)
      c[size_t(d)] += m.coords[size_t(f.nodes[size_t(a)])][size_t(d)] / f.num_nodes;
  return c;
}

Real distance(const std::array<Real, 3> &a, const std::array<Real, 3> &b)
{
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                   (a[2] - b[2]) * (a[2] - b[2]));
}

struct WallCase
{
  const char *name;
  HostMesh mesh;
  int dim;
  Real bin;
};

std::vector<WallCase> wallCases()
{
  std::vector<WallCase> cases;
  cases.push_back({"2D running bond", HostMesh(), 2, 0.25});
  appendBrickWall(cases.back().mesh, "w", ElementType::Quad4, {4, 2, 1}, {0, 0, 0}, {0.4, 0.1, 1},
                  {4, 5, 1}, 0.5);
  cases.push_back({"3D stack", HostMesh(), 3, 0.3});
  appendBrickWall(cases.back().mesh, "w", ElementType::Hex8, {3, 2, 2}, {0, 0, 0}, {0.3, 0.2, 0.2},
                  {3, 3, 2}, 0.0);
  return cases;
}

} // namespace

// Every face of another rank whose centroid is within one bin edge of a local face's centroid
// must arrive (the bins' 3^d stencil guarantees it; the common-plane search needs exactly these
// pairs), each ghost face exactly once, and ghost-node coordinates copied bitwise.
TEST(GhostFaces, NearFacesArriveOnceAndCopiesAreExact)
{
  const int size = mpiSize(), rank = mpiRank();
  for (WallCase &c : wallCases())
  {
    const std::vector<HostFace> faces = extractExternalFaces(c.mesh);
    PartitionOptions o;
    o.joint_weight = 0; // cut many joints: many cross-rank face pairs
    const std::vector<int> er = partitionElements(c.mesh, faces, size, o);
    const LocalDomain d = buildLocalDomain(c.mesh, er, rank);
    const std::vector<HostFace> local = localFaces(faces, d);

    std::vector<GhostFaceDesc> desc;
    std::vector<std::array<Real, 3>> cen;
    for (const HostFace &f : local)
    {
      GhostFaceDesc g;
      g.key = long(d.global_element[size_t(f.element)]) * 8 + f.local_face;
      g.part = f.part;
      g.surface = 0;
      g.num_nodes = f.num_nodes;
      g.mass = 0.5 + g.key;
      for (int a = 0; a < f.num_nodes; ++a)
        g.nodes[a] = f.nodes[size_t(a)];
      desc.push_back(g);
      cen.push_back(centroid(d.mesh, f));
    }
    std::vector<Real> mass;
    std::vector<std::array<int, 3>> bc;
    for (Index n = 0; n < d.mesh.numNodes(); ++n)
    {
      mass.push_back(1.0 + d.global_node[size_t(n)]);
      bc.push_back({int(d.global_node[size_t(n)] % 3) - 1, -1, 0});
    }
    GhostFaces gf(MPI_COMM_WORLD, d.global_node, mass, bc);
    gf.rebuild(desc, cen, c.bin, c.dim);

    // expected: remote faces near any local face (brute force over the global faces)
    std::set<long> expected, got;
    for (const HostFace &g : faces)
    {
      if (er[size_t(g.element)] == rank)
        continue;
      const auto cg = centroid(c.mesh, g);
      for (const HostFace &f : faces)
        if (er[size_t(f.element)] == rank && distance(centroid(c.mesh, f), cg) <= c.bin)
        {
          expected.insert(long(g.element) * 8 + g.local_face);
          break;
        }
    }
    long duplicates = 0, bad_mass = 0;
    for (const GhostFaceDesc &g : gf.faces())
    {
      duplicates += got.count(g.key) ? 1 : 0;
      got.insert(g.key);
      bad_mass += g.mass == 0.5 + g.key ? 0 : 1;
    }
    long missing = 0;
    for (long k : expected)
      missing += got.count(k) ? 0 : 1;
    EXPECT_EQ(missing, 0) << c.name << " rank " << rank;
    EXPECT_EQ(duplicates, 0) << c.name;
    EXPECT_EQ(bad_mass, 0) << c.name;
    if (size == 1)
      EXPECT_TRUE(gf.faces().empty());

    // step 8: coordinates of every ghost-face node, bitwise the global mesh's
    const Index nl = gf.numLocalNodes(), ng = gf.numGhostNodes();
    VectorView x("x", size_t(nl + ng));
    auto hx = Kokkos::create_mirror_view(x);
    for (Index n = 0; n < nl; ++n)
      for (int k = 0; k < 3; ++k)
        hx(n, k) = d.mesh.coords[size_t(n)][size_t(k)];
    for (Index n = nl; n < nl + ng; ++n)
      for (int k = 0; k < 3; ++k)
        hx(n, k) = -1e30;
    Kokkos::deep_copy(x, hx);
    gf.gather(&x, 1);
    Kokkos::deep_copy(hx, x);
    long wrong = 0;
    for (Index i = 0; i < ng; ++i)
    {
      const Index id = gf.ghostGlobal()[size_t(i)];
      for (int k = 0; k < 3; ++k)
        wrong += bits(hx(nl + i, k)) == bits(c.mesh.coords[size_t(id)][size_t(k)]) ? 0 : 1;
      wrong += gf.ghostMass()[size_t(i)] == 1.0 + id ? 0 : 1;
      wrong += gf.ghostBc()[size_t(i)][0] == int(id % 3) - 1 ? 0 : 1;
    }
    EXPECT_EQ(wrong, 0) << c.name;
    // ghost faces reference the right global nodes (local ids for the nodes held here)
    long wrong_nodes = 0;
    for (const GhostFaceDesc &g : gf.faces())
    {
      const HostFace *src = nullptr;
      for (const HostFace &f : faces)
        if (long(f.element) * 8 + f.local_face == g.key)
          src = &f;
      for (int a = 0; src && a < g.num_nodes; ++a)
      {
        const Index k = g.nodes[a];
        const Index id = k < nl ? d.global_node[size_t(k)] : gf.ghostGlobal()[size_t(k - nl)];
        wrong_nodes += id == src->nodes[size_t(a)] ? 0 : 1;
      }
      wrong_nodes += src ? 0 : 1;
    }
    EXPECT_EQ(wrong_nodes, 0) << c.name;
    // per-face values (the element density of the explicit time step) arrive by key
    std::vector<Real> local_value, ghost_value;
    for (const GhostFaceDesc &g : desc)
      local_value.push_back(0.25 * g.key);
    gf.gatherFaces(local_value, ghost_value);
    long wrong_faces = 0;
    for (size_t k = 0; k < gf.faces().size(); ++k)
      wrong_faces += ghost_value[k] == 0.25 * gf.faces()[k].key ? 0 : 1;
    EXPECT_EQ(wrong_faces, 0) << c.name;
    const long total = allReduceSum((long long)gf.faces().size());
    SCPDYN_ROOT_PRINT("[ ghosts ] %s, %d ranks: %ld ghost faces, %zu bytes sent per 4-field gather "
                      "on rank 0\n",
                      c.name, size, total, size_t(gf.numSendNodes()) * 12 * sizeof(Real));
  }
}
