// External faces, node merging, selections and element checks.
#include "mesh/MeshGenerators.hpp"
#include "mesh/MeshOps.hpp"
#include "mesh/PartOverlap.hpp"

#include <gtest/gtest.h>

#include <map>

#include <cmath>

using namespace scpdyn;

namespace
{
using Vec3 = std::array<Real, 3>;

// Area-weighted outward normal of a face: 2D (t_y, -t_x); 3D half the sum of fan cross products.
Vec3 faceNormal(const HostMesh &m, const HostFace &f)
{
  auto x = [&](int i) { return m.coords[f.nodes[i]]; };
  if (f.num_nodes == 2)
    return {x(1)[1] - x(0)[1], -(x(1)[0] - x(0)[0]), 0};
  Vec3 n{0, 0, 0};
  for (int i = 1; i + 1 < f.num_nodes; ++i)
  {
    Vec3 a, b;
    for (int k = 0; k < 3; ++k)
      a[k] = x(i)[k] - x(0)[k], b[k] = x(i + 1)[k] - x(0)[k];
    n[0] += 0.5 * (a[1] * b[2] - a[2] * b[1]);
    n[1] += 0.5 * (a[2] * b[0] - a[0] * b[2]);
    n[2] += 0.5 * (a[0] * b[1] - a[1] * b[0]);
  }
  return n;
}

// Element id -> (part, local element).
std::pair<int, Index> locate(const HostMesh &m, Index e)
{
  for (int p = 0; p < int(m.parts.size()); ++p)
  {
    if (e < m.parts[p].numElements())
      return {p, e};
    e -= m.parts[p].numElements();
  }
  return {-1, -1};
}

Vec3 centroid(const HostMesh &m, const Index *n, int count)
{
  Vec3 c{0, 0, 0};
  for (int i = 0; i < count; ++i)
    for (int k = 0; k < 3; ++k)
      c[k] += m.coords[n[i]][k] / count;
  return c;
}

// Every face normal points away from its element's centroid, and the area vectors of a
// closed surface sum to zero (1e-13 of the size: round-off of a few hundred O(1) terms).
void expectOutward(const HostMesh &m, const std::vector<HostFace> &faces, Real scale)
{
  Vec3 sum{0, 0, 0};
  for (const auto &f : faces)
  {
    const auto pe = locate(m, f.element);
    ASSERT_EQ(pe.first, f.part);
    const HostPart &p = m.parts[pe.first];
    const int npe = nodesPerElement(p.type);
    const Vec3 ce = centroid(m, &p.connectivity[size_t(pe.second) * npe], npe);
    const Vec3 cf = centroid(m, f.nodes.data(), f.num_nodes);
    Vec3 n = faceNormal(m, f);
    if (m.dim == 1) // a point face: its normal is -x at the left end, +x at the right
      n = {f.local_face == 0 ? -1.0 : 1.0, 0, 0};
    EXPECT_GT((cf[0] - ce[0]) * n[0] + (cf[1] - ce[1]) * n[1] + (cf[2] - ce[2]) * n[2], 0);
    for (int k = 0; k < 3; ++k)
      sum[k] += n[k];
  }
  if (m.dim >= 2)
  {
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(sum[k], 0, 1e-13 * scale);
  }
}
} // namespace

