// The English bond of a 3D brick wall: stretcher courses of two leaves alternate with header
// courses spanning the thickness, with quarter-brick closers; the bricks fill the wall's box
// without overlap and no joint plane runs straight through two consecutive courses.
#include "mesh/MeshGenerators.hpp"
#include "mesh/MeshOps.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

using namespace scpdyn;

namespace
{
// Brick corners are sums of a few multiples of the brick size: round-off near 1e-16 m.
constexpr Real kPosTol = 1e-12;

struct Box
{
  std::array<Real, 3> lo{{1e300, 1e300, 1e300}}, hi{{-1e300, -1e300, -1e300}};
};

Box boxOf(const HostMesh &m, const HostPart &p)
{
  Box b;
  for (Index n : p.connectivity)
    for (int d = 0; d < 3; ++d)
    {
      b.lo[size_t(d)] = std::min(b.lo[size_t(d)], m.coords[size_t(n)][size_t(d)]);
      b.hi[size_t(d)] = std::max(b.hi[size_t(d)], m.coords[size_t(n)][size_t(d)]);
    }
  return b;
}

int courseOf(const std::string &name) { return std::stoi(name.substr(name.find('.') + 1)); }

// The wall: 3 bricks (0.24 m) along x, 2 leaves (0.12 m) along y, 4 courses (0.06 m) along z.
constexpr int kAlong = 3, kCourses = 4;
const std::array<Real, 3> kOrigin{{0.5, -0.1, 0.2}}, kBrick{{0.24, 0.12, 0.06}};
const std::array<Real, 3> kWall{{kAlong * 0.24, 0.24, kCourses * 0.06}};

HostMesh englishWall(std::array<int, 3> cells = {{4, 2, 1}}, int stagger_axis = 0)
{
  HostMesh m;
  appendBrickWall(m, "w", ElementType::Hex8, cells, kOrigin, kBrick, {{kAlong, 2, kCourses}}, 0.5,
                  stagger_axis, BrickBond::English);
  return m;
}

/// Interior joint planes (a brick face inside the wall, normal along `axis`) of each course.
std::vector<std::set<long>> jointPlanes(const HostMesh &m, int axis)
{
  std::vector<std::set<long>> planes(kCourses);
  for (const HostPart &p : m.parts)
  {
    const Box b = boxOf(m, p);
    for (Real x : {b.lo[size_t(axis)], b.hi[size_t(axis)]})
    {
      const Real u = x - kOrigin[size_t(axis)];
      if (u > kPosTol && u < kWall[size_t(axis)] - kPosTol)            // not the wall's own face
        planes[size_t(courseOf(p.name))].insert(std::lround(u * 1e6)); // micrometres
    }
  }
  return planes;
}

} // namespace

TEST(BrickBond, EnglishBondFillsTheWallWithStretcherAndHeaderCourses)
{
  const HostMesh m = englishWall();
  // stretcher courses 2 leaves x 3; header courses 2 closers + 2 x 3 - 1 headers
  const size_t stretchers = 2 * kAlong, headers = 2 + 2 * kAlong - 1;
  ASSERT_EQ(m.parts.size(), 2 * stretchers + 2 * headers);
  EXPECT_NO_THROW(checkElements(m));
  Real volume = 0;
  for (int p = 0; p < int(m.parts.size()); ++p)
    volume += meshMeasure(m, p);
  const Real box = kWall[0] * kWall[1] * kWall[2];
  EXPECT_NEAR(volume, box, 1e-12 * box);

  std::vector<Box> boxes;
  for (const HostPart &p : m.parts)
    boxes.push_back(boxOf(m, p));
  for (size_t i = 0; i < boxes.size(); ++i)
  {
    // inside the wall's box
    for (int d = 0; d < 3; ++d)
    {
      EXPECT_GE(boxes[i].lo[size_t(d)], kOrigin[size_t(d)] - kPosTol) << m.parts[i].name;
      EXPECT_LE(boxes[i].hi[size_t(d)], kOrigin[size_t(d)] + kWall[size_t(d)] + kPosTol)
          << m.parts[i].name;
    }
    // no two bricks overlap: their boxes share at most a face
    for (size_t j = i + 1; j < boxes.size(); ++j)
    {
      Real overlap = 1;
      for (int d = 0; d < 3; ++d)
        overlap *= std::max<Real>(0, std::min(boxes[i].hi[size_t(d)], boxes[j].hi[size_t(d)]) -
                                         std::max(boxes[i].lo[size_t(d)], boxes[j].lo[size_t(d)]));
      EXPECT_LT(overlap, 1e-15) << m.parts[i].name << " and " << m.parts[j].name;
    }
  }
  for (size_t i = 0; i < m.parts.size(); ++i)
  {
    const int c = courseOf(m.parts[i].name);
    const Real thick = boxes[i].hi[1] - boxes[i].lo[1], len = boxes[i].hi[0] - boxes[i].lo[0];
    if (c % 2 == 0) // a stretcher: one leaf, a brick long
    {
      EXPECT_NEAR(thick, kBrick[1], kPosTol) << m.parts[i].name;
      EXPECT_NEAR(len, kBrick[0], kPosTol) << m.parts[i].name;
      EXPECT_EQ(m.parts[i].numElements(), 4 * 2 * 1);
    }
    else // a header spans the whole thickness: a header is a brick width along the wall,
    {    // a closer half that
      EXPECT_NEAR(thick, kWall[1], kPosTol) << m.parts[i].name;
      const bool closer = len < 0.75 * kBrick[1];
      EXPECT_NEAR(len, closer ? kBrick[1] / 2 : kBrick[1], kPosTol) << m.parts[i].name;
      EXPECT_EQ(m.parts[i].numElements(), (closer ? 1 : 2) * 4 * 1) << m.parts[i].name;
    }
  }
  EXPECT_EQ(m.parts[2 * kAlong].name, "w.1.0");
}

