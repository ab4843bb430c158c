// Structured blocks and brick walls: counts, measures, orientation and conformity.
#include "mesh/MeshGenerators.hpp"
#include "mesh/MeshOps.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

using namespace scpdyn;

namespace
{
// Sums of a few hundred positive terms of similar size: round-off stays near 1e-14 relative.
constexpr Real kMeasureTol = 1e-12;

struct BlockCase
{
  ElementType type;
  std::array<int, 3> cells;
  Index elements, nodes;
  Real measure;
};
} // namespace

TEST(MeshGenerators, BlockCountsMeasuresAndValidity)
{
  const std::array<Real, 3> o{{0.1, -0.2, 0.3}}, s{{1.3, 0.7, 0.45}};
  const BlockCase cases[] = {
      {ElementType::Line2, {{7, 1, 1}}, 7, 8, 1.3},
      {ElementType::Quad4, {{5, 3, 1}}, 15, 24, 1.3 * 0.7},
      {ElementType::Hex8, {{4, 3, 2}}, 24, 60, 1.3 * 0.7 * 0.45},
      {ElementType::Tet4, {{3, 2, 2}}, 72, 36, 1.3 * 0.7 * 0.45},
  };
  for (const auto &c : cases)
  {
    HostMesh m;
    appendBlock(m, "b", c.type, c.cells, o, s);
    EXPECT_EQ(m.dim, dimensionOf(c.type));
    EXPECT_EQ(m.numElements(), c.elements);
    EXPECT_EQ(m.numNodes(), c.nodes);
    EXPECT_NEAR(meshMeasure(m, 0), c.measure, kMeasureTol * c.measure);
    EXPECT_NO_THROW(checkElements(m));
    // unused coordinates stay zero
    for (const auto &x : m.coords)
      for (int d = m.dim; d < 3; ++d)
        EXPECT_EQ(x[d], 0.0);
  }
}