TEST(MeshOps, ExternalFacesOfBoxes)
{
  const int nx = 4, ny = 3, nz = 2;
  struct Case
  {
    ElementType type;
    size_t faces;
  } cases[] = {{ElementType::Line2, 2},
               {ElementType::Quad4, size_t(2 * (nx + ny))},
               {ElementType::Hex8, size_t(2 * (nx * ny + ny * nz + nz * nx))},
               {ElementType::Tet4, size_t(4 * (nx * ny + ny * nz + nz * nx))}};
  for (const auto &c : cases)
  {
    HostMesh m;
    appendBlock(m, "b", c.type, {{nx, ny, nz}}, {{0.5, 0.25, -1}}, {{2, 1.5, 1}});
    const auto faces = extractExternalFaces(m);
    EXPECT_EQ(faces.size(), c.faces);
    for (size_t i = 1; i < faces.size(); ++i) // sorted by element, then local face
      EXPECT_TRUE(faces[i - 1].element < faces[i].element ||
                  (faces[i - 1].element == faces[i].element &&
                   faces[i - 1].local_face < faces[i].local_face));
    for (const auto &f : faces)
      EXPECT_EQ(f.num_nodes, nodesPerFace(c.type));
    expectOutward(m, faces, 2.0);
  }
}

TEST(MeshOps, FacesBetweenPartsAreExternalUnlessTheirNodesAreMerged)
{
  auto twoCubes = [](bool merged) {
    HostMesh m;
    appendBlock(m, "a", ElementType::Hex8, {{2, 2, 2}}, {{0, 0, 0}}, {{1, 1, 1}});
    appendBlock(m, "b", ElementType::Hex8, {{2, 2, 2}}, {{1, 0, 0}}, {{1, 1, 1}});
    if (merged)
      mergeCoincidentNodes(m, {0, 1}, 1e-9);
    return m;
  };
  // separate bodies: the 4 faces of each part on the interface x = 1 are external for both
  const HostMesh apart = twoCubes(false);
  const auto faces = extractExternalFaces(apart);
  EXPECT_EQ(faces.size(), 2u * 24);
  EXPECT_EQ(facesOfParts(faces, {1}).size(), 24u);
  EXPECT_EQ(faces.back().element, 15); // global numbering continues across parts
  expectOutward(apart, faces, 1.0);
  EXPECT_EQ(facesInBox(faces, apart, {{1, 0, 0}}, {{1, 1, 1}}, 1e-12).size(), 8u);
  // one body: the interface is inside it, its 8 faces are not external; the surface is closed
  const HostMesh joined = twoCubes(true);
  const auto outer = extractExternalFaces(joined);
  EXPECT_EQ(outer.size(), 2u * 24 - 8);
  EXPECT_EQ(facesOfParts(outer, {1}).size(), 20u);
  EXPECT_TRUE(facesInBox(outer, joined, {{1, 0, 0}}, {{1, 1, 1}}, 1e-12).empty());
  expectOutward(joined, outer, 2.0);
}

// The faces erosion can expose (docs/theory.md 11.6): every face two elements of a selected
// part share, once per element, with the other element as its twin; none of an unselected part.
TEST(MeshOps, InteriorFacesComeInTwinPairsOfSelectedParts)
{
  HostMesh m;
  appendBlock(m, "a", ElementType::Hex8, {{3, 2, 2}}, {{0, 0, 0}}, {{3, 2, 2}});
  appendBlock(m, "b", ElementType::Hex8, {{2, 2, 2}}, {{5, 0, 0}}, {{2, 2, 2}});
  const auto faces = interiorFaces(m, {1, 0});
  // 3 x 2 x 2 hexes share 2*2*2 + 3*1*2 + 3*2*1 = 20 faces, each seen from both sides
  ASSERT_EQ(faces.size(), 40u);
  std::map<std::pair<Index, Index>, int> seen;
  for (const HostFace &f : faces)
  {
    EXPECT_EQ(f.part, 0);
    ASSERT_GE(f.twin, 0);
    EXPECT_NE(f.twin, f.element);
    ++seen[{std::min(f.element, f.twin), std::max(f.element, f.twin)}];
  }
  EXPECT_EQ(seen.size(), 20u);
  for (const auto &kv : seen)
    EXPECT_EQ(kv.second, 2); // once from each element
  EXPECT_TRUE(interiorFaces(m, {0, 0}).empty());
  for (const HostFace &f : extractExternalFaces(m))
    EXPECT_EQ(f.twin, -1);

  // a part merged to a selected one: the faces between them are interior from both sides, so
  // erosion on either side exposes the face of the other
  HostMesh j;
  appendBlock(j, "a", ElementType::Hex8, {{1, 2, 2}}, {{0, 0, 0}}, {{1, 2, 2}});
  appendBlock(j, "b", ElementType::Hex8, {{1, 2, 2}}, {{1, 0, 0}}, {{1, 2, 2}});
  mergeCoincidentNodes(j, {0, 1}, 1e-9);
  const auto joined = interiorFaces(j, {1, 0});
  // 1 x 2 x 2 hexes share 4 faces in a, and the parts share the 4 faces at x = 1; the faces
  // inside b (not selected) are not listed
  ASSERT_EQ(joined.size(), 2u * (4 + 4));
  int across = 0;
  for (const HostFace &f : joined)
  {
    across += (f.element < 4) != (f.twin < 4) ? 1 : 0;
    EXPECT_TRUE(f.element < 4 || f.twin < 4) << f.element << " " << f.twin;
  }
  EXPECT_EQ(across, 8);
}

