// Common-plane geometry (docs/theory.md section 4) and nodal weights (section 8).
#include "contact/CommonPlaneGeometry.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

using namespace scpdyn;

namespace
{
using P2 = std::array<Real, 2>;

// Independent reference for the intersection of two convex polygons: the convex hull of the
// vertices of each inside the other plus all edge-edge crossings (no clipping involved).
Real crossz(const P2 &o, const P2 &a, const P2 &b)
{
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}
std::vector<P2> hull(std::vector<P2> p)
{
  std::sort(p.begin(), p.end());
  if (p.size() < 3)
    return p;
  std::vector<P2> h(2 * p.size());
  size_t k = 0;
  for (size_t i = 0; i < p.size(); ++i)
  {
    while (k >= 2 && crossz(h[k - 2], h[k - 1], p[i]) <= 0)
      --k;
    h[k++] = p[i];
  }
  for (size_t i = p.size() - 1, t = k + 1; i > 0; --i)
  {
    while (k >= t && crossz(h[k - 2], h[k - 1], p[i - 1]) <= 0)
      --k;
    h[k++] = p[i - 1];
  }
  h.resize(k - 1);
  return h;
}
bool insideConvex(const std::vector<P2> &P, const P2 &x)
{
  for (size_t k = 0; k < P.size(); ++k)
    if (crossz(P[k], P[(k + 1) % P.size()], x) < 0)
      return false;
  return true;
}
void refMoments(const std::vector<P2> &P, const std::vector<P2> &Q, Real &A, Real &Mx, Real &My)
{
  std::vector<P2> pts;
  for (auto &p : P)
    if (insideConvex(Q, p))
      pts.push_back(p);
  for (auto &q : Q)
    if (insideConvex(P, q))
      pts.push_back(q);
  for (size_t i = 0; i < P.size(); ++i)
    for (size_t j = 0; j < Q.size(); ++j)
    {
      const P2 &a = P[i], &b = P[(i + 1) % P.size()], &c = Q[j], &d = Q[(j + 1) % Q.size()];
      const Real den = (b[0] - a[0]) * (d[1] - c[1]) - (b[1] - a[1]) * (d[0] - c[0]);
      if (den == 0)
        continue;
      const Real t = ((c[0] - a[0]) * (d[1] - c[1]) - (c[1] - a[1]) * (d[0] - c[0])) / den;
      const Real s = ((c[0] - a[0]) * (b[1] - a[1]) - (c[1] - a[1]) * (b[0] - a[0])) / den;
      if (t >= 0 && t <= 1 && s >= 0 && s <= 1)
        pts.push_back({a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])});
    }
  A = Mx = My = 0;
  const auto h = hull(pts);
  if (h.size() < 3)
    return;
  Real buf[64][2];
  for (size_t k = 0; k < h.size(); ++k)
    buf[k][0] = h[k][0], buf[k][1] = h[k][1];
  cp_geometry::polygonMoments(buf, int(h.size()), A, Mx, My);
}
std::vector<P2> randomConvex(std::mt19937_64 &rng, int maxv)
{
  std::uniform_real_distribution<Real> u(-1, 1);
  std::vector<P2> pts;
  for (int i = 0; i < 12; ++i)
    pts.push_back({0.3 * u(rng) + 0.6 * u(rng), 0.3 * u(rng) + 0.6 * u(rng)});
  auto h = hull(pts);
  while (int(h.size()) > maxv)
    h.erase(h.begin() + (rng() % h.size())); // dropping hull vertices keeps convexity
  return h;
}
void toArray(const std::vector<P2> &v, Real a[][2])
{
  for (size_t k = 0; k < v.size(); ++k)
    a[k][0] = v[k][0], a[k][1] = v[k][1];
}

