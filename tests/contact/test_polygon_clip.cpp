// The fast path of the polygon clip (PolygonClip.hpp: each vertex's side once per edge, two
// alternating buffers, no copy before each edge) against the clip it replaced, bit for bit:
// the same vertices in the same order. Whole runs keep their gauges bit for bit only if this
// holds (scripts/same_bits.sh).
#include "contact/PolygonClip.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>

using namespace scpdyn;

namespace
{
bool sameBits(Real a, Real b)
{
  std::uint64_t ia, ib;
  std::memcpy(&ia, &a, sizeof(a));
  std::memcpy(&ib, &b, sizeof(b));
  return ia == ib;
}
} // namespace

namespace
{
// The clip as it was: copy the polygon before every edge, each side computed for S and for E.
int referenceClip(const Real subj[][2], int ns, const Real clip[][2], int nc, Real out[][2])
{
  Real buf[kMaxPolyVerts][2];
  int n = ns;
  for (int k = 0; k < ns; ++k)
    out[k][0] = subj[k][0], out[k][1] = subj[k][1];
  for (int e = 0; e < nc && n > 0; ++e)
  {
    const Real ax = clip[e][0], ay = clip[e][1];
    const int f = (e + 1) % nc;
    const Real ex = clip[f][0] - ax, ey = clip[f][1] - ay;
    for (int k = 0; k < n; ++k)
      buf[k][0] = out[k][0], buf[k][1] = out[k][1];
    const int nin = n;
    n = 0;
    for (int k = 0, j = nin - 1; k < nin; j = k++)
    {
      const Real dS = cp_geometry::cross2(ex, ey, buf[j][0] - ax, buf[j][1] - ay);
      const Real dE = cp_geometry::cross2(ex, ey, buf[k][0] - ax, buf[k][1] - ay);
      if ((dE >= 0) != (dS >= 0) && n < kMaxPolyVerts)
      {
        const Real t = dS / (dS - dE);
        out[n][0] = buf[j][0] + t * (buf[k][0] - buf[j][0]);
        out[n][1] = buf[j][1] + t * (buf[k][1] - buf[j][1]);
        ++n;
      }
      if (dE >= 0 && n < kMaxPolyVerts)
      {
        out[n][0] = buf[k][0], out[n][1] = buf[k][1];
        ++n;
      }
    }
  }
  return n < 3 ? 0 : n;
}
} // namespace

TEST(PolygonClip, ClipWithoutCopiesGivesTheVerticesOfTheCopyingClip)
{
  std::mt19937 rng(11);
  std::uniform_real_distribution<Real> u(-1.0, 1.0);
  int clipped = 0;
  for (int trial = 0; trial < 4000; ++trial)
  {
    // convex CCW polygons of 3 or 4 vertices (points on a circle, ascending angle), shifted
    Real P[2][4][2];
    int nv[2];
    for (int k = 0; k < 2; ++k)
    {
      nv[k] = 3 + (trial >> k) % 2;
      const Real cx = 0.8 * u(rng), cy = 0.8 * u(rng), r = 0.5 + 0.5 * (u(rng) + 1);
      for (int i = 0; i < nv[k]; ++i)
      {
        const Real ang = 2 * M_PI * (i + 0.4 * u(rng)) / nv[k];
        P[k][i][0] = cx + r * std::cos(ang), P[k][i][1] = cy + r * std::sin(ang);
      }
      if (trial % 7 == 0) // shared vertices and edges: the touching cases
        for (int i = 0; i < nv[k]; ++i)
          P[k][i][0] = std::round(4 * P[k][i][0]) / 4, P[k][i][1] = std::round(4 * P[k][i][1]) / 4;
    }
    Real a[kMaxPolyVerts][2], b[kMaxPolyVerts][2];
    const int na = cp_geometry::clipConvex(P[0], nv[0], P[1], nv[1], a);
    const int nb = referenceClip(P[0], nv[0], P[1], nv[1], b);
    ASSERT_EQ(na, nb) << "trial " << trial;
    for (int i = 0; i < na; ++i)
      for (int d = 0; d < 2; ++d)
        ASSERT_TRUE(sameBits(a[i][d], b[i][d])) << "trial " << trial << " vertex " << i;
    clipped += na > 0 ? 1 : 0;
  }
  EXPECT_GT(clipped, 1000);
  EXPECT_LT(clipped, 4000);
}