TEST(MeshOps, MergeRemovesExactlyTheInterfaceNodes)
{
  HostMesh m;
  appendBlock(m, "a", ElementType::Quad4, {{3, 5, 1}}, {{0, 0, 0}}, {{1, 1, 0}});
  appendBlock(m, "b", ElementType::Quad4, {{2, 5, 1}}, {{1, 0, 0}}, {{0.5, 1, 0}});
  appendBlock(m, "c", ElementType::Quad4, {{2, 2, 1}}, {{1.5, 0, 0}}, {{1, 1, 0}}); // not listed
  const Index before = m.numNodes();
  m.node_sets["right_of_a"] = nodesInBox(m, {{1, 0, 0}}, {{1, 1, 0}}, 1e-12);
  ASSERT_EQ(m.node_sets["right_of_a"].size(), 12u); // 6 of a + 6 of b
  m.face_sets["top"] = facesInBox(extractExternalFaces(m), m, {{0, 1, 0}}, {{2.5, 1, 0}}, 1e-12);
  mergeCoincidentNodes(m, {0, 1}, 1e-9);
  EXPECT_EQ(m.numNodes(), before - 6); // the 6 nodes on x = 1; part c keeps its copies at 1.5
  EXPECT_EQ(m.node_sets["right_of_a"].size(), 6u);
  EXPECT_NO_THROW(checkElements(m));
  // a and b share the 5 faces of x = 1 (now inside one body); c keeps all its faces
  EXPECT_EQ(extractExternalFaces(m).size(), size_t(2 * 8 + 2 * 7 + 2 * 4 - 2 * 5));
  for (const auto &f : m.face_sets["top"])
    for (int i = 0; i < 2; ++i)
      EXPECT_EQ(m.coords[f.nodes[i]][1], 1.0); // face-set node ids were renumbered
  EXPECT_NEAR(meshMeasure(m, 0) + meshMeasure(m, 1), 1.5, 1e-14);
}

TEST(MeshOps, MergedBrickWallHasTheMonolithicNodes)
{
  // T6d wall (200 x 80 mm, h = 2.5 mm): merging every brick must give exactly the node grid of
  // the monolithic 80 x 32 cell twin, i.e. brick nodes coincide across every joint.
  HostMesh m;
  appendBrickWall(m, "wall", ElementType::Quad4, {{10, 4, 1}}, {{0, 0, 0}}, {{0.025, 0.010, 0}},
                  {{8, 8, 1}}, 0.5);
  std::vector<int> all(m.parts.size());
  for (size_t p = 0; p < all.size(); ++p)
    all[p] = int(p);
  mergeCoincidentNodes(m, all, 1e-6 * 0.0025); // round-off is ~1e-17 m, h is 2.5e-3 m
  EXPECT_EQ(m.numNodes(), 81 * 33);
  EXPECT_NO_THROW(checkElements(m));
}