TEST(BrickBond, NoJointPlaneRunsThroughTwoConsecutiveCourses)
{
  const HostMesh english = englishWall();
  for (int axis : {0, 1})
  {
    const auto planes = jointPlanes(english, axis);
    for (int c = 0; c + 1 < kCourses; ++c)
      for (long u : planes[size_t(c)])
        EXPECT_EQ(planes[size_t(c + 1)].count(u), 0u)
            << "joint plane normal to axis " << axis << " at " << u << " um through courses " << c
            << " and " << c + 1;
  }
  // the running bond's leaves are separate: its joint between them crosses every course
  HostMesh running;
  appendBrickWall(running, "w", ElementType::Hex8, {{4, 2, 1}}, kOrigin, kBrick,
                  {{kAlong, 2, kCourses}}, 0.5);
  const auto planes = jointPlanes(running, 1);
  for (int c = 0; c < kCourses; ++c)
    EXPECT_EQ(planes[size_t(c)].count(120000), 1u) << "course " << c;
}

TEST(BrickBond, StaggeredAlongYIsTheTransposedWall)
{
  // the wall along y: count [2, kAlong, kCourses] with brick [W, L, H]
  HostMesh y;
  appendBrickWall(y, "w", ElementType::Hex8, {{2, 4, 1}}, {{kOrigin[1], kOrigin[0], kOrigin[2]}},
                  {{kBrick[1], kBrick[0], kBrick[2]}}, {{2, kAlong, kCourses}}, 0.5, 1,
                  BrickBond::English);
  const HostMesh x = englishWall();
  ASSERT_EQ(x.parts.size(), y.parts.size());
  for (size_t p = 0; p < x.parts.size(); ++p)
  {
    const Box a = boxOf(x, x.parts[p]), b = boxOf(y, y.parts[p]);
    EXPECT_EQ(x.parts[p].name, y.parts[p].name);
    EXPECT_EQ(x.parts[p].numElements(), y.parts[p].numElements());
    for (int d = 0; d < 3; ++d)
    {
      const int e = d == 2 ? 2 : 1 - d;
      EXPECT_NEAR(a.lo[size_t(d)], b.lo[size_t(e)], kPosTol) << x.parts[p].name;
      EXPECT_NEAR(a.hi[size_t(d)], b.hi[size_t(e)], kPosTol) << x.parts[p].name;
    }
  }
}

TEST(BrickBond, EnglishBondRefusesWallsItCannotLay)
{
  HostMesh m;
  // three rows through the thickness
  EXPECT_THROW(appendBrickWall(m, "w", ElementType::Hex8, {{4, 2, 1}}, kOrigin, kBrick,
                               {{kAlong, 3, kCourses}}, 0.5, 0, BrickBond::English),
               std::runtime_error);
  // a brick not twice as long as wide
  EXPECT_THROW(appendBrickWall(m, "w", ElementType::Hex8, {{4, 2, 1}}, kOrigin,
                               {{0.25, 0.12, 0.06}}, {{kAlong, 2, kCourses}}, 0.5, 0,
                               BrickBond::English),
               std::runtime_error);
  // 2D
  EXPECT_THROW(appendBrickWall(m, "w", ElementType::Quad4, {{4, 2, 1}}, kOrigin, kBrick,
                               {{kAlong, 2, 1}}, 0.5, 0, BrickBond::English),
               std::runtime_error);
  EXPECT_TRUE(m.parts.empty());
}