TEST(MeshGenerators, NodeOrderingConventions)
{
  HostMesh q;
  appendBlock(q, "q", ElementType::Quad4, {{2, 2, 1}}, {{0, 0, 0}}, {{2, 2, 0}});
  // first element is the unit square at the origin: CCW from (-,-)
  const Real expect_q[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int i = 0; i < 4; ++i)
    for (int d = 0; d < 2; ++d)
      EXPECT_DOUBLE_EQ(q.coords[q.parts[0].connectivity[i]][d], expect_q[i][d]);

  HostMesh h;
  appendBlock(h, "h", ElementType::Hex8, {{1, 1, 1}}, {{0, 0, 0}}, {{1, 1, 1}});
  const Real expect_h[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                               {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (int i = 0; i < 8; ++i)
    for (int d = 0; d < 3; ++d)
      EXPECT_DOUBLE_EQ(h.coords[h.parts[0].connectivity[i]][d], expect_h[i][d]);

  HostMesh l;
  appendBlock(l, "l", ElementType::Line2, {{3, 1, 1}}, {{-1, 0, 0}}, {{3, 0, 0}});
  for (Index e = 0; e < 3; ++e)
    EXPECT_LT(l.coords[l.parts[0].connectivity[2 * e]][0],
              l.coords[l.parts[0].connectivity[2 * e + 1]][0]);
}

TEST(MeshGenerators, TetSplitIsConformingAndPositive)
{
  const int nx = 3, ny = 2, nz = 4;
  HostMesh m;
  appendBlock(m, "t", ElementType::Tet4, {{nx, ny, nz}}, {{0, 0, 0}}, {{1, 1, 1}});
  const auto &c = m.parts[0].connectivity;
  std::map<std::array<Index, 3>, int> count;
  for (Index e = 0; e < m.numElements(); ++e)
    for (int f = 0; f < 4; ++f)
    {
      std::array<Index, 3> k;
      for (int i = 0; i < 3; ++i)
        k[i] = c[4 * e + kTet4Faces[f][i]];
      std::sort(k.begin(), k.end());
      ++count[k];
    }
  int boundary = 0;
  for (const auto &kv : count)
  {
    ASSERT_LE(kv.second, 2);
    if (kv.second == 2)
      continue;
    ++boundary;
    // a face seen once must lie on the box surface, else the split does not conform
    bool onPlane = false;
    for (int d = 0; d < 3; ++d)
      for (Real v : {0.0, 1.0})
        onPlane = onPlane || std::all_of(kv.first.begin(), kv.first.end(),
                                         [&](Index n) { return m.coords[n][d] == v; });
    EXPECT_TRUE(onPlane);
  }
  EXPECT_EQ(boundary, 4 * (nx * ny + ny * nz + nz * nx)); // 2 triangles per boundary quad
  for (Index e = 0; e < m.numElements(); ++e)
  {
    auto x = [&](int i) { return m.coords[c[4 * e + i]]; };
    Real a[3], b[3], d[3];
    for (int k = 0; k < 3; ++k)
      a[k] = x(1)[k] - x(0)[k], b[k] = x(2)[k] - x(0)[k], d[k] = x(3)[k] - x(0)[k];
    const Real triple = (a[1] * b[2] - a[2] * b[1]) * d[0] + (a[2] * b[0] - a[0] * b[2]) * d[1] +
                        (a[0] * b[1] - a[1] * b[0]) * d[2];
    // every Kuhn tet has 1/6 of its cell: 6 V = cell volume exactly (cell edges are exact)
    EXPECT_NEAR(triple, 1.0 / (nx * ny * nz), 1e-14);
  }
}

TEST(MeshGenerators, DimensionMismatchAndBadInputThrow)
{
  HostMesh m;
  appendBlock(m, "a", ElementType::Quad4, {{2, 2, 1}}, {{0, 0, 0}}, {{1, 1, 0}});
  EXPECT_THROW(appendBlock(m, "b", ElementType::Hex8, {{1, 1, 1}}, {{0, 0, 0}}, {{1, 1, 1}}),
               std::runtime_error);
  EXPECT_THROW(appendBlock(m, "c", ElementType::Quad4, {{0, 2, 1}}, {{0, 0, 0}}, {{1, 1, 0}}),
               std::runtime_error);
  EXPECT_THROW(appendBrickWall(m, "w", ElementType::Quad4, {{2, 2, 1}}, {{0, 0, 0}}, {{1, 1, 0}},
                               {{2, 2, 1}}, 1.0),
               std::runtime_error);
  EXPECT_EQ(m.parts.size(), 1u); // failed calls add nothing
}

// verification.md T6d: 200 x 80 mm wall, 8 courses of 25 x 10 mm bricks, half-brick offset,
// h = 2.5 mm.
TEST(MeshGenerators, BrickWallT6d)
{
  HostMesh m;
  appendBrickWall(m, "wall", ElementType::Quad4, {{10, 4, 1}}, {{0, 0, 0}}, {{0.025, 0.010, 0}},
                  {{8, 8, 1}}, 0.5);
  ASSERT_EQ(m.parts.size(), 4u * 8 + 4u * 9);
  std::map<int, int> perCourse;
  Real area = 0;
  for (int p = 0; p < int(m.parts.size()); ++p)
  {
    const std::string &name = m.parts[p].name;
    ASSERT_EQ(name.rfind("wall.", 0), 0u);
    const int course = std::stoi(name.substr(5, name.find('.', 5) - 5));
    ++perCourse[course];
    area += meshMeasure(m, p);
    // full bricks 10 x 4 cells, half bricks 5 x 4
    const Index ne = m.parts[p].numElements();
    EXPECT_TRUE(ne == 40 || (ne == 20 && course % 2 == 1)) << name;
  }
  ASSERT_EQ(perCourse.size(), 8u);
  for (const auto &kv : perCourse)
    EXPECT_EQ(kv.second, kv.first % 2 ? 9 : 8) << "course " << kv.first;
  EXPECT_NEAR(area, 0.2 * 0.08, kMeasureTol * 0.016);
  EXPECT_EQ(m.numElements(), 80 * 32); // same h as the 200 x 80 mm monolithic twin
  Real xmax = 0, ymax = 0;
  for (const auto &x : m.coords)
    xmax = std::max(xmax, x[0]), ymax = std::max(ymax, x[1]);
  EXPECT_NEAR(xmax, 0.2, 1e-15);
  EXPECT_NEAR(ymax, 0.08, 1e-15);
  EXPECT_NO_THROW(checkElements(m));
  EXPECT_EQ(m.parts[8].name, "wall.1.0"); // odd course starts with the half brick
  EXPECT_NEAR(meshMeasure(m, 8), 0.0125 * 0.010, 1e-12 * 1.25e-4);
}

TEST(MeshGenerators, BrickWallStackBondAnd3D)
{
  HostMesh s;
  appendBrickWall(s, "s", ElementType::Quad4, {{2, 1, 1}}, {{0, 0, 0}}, {{1, 0.5, 0}}, {{3, 4, 1}},
                  0.0);
  EXPECT_EQ(s.parts.size(), 12u);

  HostMesh h;
  // count: 2 along x, 3 along y, 3 courses along z; odd course: 3 per row, 9 in all
  appendBrickWall(h, "h", ElementType::Hex8, {{4, 2, 2}}, {{1, 2, 3}}, {{0.2, 0.1, 0.05}},
                  {{2, 3, 3}}, 0.25);
  EXPECT_EQ(h.parts.size(), 6u + 9u + 6u);
  EXPECT_EQ(h.parts[6].name, "h.1.0");
  EXPECT_EQ(h.parts[6].numElements(), 1 * 2 * 2); // round(4 * 0.25) cells along x
  EXPECT_EQ(h.parts[8].numElements(), 3 * 2 * 2); // round(4 * 0.75)
  Real vol = 0;
  for (int p = 0; p < int(h.parts.size()); ++p)
    vol += meshMeasure(h, p);
  EXPECT_NEAR(vol, 0.4 * 0.3 * 0.15, kMeasureTol * 0.018);
  EXPECT_NO_THROW(checkElements(h));

  // 1D: one course of line2 blocks (the jointed bar), each its own part, blocks touching
  HostMesh b;
  appendBrickWall(b, "b", ElementType::Line2, {{3, 1, 1}}, {{0.5, 0, 0}}, {{0.001, 0, 0}},
                  {{4, 1, 1}}, 0.5);
  ASSERT_EQ(b.parts.size(), 4u);
  EXPECT_EQ(b.dim, 1);
  EXPECT_EQ(b.numElements(), 12);
  EXPECT_EQ(b.parts[3].name, "b.0.3");
  EXPECT_DOUBLE_EQ(b.coords.back()[0], 0.5 + 4 * 0.001); // the last node of the last block
  Real length = 0;
  for (int p = 0; p < int(b.parts.size()); ++p)
    length += meshMeasure(b, p);
  EXPECT_NEAR(length, 0.004, 1e-15);

  HostMesh t;
  appendBrickWall(t, "t", ElementType::Tet4, {{2, 1, 1}}, {{0, 0, 0}}, {{1, 1, 1}}, {{2, 1, 2}},
                  0.5);
  EXPECT_EQ(t.parts.size(), 2u + 3u);
  EXPECT_EQ(t.numElements(), 6 * (2 * 2 + 1 + 2 + 1));
  EXPECT_NO_THROW(checkElements(t));
}

// The paper's Fig. 3 imbricate mesh is staggered in y: columns of bricks along y, every other
// column shifted. It must be the x-staggered wall with x and y exchanged, brick for brick.
TEST(MeshGenerators, BrickWallStaggeredInYIsTheTransposedWall)
{
  HostMesh xw, yw;
  appendBrickWall(xw, "w", ElementType::Quad4, {{4, 2, 1}}, {{0, 0, 0}}, {{0.02, 0.01, 0}},
                  {{3, 4, 1}}, 0.5);
  appendBrickWall(yw, "w", ElementType::Quad4, {{2, 4, 1}}, {{0, 0, 0}}, {{0.01, 0.02, 0}},
                  {{4, 3, 1}}, 0.5, 1);
  ASSERT_EQ(yw.parts.size(), xw.parts.size());
  EXPECT_EQ(yw.parts.size(), 3u * 2 + 4u * 2); // odd columns: one brick more
  EXPECT_NO_THROW(checkElements(yw));
  for (size_t p = 0; p < xw.parts.size(); ++p)
  {
    EXPECT_EQ(yw.parts[p].name, xw.parts[p].name);
    EXPECT_EQ(yw.parts[p].numElements(), xw.parts[p].numElements()) << xw.parts[p].name;
    EXPECT_NEAR(meshMeasure(yw, int(p)), meshMeasure(xw, int(p)), 1e-18) << xw.parts[p].name;
    // the same brick: its box with x and y exchanged
    std::array<Real, 2> lo_x{{1, 1}}, lo_y{{1, 1}};
    for (Index n : xw.parts[p].connectivity)
      for (int d = 0; d < 2; ++d)
        lo_x[size_t(d)] = std::min(lo_x[size_t(d)], xw.coords[size_t(n)][size_t(d)]);
    for (Index n : yw.parts[p].connectivity)
      for (int d = 0; d < 2; ++d)
        lo_y[size_t(d)] = std::min(lo_y[size_t(d)], yw.coords[size_t(n)][size_t(d)]);
    EXPECT_NEAR(lo_y[0], lo_x[1], 1e-15) << xw.parts[p].name;
    EXPECT_NEAR(lo_y[1], lo_x[0], 1e-15) << xw.parts[p].name;
  }
  EXPECT_EQ(yw.parts[3].name, "w.1.0"); // column 1 starts with the half brick at y = 0
  EXPECT_NEAR(meshMeasure(yw, 3), 0.01 * 0.01, 1e-18);

  // 3D: courses along z stay; a course runs along y, rows along x
  HostMesh h;
  appendBrickWall(h, "h", ElementType::Hex8, {{2, 4, 2}}, {{0, 0, 0}}, {{0.1, 0.2, 0.05}},
                  {{3, 2, 2}}, 0.25, 1);
  EXPECT_EQ(h.parts.size(), 6u + 9u);
  EXPECT_EQ(h.parts[6].numElements(), 2 * 1 * 2); // round(4 * 0.25) cells along y
  Real vol = 0;
  for (int p = 0; p < int(h.parts.size()); ++p)
    vol += meshMeasure(h, p);
  EXPECT_NEAR(vol, 0.3 * 0.4 * 0.1, kMeasureTol * 0.012);
  EXPECT_NO_THROW(checkElements(h));

  HostMesh b;
  EXPECT_THROW(appendBrickWall(b, "b", ElementType::Line2, {{3, 1, 1}}, {{0, 0, 0}},
                               {{0.001, 0, 0}}, {{4, 1, 1}}, 0.5, 1),
               std::runtime_error);
}