TEST(MeshOps, MergeHonoursTolerance)
{
  auto twoBlocks = [](Real gap) {
    HostMesh m;
    appendBlock(m, "a", ElementType::Hex8, {{2, 3, 2}}, {{0, 0, 0}}, {{1, 1, 1}});
    appendBlock(m, "b", ElementType::Hex8, {{2, 3, 2}}, {{1 + gap, 0, 0}}, {{1, 1, 1}});
    return m;
  };
  HostMesh far = twoBlocks(1e-3), near = twoBlocks(1e-3);
  const Index n = far.numNodes();
  mergeCoincidentNodes(far, {0, 1}, 1e-4);
  EXPECT_EQ(far.numNodes(), n);
  mergeCoincidentNodes(near, {0, 1}, 2e-3);
  EXPECT_EQ(near.numNodes(), n - 4 * 3); // interface has 4 x 3 nodes
  // lowest id kept: the interface nodes keep part a's coordinates (x = 1, not 1.001)
  for (Index v : nodesOfParts(near, {1}))
    EXPECT_TRUE(near.coords[v][0] == 1.0 || near.coords[v][0] > 1.4);
}

TEST(MeshOps, SelectionsByBoxAndPart)
{
  HostMesh m;
  appendBlock(m, "a", ElementType::Quad4, {{4, 2, 1}}, {{0, 0, 0}}, {{2, 1, 0}});
  appendBlock(m, "b", ElementType::Quad4, {{1, 1, 1}}, {{5, 5, 0}}, {{1, 1, 0}});
  EXPECT_EQ(nodesInBox(m, {{0, 0, 0}}, {{0, 1, 0}}, 1e-12).size(), 3u);
  EXPECT_EQ(nodesOfParts(m, {1}), (std::vector<Index>{15, 16, 17, 18}));
  EXPECT_EQ(nodesOfParts(m, {0, 1}).size(), 19u);
  EXPECT_THROW(nodesOfParts(m, {2}), std::runtime_error);
  const auto ext = extractExternalFaces(m);
  EXPECT_EQ(facesOfParts(ext, {0}).size(), 12u);
  const auto bottom = facesInBox(ext, m, {{0, 0, 0}}, {{2, 0, 0}}, 1e-12);
  ASSERT_EQ(bottom.size(), 4u);
  for (const auto &f : bottom)
    EXPECT_EQ(f.local_face, 0); // Quad4 face 0 is the -y side
}

