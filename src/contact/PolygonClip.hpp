#pragma once
/// \file PolygonClip.hpp
/// \brief Planar polygon kernels of the common-plane overlap (docs/theory.md 4.4): shoelace area
/// and first moments, convexity test, Sutherland-Hodgman clipping and the signed fan split of a
/// non-convex polygon. Device-callable, fixed-size buffers, no allocation.
#include "contact/CommonPlaneState.hpp"

namespace scpdyn
{

constexpr int kMaxPolyVerts = 16; ///< overlap buffer; clipConvex needs n_subject + n_clip <= 16

namespace cp_geometry
{
using namespace contact_math;

KOKKOS_INLINE_FUNCTION Real cross2(Real ax, Real ay, Real bx, Real by) { return ax * by - ay * bx; }

/// The vertex after k of a closed polygon of np vertices: (k + 1) % np without the integer
/// division, which in the clipping's inner loops cost as much as the arithmetic.
KOKKOS_INLINE_FUNCTION int nextVertex(int k, int np) { return k + 1 < np ? k + 1 : 0; }

/// \brief Shoelace area and first moments (integral of xi, eta) of a closed polygon.
KOKKOS_INLINE_FUNCTION void polygonMoments(const Real p[][2], int np, Real &A, Real &Mx, Real &My)
{
  A = Mx = My = 0;
  for (int k = 0; k < np; ++k)
  {
    const int l = nextVertex(k, np);
    const Real w = cross2(p[k][0], p[k][1], p[l][0], p[l][1]);
    A += w;
    Mx += (p[k][0] + p[l][0]) * w;
    My += (p[k][1] + p[l][1]) * w;
  }
  A *= 0.5;
  Mx /= 6.0;
  My /= 6.0;
}

KOKKOS_INLINE_FUNCTION Real polygonSignedArea(const Real p[][2], int np)
{
  Real A, Mx, My;
  polygonMoments(p, np, A, Mx, My);
  return A;
}

KOKKOS_INLINE_FUNCTION void reversePolygon(Real p[][2], int np)
{
  for (int i = 0, j = np - 1; i < j; ++i, --j)
    for (int d = 0; d < 2; ++d)
    {
      const Real t = p[i][d];
      p[i][d] = p[j][d];
      p[j][d] = t;
    }
}

/// \brief Convexity of a counter-clockwise polygon: no turn to the right beyond round-off
/// (tolerance relative to the squared edge lengths, so collinear vertices count as convex).
KOKKOS_INLINE_FUNCTION bool isConvexCCW(const Real p[][2], int np)
{
  Real scale = 0;
  for (int k = 0; k < np; ++k)
  {
    const int l = nextVertex(k, np);
    scale += (p[l][0] - p[k][0]) * (p[l][0] - p[k][0]) + (p[l][1] - p[k][1]) * (p[l][1] - p[k][1]);
  }
  const Real tol = 1e-12 * scale;
  for (int k = 0; k < np; ++k)
  {
    const int l = nextVertex(k, np), m = nextVertex(l, np);
    const Real t =
        cross2(p[l][0] - p[k][0], p[l][1] - p[k][1], p[m][0] - p[l][0], p[m][1] - p[l][1]);
    if (t < -tol)
      return false;
  }
  return true;
}

/// \brief Sutherland-Hodgman: clip `subj` by the convex CCW polygon `clip` (section 4.4 step 3).
/// Keeps the part left of every clip edge. Returns the vertex count of `out` (0 if empty).
/// Capacity: ns + nc <= kMaxPolyVerts (each convex half-plane cut adds at most one vertex).
///
/// Each vertex's side of the edge is computed once per edge (every vertex is the E of one step
/// and the S of the next: the same product, so the same bits as computing it twice), and the
/// passes alternate between `out` and a local buffer, ending in `out`, instead of copying the
/// polygon before every edge: the clip is the largest share of the CP geometry.
KOKKOS_INLINE_FUNCTION int clipConvex(const Real subj[][2], int ns, const Real clip[][2], int nc,
                                      Real out[][2])
{
  Real buf[kMaxPolyVerts][2];
  Real side[kMaxPolyVerts];
  // the first pass writes to `out` when nc is odd, so that the last one does
  const Real(*src)[2] = subj;
  Real(*dst)[2] = nc % 2 == 1 ? out : buf;
  int n = ns;
  for (int e = 0; e < nc && n > 0; ++e)
  {
    const Real ax = clip[e][0], ay = clip[e][1];
    const int f = nextVertex(e, nc);
    const Real ex = clip[f][0] - ax, ey = clip[f][1] - ay;
    const int nin = n;
    for (int k = 0; k < nin; ++k)
      side[k] = cross2(ex, ey, src[k][0] - ax, src[k][1] - ay);
    n = 0;
    for (int k = 0, j = nin - 1; k < nin; j = k++)
    { // S = previous vertex j, E = current vertex k
      const Real dS = side[j], dE = side[k];
      // dS - dE cannot vanish below: exactly one of the two is negative
      if ((dE >= 0) != (dS >= 0) && n < kMaxPolyVerts)
      {
        const Real t = dS / (dS - dE);
        dst[n][0] = src[j][0] + t * (src[k][0] - src[j][0]);
        dst[n][1] = src[j][1] + t * (src[k][1] - src[j][1]);
        ++n;
      }
      if (dE >= 0 && n < kMaxPolyVerts)
      {
        dst[n][0] = src[k][0], dst[n][1] = src[k][1];
        ++n;
      }
    }
    src = dst;
    dst = dst == out ? buf : out;
  }
  if (n < 3)
    return 0;
  if (src != out) // no clip edge (nc = 0)
    for (int k = 0; k < n; ++k)
      out[k][0] = src[k][0], out[k][1] = src[k][1];
  return n;
}

/// \brief A polygon as a signed sum of convex pieces: itself if convex, else its fan triangles
/// about the vertex centroid, each oriented CCW and carrying the sign of its shoelace area
/// (section 4.4 step 4). Exact for any simple polygon: the fan's winding numbers add up to the
/// polygon's.
struct ConvexPieces
{
  Real p[4][4][2]; ///< up to 4 pieces of up to 4 vertices (face polygons have <= 4 vertices)
  int nv[4];
  Real sign[4];
  int count;
};

KOKKOS_INLINE_FUNCTION void splitConvex(const Real poly[][2], int np, ConvexPieces &cp)
{
  if (isConvexCCW(poly, np))
  {
    cp.count = 1;
    cp.nv[0] = np;
    cp.sign[0] = 1;
    for (int k = 0; k < np; ++k)
      cp.p[0][k][0] = poly[k][0], cp.p[0][k][1] = poly[k][1];
    return;
  }
  Real cx = 0, cy = 0;
  for (int k = 0; k < np; ++k)
    cx += poly[k][0] / np, cy += poly[k][1] / np;
  cp.count = 0;
  for (int k = 0; k < np; ++k)
  {
    const int l = nextVertex(k, np), m = cp.count;
    cp.p[m][0][0] = poly[k][0], cp.p[m][0][1] = poly[k][1];
    cp.p[m][1][0] = poly[l][0], cp.p[m][1][1] = poly[l][1];
    cp.p[m][2][0] = cx, cp.p[m][2][1] = cy;
    cp.nv[m] = 3;
    const Real a = polygonSignedArea(cp.p[m], 3);
    if (a == 0)
      continue; // a spoke-aligned sliver contributes nothing
    cp.sign[m] = a > 0 ? 1 : -1;
    if (a < 0)
      reversePolygon(cp.p[m], 3);
    ++cp.count;
  }
}

/// \brief Area and first moments of the intersection of two CCW simple polygons (<= 4 vertices
/// each) in the CP coordinates: Sutherland-Hodgman when both are convex, signed fans otherwise.
KOKKOS_INLINE_FUNCTION void overlapMoments(const Real P[][2], int np, const Real Q[][2], int nq,
                                           Real &A, Real &Mx, Real &My)
{
  ConvexPieces a, b;
  splitConvex(P, np, a);
  splitConvex(Q, nq, b);
  A = Mx = My = 0;
  Real out[kMaxPolyVerts][2];
  for (int i = 0; i < a.count; ++i)
    for (int j = 0; j < b.count; ++j)
    {
      const int no = clipConvex(a.p[i], a.nv[i], b.p[j], b.nv[j], out);
      if (no == 0)
        continue;
      Real ai, mx, my;
      polygonMoments(out, no, ai, mx, my);
      const Real s = a.sign[i] * b.sign[j];
      A += s * ai, Mx += s * mx, My += s * my;
    }
}

} // namespace cp_geometry
} // namespace scpdyn