// 3D rotation from a random unit quaternion
void randomRotation(std::mt19937_64 &rng, Real R[3][3])
{
  std::normal_distribution<Real> g(0, 1);
  Real q[4];
  Real l = 0;
  for (auto &c : q)
    c = g(rng), l += c * c;
  l = std::sqrt(l);
  const Real w = q[0] / l, x = q[1] / l, y = q[2] / l, z = q[3] / l;
  const Real M[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                        {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                        {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      R[i][j] = M[i][j];
}
void transform(const Real R[3][3], const Real t[3], const Real x[][3], int n, Real y[][3])
{
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d)
      y[i][d] = R[d][0] * x[i][0] + R[d][1] * x[i][1] + R[d][2] * x[i][2] + t[d];
}
Real relDiff(Real a, Real b, Real scale) { return std::fabs(a - b) / scale; }
} // namespace

// Section 4.8 worked example: every number is exact in binary except 0.001 and its halves, so
// 1e-15 absolute (a few ulps of O(1) coordinates) is the round-off bound.
TEST(CpGeometry, WorkedExample48)
{
  const Real h = 0.001;
  const Real x1[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const Real x2[4][3] = {{0.5, 0, h}, {0.5, 1, h}, {1.5, 1, h}, {1.5, 0, h}};
  const CpGeometry g = computeCommonPlane<3>(x1, 4, x2, 4, false);
  ASSERT_TRUE(g.valid);
  EXPECT_NEAR(g.n[0], 0, 1e-15);
  EXPECT_NEAR(g.n[1], 0, 1e-15);
  EXPECT_NEAR(g.n[2], 1, 1e-15);
  const Real poc[3] = {0.75, 0.5, 0.0005};
  for (int d = 0; d < 3; ++d)
  {
    EXPECT_NEAR(g.x_cp[d], poc[d], 1e-15);
    EXPECT_NEAR(g.x_poc[d], poc[d], 1e-15);
  }
  EXPECT_NEAR(g.Ac, 0.5, 1e-15);
  EXPECT_NEAR(g.u0, -0.001, 1e-15);
  EXPECT_NEAR(g.f1, 0.5, 1e-15);
  EXPECT_NEAR(g.f2, 0.5, 1e-15);
  EXPECT_NEAR(g.A1, 1.0, 1e-15);
  EXPECT_TRUE(cpIsActive(g));
}

// Coincident, edge-touching and disjoint faces. Touching faces give a degenerate polygon whose
// area is round-off of O(1) coordinates (<= 1e-15); disjoint faces give exactly zero.
TEST(CpGeometry, CoincidentTouchingDisjoint)
{
  const Real x1[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const Real same[4][3] = {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}};
  CpGeometry g = computeCommonPlane<3>(x1, 4, same, 4, false);
  EXPECT_NEAR(g.Ac, 1.0, 1e-15);
  EXPECT_EQ(g.u0, 0.0);
  EXPECT_NEAR(g.x_poc[0], 0.5, 1e-15);
  EXPECT_NEAR(g.x_poc[1], 0.5, 1e-15);
  EXPECT_EQ(g.f1, 1.0);

  const Real edge[4][3] = {{1, 0, 0}, {1, 1, 0}, {2, 1, 0}, {2, 0, 0}};
  g = computeCommonPlane<3>(x1, 4, edge, 4, false);
  EXPECT_LE(g.Ac, 1e-15);
  EXPECT_FALSE(cpIsActive(g));
  const Real corner[4][3] = {{1, 1, 0}, {1, 2, 0}, {2, 2, 0}, {2, 1, 0}};
  g = computeCommonPlane<3>(x1, 4, corner, 4, false);
  EXPECT_LE(g.Ac, 1e-15);
  const Real far[4][3] = {{1.5, 0, 0}, {1.5, 1, 0}, {2.5, 1, 0}, {2.5, 0, 0}};
  g = computeCommonPlane<3>(x1, 4, far, 4, false);
  EXPECT_EQ(g.Ac, 0.0);
  EXPECT_TRUE(g.valid);
}

// Random convex polygon pairs (3..8 vertices) against the hull-based reference: area and
// centroid to 1e-12 of the O(1) polygon area (double round-off of a few dozen operations),
// symmetric in the two polygons, never above the smaller area.
TEST(CpGeometry, RandomConvexOverlap)
{
  std::mt19937_64 rng(12345);
  Real worst = 0, worst_sym = 0;
  int nonempty = 0;
  for (int trial = 0; trial < 3000; ++trial)
  {
    const auto P = randomConvex(rng, 3 + trial % 6), Q = randomConvex(rng, 3 + (trial / 6) % 6);
    Real a[16][2], b[16][2], out[kMaxPolyVerts][2];
    toArray(P, a), toArray(Q, b);
    Real A1, M1x, M1y, A2, M2x, M2y, Ar, Mrx, Mry;
    int n = cp_geometry::clipConvex(a, int(P.size()), b, int(Q.size()), out);
    cp_geometry::polygonMoments(out, n, A1, M1x, M1y);
    n = cp_geometry::clipConvex(b, int(Q.size()), a, int(P.size()), out);
    cp_geometry::polygonMoments(out, n, A2, M2x, M2y);
    refMoments(P, Q, Ar, Mrx, Mry);
    const Real Ap = cp_geometry::polygonSignedArea(a, int(P.size()));
    const Real Aq = cp_geometry::polygonSignedArea(b, int(Q.size()));
    ASSERT_GT(Ap, 0);
    worst = std::max({worst, std::fabs(A1 - Ar), std::fabs(M1x - Mrx), std::fabs(M1y - Mry)});
    worst_sym = std::max(worst_sym, std::fabs(A1 - A2));
    EXPECT_LE(A1, std::min(Ap, Aq) * (1 + 1e-12));
    nonempty += Ar > 0;
  }
  EXPECT_LT(worst, 1e-12);
  EXPECT_LT(worst_sym, 1e-12);
  EXPECT_GT(nonempty, 1000); // the sample really exercises overlaps
  std::printf("[ measured ] random convex overlap: max |A - Aref| or moment error %.2e, "
              "max asymmetry %.2e, %d non-empty of 3000\n",
              worst, worst_sym, nonempty);
}

// A non-convex (dart) face whose vertex centroid lies outside the polygon: the signed fan of 4.4
// must still give the exact area and centroid. Reference: split along the reflex diagonal into
// two convex triangles. Tolerance as above.
TEST(CpGeometry, NonConvexSignedFan)
{
  const std::vector<P2> dart = {{0, 0}, {4, 1}, {0, 2}, {3.5, 1}};
  const std::vector<P2> t1 = {{0, 0}, {4, 1}, {3.5, 1}}, t2 = {{3.5, 1}, {4, 1}, {0, 2}};
  Real d[4][2];
  toArray(dart, d);
  ASSERT_FALSE(cp_geometry::isConvexCCW(d, 4));
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<Real> u(-0.5, 4.0);
  Real worst = 0;
  for (int trial = 0; trial < 500; ++trial)
  {
    const Real x0 = u(rng), y0 = 0.5 * u(rng), s = 0.3 + 0.5 * std::fabs(u(rng));
    const std::vector<P2> sq = {{x0, y0}, {x0 + s, y0}, {x0 + s, y0 + s}, {x0, y0 + s}};
    Real q[4][2];
    toArray(sq, q);
    Real A, Mx, My, Ar1, Mx1, My1, Ar2, Mx2, My2;
    cp_geometry::overlapMoments(d, 4, q, 4, A, Mx, My);
    refMoments(t1, sq, Ar1, Mx1, My1);
    refMoments(t2, sq, Ar2, Mx2, My2);
    worst = std::max(
        {worst, std::fabs(A - Ar1 - Ar2), std::fabs(Mx - Mx1 - Mx2), std::fabs(My - My1 - My2)});
  }
  EXPECT_LT(worst, 1e-12);

  // the same through computeCommonPlane: planar dart face 1 (n1 = +z) against a big square
  const Real x1[4][3] = {{0, 0, 0}, {4, 1, 0}, {0, 2, 0}, {3.5, 1, 0}};
  const Real x2[4][3] = {{-1, -1, 0}, {-1, 3, 0}, {5, 3, 0}, {5, -1, 0}};
  const CpGeometry g = computeCommonPlane<3>(x1, 4, x2, 4, false);
  Real A1r, a, b, A2r;
  refMoments(t1, {{-1, -1}, {5, -1}, {5, 3}, {-1, 3}}, A1r, a, b);
  refMoments(t2, {{-1, -1}, {5, -1}, {5, 3}, {-1, 3}}, A2r, a, b);
  EXPECT_NEAR(g.Ac, A1r + A2r, 1e-12);
  EXPECT_NEAR(g.A1p, A1r + A2r, 1e-12); // the whole dart overlaps
  EXPECT_NEAR(g.f1, 1.0, 1e-12);
  std::printf("[ measured ] signed fan vs triangulation: max error %.2e; dart area %.15g\n", worst,
              g.Ac);
}

// Random rigid motions leave Ac, u0, projected areas and fractions unchanged and move the POC
// with the body. Faces: random convex-ish quads of about 1 m, face 2 tilted and warped, gaps
// and overlaps up to 5 mm. 1e-12 relative is ~1e4 ulps of slack over the round-off of the
// rotated coordinates.
TEST(CpGeometry, RigidMotionInvariance)
{
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<Real> u(-1, 1);
  Real worstA = 0, worstU = 0, worstP = 0;
  for (int trial = 0; trial < 500; ++trial)
  {
    Real x1[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    Real x2[4][3] = {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}};
    const Real gap = 0.005 * u(rng), ox = 0.4 * u(rng), oy = 0.4 * u(rng), tilt = 0.05 * u(rng);
    for (int i = 0; i < 4; ++i)
    {
      x1[i][0] += 0.15 * u(rng), x1[i][1] += 0.15 * u(rng);
      x2[i][0] += ox + 0.15 * u(rng), x2[i][1] += oy + 0.15 * u(rng);
      x2[i][2] = gap + tilt * x2[i][0] + 0.002 * u(rng); // warped
    }
    const CpGeometry g = computeCommonPlane<3>(x1, 4, x2, 4, false);
    Real R[3][3], t[3] = {u(rng), u(rng), u(rng)}, y1[4][3], y2[4][3];
    randomRotation(rng, R);
    transform(R, t, x1, 4, y1);
    transform(R, t, x2, 4, y2);
    const CpGeometry h = computeCommonPlane<3>(y1, 4, y2, 4, false);
    ASSERT_TRUE(g.valid && h.valid);
    worstA =
        std::max({worstA, relDiff(g.Ac, h.Ac, g.A1), relDiff(g.A1p, h.A1p, g.A1p),
                  relDiff(g.A2p, h.A2p, g.A2p), std::fabs(g.f1 - h.f1), std::fabs(g.f2 - h.f2)});
    // u0 is a difference of O(1) coordinates that the rotation rounds by ~1e-16 m, so its
    // invariance is relative only down to |u0| = 1e-3 m, absolute (1e-15 m) below
    worstU = std::max(worstU, relDiff(g.u0, h.u0, std::max(std::fabs(g.u0), 1e-3)));
    Real p[1][3];
    const Real gp[1][3] = {{g.x_poc[0], g.x_poc[1], g.x_poc[2]}};
    transform(R, t, gp, 1, p);
    for (int d = 0; d < 3; ++d)
      worstP = std::max(worstP, std::fabs(p[0][d] - h.x_poc[d]));
  }
  EXPECT_LT(worstA, 1e-12);
  EXPECT_LT(worstU, 1e-12);
  EXPECT_LT(worstP, 1e-12);
  std::printf("[ measured ] rigid motion: max rel change Ac/Ap/f %.2e, u0 %.2e, POC %.2e m\n",
              worstA, worstU, worstP);
}

// Swapping the faces reverses n and leaves x_cp, Ac, x_poc and u0 unchanged (round-off only:
// the clip runs with the roles exchanged), in 3D and 2D.
TEST(CpGeometry, SwapFaces)
{
  const Real x1[4][3] = {{0, 0, 0}, {1, 0.1, 0}, {1.1, 1, 0.01}, {0, 0.9, 0}};
  const Real x2[3][3] = {{0.3, -0.2, 0.002}, {0.2, 0.8, 0.001}, {1.4, 0.5, 0.003}};
  const CpGeometry g = computeCommonPlane<3>(x1, 4, x2, 3, false);
  const CpGeometry h = computeCommonPlane<3>(x2, 3, x1, 4, false);
  EXPECT_GT(g.Ac, 0.1);
  EXPECT_NEAR(g.Ac, h.Ac, 1e-14);
  EXPECT_NEAR(g.u0, h.u0, 1e-15);
  EXPECT_NEAR(g.f1, h.f2, 1e-14);
  for (int d = 0; d < 3; ++d)
  {
    EXPECT_EQ(g.n[d], -h.n[d]);
    EXPECT_EQ(g.x_cp[d], h.x_cp[d]);
    EXPECT_NEAR(g.x_poc[d], h.x_poc[d], 1e-14);
  }
  const Real s1[2][3] = {{1, 0, 0}, {0, 0.01, 0}};        // normal ~ +y
  const Real s2[2][3] = {{0.4, 0.02, 0}, {1.5, 0.03, 0}}; // normal ~ -y
  const CpGeometry a = computeCommonPlane<2>(s1, 2, s2, 2, false);
  const CpGeometry b = computeCommonPlane<2>(s2, 2, s1, 2, false);
  EXPECT_NEAR(a.Ac, b.Ac, 1e-15);
  EXPECT_NEAR(a.u0, b.u0, 1e-15);
  for (int d = 0; d < 3; ++d)
    EXPECT_NEAR(a.x_poc[d], b.x_poc[d], 1e-15);
}

// 2D plane strain (4.5): Ac = overlap length per metre, POC at its middle, u0 = -gap.
TEST(CpGeometry, PlaneStrainSegments)
{
  const Real s1[2][3] = {{2, 0, 0}, {0, 0, 0}};         // element below: outward +y
  const Real s2[2][3] = {{1.5, 0.01, 0}, {3, 0.01, 0}}; // element above: outward -y
  const CpGeometry g = computeCommonPlane<2>(s1, 2, s2, 2, false);
  EXPECT_NEAR(g.n[1], 1, 1e-15);
  EXPECT_NEAR(g.Ac, 0.5, 1e-15);
  EXPECT_NEAR(g.x_poc[0], 1.75, 1e-15);
  EXPECT_NEAR(g.u0, -0.01, 1e-15);
  EXPECT_NEAR(g.A1, 2.0, 1e-15);
  EXPECT_NEAR(g.f1, 0.25, 1e-15);
  EXPECT_NEAR(g.f2, 0.5 / 1.5, 1e-15);
}

// 2D axisymmetric (4.6): per-radian strip area 0.5 (ra + rb) L and the trapezoid centroid, for
// a radial strip (CP line perpendicular to the axis) and an inclined (conical) one.
TEST(CpGeometry, AxisymmetricStrip)
{
  { // radial strip: faces on z = 0, overlap r in [1.5, 2]
    const Real s1[2][3] = {{2, 0, 0}, {1, 0, 0}};
    const Real s2[2][3] = {{1.5, 0, 0}, {3, 0, 0}};
    const CpGeometry g = computeCommonPlane<2>(s1, 2, s2, 2, true);
    EXPECT_NEAR(g.Ac, 0.5 * (1.5 + 2.0) * 0.5, 1e-15);
    EXPECT_NEAR(g.A1, 0.5 * (1 + 2) * 1, 1e-15);
    EXPECT_NEAR(g.A2p, 0.5 * (1.5 + 3) * 1.5, 1e-14);
    EXPECT_NEAR(g.x_poc[0], 1.5 + 0.5 * (1.5 + 2 * 2) / (3 * (1.5 + 2)), 1e-15);
  }
  { // inclined coincident faces from (1,0) to (2,1): L = sqrt 2, ra = 1, rb = 2
    const Real s1[2][3] = {{1, 0, 0}, {2, 1, 0}};
    const Real s2[2][3] = {{2, 1, 0}, {1, 0, 0}};
    const CpGeometry g = computeCommonPlane<2>(s1, 2, s2, 2, true);
    EXPECT_NEAR(g.Ac, 0.5 * 3 * std::sqrt(2.0), 1e-14);
    EXPECT_NEAR(g.f1, 1.0, 1e-14);
    // centroid of the conical strip along the line: 1 + (1 + 2*2)/(3*3) in r
    EXPECT_NEAR(g.x_poc[0], 1 + 5.0 / 9.0, 1e-14);
  }
}

// 4.1: a triangle and a warped quad. The warped quad (z = h at nodes 1, 3) is symmetric about
// its centre, so the vector-area normal is exactly +z; each pallet has area sqrt(1 + h^2)/4.
TEST(CpGeometry, FaceNormalsAndAreas)
{
  const Real tri[3][3] = {{0, 0, 0}, {2, 0, 0}, {0, 0, 3}};
  FaceGeometry f = faceGeometry<3>(tri, 3, false);
  EXPECT_NEAR(f.area, 3.0, 1e-15);
  EXPECT_NEAR(f.n[1], -1.0, 1e-15);
  const Real h = 0.2;
  const Real quad[4][3] = {{0, 0, 0}, {1, 0, h}, {1, 1, 0}, {0, 1, h}};
  f = faceGeometry<3>(quad, 4, false);
  EXPECT_NEAR(f.n[2], 1.0, 1e-15);
  EXPECT_GT(f.area, 1.0 + 1e-3);
  EXPECT_NEAR(f.area, std::sqrt(1 + h * h), 1e-15); // four pallets of sqrt(1 + h^2)/4 each
  EXPECT_NEAR(f.c[2], 0.5 * h, 1e-15);
}

// Section 8: penetration weights (8.1 example delta = 2,1,1,0 um -> 0.5, 0.25, 0.25, 0) and
// the shape-function fallback (8.2) for coincident faces, whose weights follow from the
// bilinear map at the POC (0.75, 0.5). Exact fractions: 1e-12.
TEST(CpGeometry, NodalWeights)
{
  const Real x1[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const Real x2[4][3] = {{0.5, 0, 0}, {0.5, 1, 0}, {1.5, 1, 0}, {1.5, 0, 0}};
  CpGeometry g = computeCommonPlane<3>(x1, 4, x2, 4, false);
  Real w[4];
  nodalWeights(x1, 4, g, 1, DistributionRule::Penetration, w);
  const Real w1[4] = {0.125, 0.375, 0.375, 0.125};
  for (int i = 0; i < 4; ++i)
    EXPECT_NEAR(w[i], w1[i], 1e-12);
  nodalWeights(x2, 4, g, 2, DistributionRule::Penetration, w);
  const Real w2[4] = {0.375, 0.375, 0.125, 0.125};
  for (int i = 0; i < 4; ++i)
    EXPECT_NEAR(w[i], w2[i], 1e-12);

  // penetration: face 1 nodes 2, 1, 1, 0 um beyond the POC plane along n (= +z)
  const Real um = 1e-6;
  const Real y1[4][3] = {{0, 0, 2 * um}, {1, 0, 1 * um}, {1, 1, 1 * um}, {0, 1, 0}};
  const Real y2[4][3] = {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}};
  g = computeCommonPlane<3>(y1, 4, y2, 4, false);
  // test the rule in isolation: measure from the face-2 plane z = 0 along +z
  g.x_poc[2] = 0;
  g.n[0] = g.n[1] = 0, g.n[2] = 1;
  nodalWeights(y1, 4, g, 1, DistributionRule::Penetration, w);
  const Real wp[4] = {0.5, 0.25, 0.25, 0};
  for (int i = 0; i < 4; ++i)
    EXPECT_NEAR(w[i], wp[i], 1e-9); // delta from z differences of 1e-6: ~1e-10 relative
  // face 2 does not penetrate (all delta = 0): falls back to shape functions, sum 1
  nodalWeights(y2, 4, g, 2, DistributionRule::Penetration, w);
  EXPECT_NEAR(w[0] + w[1] + w[2] + w[3], 1.0, 1e-15);

  // 2D segment and triangle
  const Real s1[2][3] = {{2, 0, 0}, {0, 0, 0}}, s2[2][3] = {{1.5, 0, 0}, {3, 0, 0}};
  g = computeCommonPlane<2>(s1, 2, s2, 2, false);
  nodalWeights(s1, 2, g, 1, DistributionRule::Poc, w); // POC at x = 1.75
  EXPECT_NEAR(w[0], 0.875, 1e-14);
  EXPECT_NEAR(w[1], 0.125, 1e-14);
  const Real t1[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}},
             t2[3][3] = {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}};
  g = computeCommonPlane<3>(t1, 3, t2, 3, false);
  nodalWeights(t1, 3, g, 1, DistributionRule::Poc, w); // POC = centroid (1/3, 1/3)
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(w[i], 1.0 / 3.0, 1e-14);
}