TEST(MeshOps, CheckElementsCatchesBadElements)
{
  auto expectMessage = [](const HostMesh &m, const std::string &what) {
    try
    {
      checkElements(m);
      ADD_FAILURE() << "no exception, expected: " << what;
    }
    catch (const std::runtime_error &e)
    {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  HostMesh q;
  appendBlock(q, "quads", ElementType::Quad4, {{2, 2, 1}}, {{0, 0, 0}}, {{1, 1, 0}});
  std::swap(q.parts[0].connectivity[4 * 3 + 1], q.parts[0].connectivity[4 * 3 + 3]); // clockwise
  expectMessage(q, "part 'quads', element 3");

  HostMesh bow; // a bow-tie has positive total area at some corners only
  appendBlock(bow, "bow", ElementType::Quad4, {{1, 1, 1}}, {{0, 0, 0}}, {{1, 1, 0}});
  std::swap(bow.parts[0].connectivity[2], bow.parts[0].connectivity[3]);
  expectMessage(bow, "part 'bow', element 0");

  HostMesh flat; // three collinear corners: zero corner area
  appendBlock(flat, "flat", ElementType::Quad4, {{1, 1, 1}}, {{0, 0, 0}}, {{1, 1, 0}});
  flat.coords[flat.parts[0].connectivity[2]] = {0.5, 0.5, 0};
  expectMessage(flat, "degenerate");

  HostMesh h;
  appendBlock(h, "hexes", ElementType::Hex8, {{2, 1, 1}}, {{0, 0, 0}}, {{1, 1, 1}});
  auto &c = h.parts[0].connectivity;
  for (int i = 0; i < 4; ++i) // element 1 upside down
    std::swap(c[8 + i], c[8 + 4 + i]);
  expectMessage(h, "part 'hexes', element 1");

  HostMesh t;
  appendBlock(t, "tets", ElementType::Tet4, {{1, 1, 1}}, {{0, 0, 0}}, {{1, 1, 1}});
  std::swap(t.parts[0].connectivity[4 * 5 + 1], t.parts[0].connectivity[4 * 5 + 2]);
  expectMessage(t, "part 'tets', element 5");

  HostMesh l;
  appendBlock(l, "bar", ElementType::Line2, {{3, 1, 1}}, {{0, 0, 0}}, {{1, 0, 0}});
  std::swap(l.parts[0].connectivity[2], l.parts[0].connectivity[3]);
  expectMessage(l, "part 'bar', element 1");

  HostMesh e;
  appendBlock(e, "ok", ElementType::Quad4, {{1, 1, 1}}, {{0, 0, 0}}, {{1, 1, 0}});
  e.parts.push_back(HostPart{});
  e.parts.back().name = "hollow";
  expectMessage(e, "part 'hollow' has no elements");
}

TEST(MeshOps, MeasureOfDistortedHexIsExact)
{
  // Unit cube sheared by 0.3 in x with top corner 6 lifted by 0.4: x = xi + 0.3 zeta, y = eta,
  // z = zeta (1 + 0.4 xi eta), so det J = 1 + 0.4 xi eta - 0.12 eta zeta, whose integral over
  // the unit cube is 1 + 0.1 - 0.03 = 1.07. 2x2x2 Gauss is exact for it (round-off only).
  HostMesh m;
  appendBlock(m, "h", ElementType::Hex8, {{1, 1, 1}}, {{0, 0, 0}}, {{1, 1, 1}});
  for (int i = 4; i < 8; ++i)
    m.coords[m.parts[0].connectivity[i]][0] += 0.3;
  m.coords[m.parts[0].connectivity[6]][2] += 0.4;
  EXPECT_NEAR(meshMeasure(m, 0), 1.07, 1e-14);
}

// Parts that overlap at t = 0 are found (and only they): a block pushed 3 mm into another, in
// 2D and 3D; a brick wall and blocks that only touch give none.
TEST(PartOverlap, FindsOverlappingPartsOnly)
{
  for (const ElementType t : {ElementType::Quad4, ElementType::Hex8, ElementType::Tet4})
  {
    SCOPED_TRACE(int(t));
    const bool is3d = t != ElementType::Quad4;
    const std::array<int, 3> cells =
        is3d ? std::array<int, 3>{{4, 4, 4}} : std::array<int, 3>{{4, 4, 1}};
    const std::array<Real, 3> size = {0.01, 0.01, is3d ? 0.01 : 0};
    HostMesh touching, overlapping;
    appendBlock(touching, "a", t, cells, {0, 0, 0}, size);
    appendBlock(touching, "b", t, cells, {0.01, 0, 0}, size);
    EXPECT_TRUE(overlappingParts(touching).empty());
    appendBlock(overlapping, "a", t, cells, {0, 0, 0}, size);
    appendBlock(overlapping, "b", t, cells, {0.007, 0, 0}, size);
    const std::vector<PartOverlap> o = overlappingParts(overlapping);
    ASSERT_EQ(o.size(), 2u); // each part's centroids in the other
    EXPECT_GT(o[0].count, 0);
  }
  HostMesh wall;
  appendBrickWall(wall, "w", ElementType::Quad4, {2, 1, 1}, {0, 0, 0}, {0.2, 0.1, 0}, {3, 3, 1},
                  0.5);
  EXPECT_TRUE(overlappingParts(wall).empty());
}
