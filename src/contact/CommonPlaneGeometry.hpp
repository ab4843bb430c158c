#pragma once
/// \file CommonPlaneGeometry.hpp
/// \brief Common-plane (CP) geometry, sub-steps B-D of docs/theory.md section 4: face centroid,
/// normal and area (4.1), CP normal and point (4.2), local basis and projection (4.3), overlap
/// polygon, contact area and point of contact (4.4-4.6), area fractions (4.7) and the initial
/// closure u0 (4.8), and the nodal weights of the CP force (section 8). Device-callable,
/// fixed-size buffers, no allocation. The planar polygon kernels are in PolygonClip.hpp.
///
/// Positions passed in are the half-step positions x^{n+1/2} (sub-step A is the caller's).
/// Every point is a 3-vector; 2D problems leave z = 0 (axisymmetric: x = r, y = z).
#include "contact/PolygonClip.hpp"

namespace scpdyn
{

constexpr Real kAreaEpsilon = 1e-8; ///< epsilon_A of 3.2/3.4: active iff Ac > eps*min(A1, A2)

/// \brief Centroid, outward unit normal, area and diameter of one face (section 4.1).
struct FaceGeometry
{
  Real c[3];     ///< vertex average [m]
  Real n[3];     ///< outward unit normal
  Real area;     ///< 3D: m^2; 2D plane strain: length*1 m; axisymmetric: per radian [m^2]
  Real diameter; ///< largest vertex distance [m]
  int valid;     ///< 0 for a degenerate (zero-area) face
};

/// \brief Everything sub-steps B-D give for one CP. Forces of the CP act along `n`, which
/// points from face 1 to face 2.
struct CpGeometry
{
  int valid;     ///< 0: degenerate face or n1 == n2 (no CP normal); other fields undefined
  Real n[3];     ///< CP normal (D1)
  Real x_cp[3];  ///< CP point = trial POC (D2) [m]
  Real x_poc[3]; ///< point of contact = overlap centroid (D5) [m]
  Real e1[3];    ///< in-plane basis (4.3); 2D: e1 = t_cp, e2 = z
  Real e2[3];
  Real Ac;       ///< contact area (D4, D6a, D6b) [m^2, per metre or per radian in 2D]
  Real A1, A2;   ///< face areas (4.1)
  Real A1p, A2p; ///< areas of the projected faces (4.7)
  Real f1, f2;   ///< area fractions Ac/Aip (4.7), clipped to 1
  Real u0;       ///< closure along n at the POC (D7), > 0 overlap [m]
  Real c1[3], c2[3], n1[3], n2[3]; ///< face centroids and outward normals
  Real h1, h2;                     ///< face diameters [m]
};

namespace cp_geometry
{
using namespace contact_math;

/// \brief In-plane basis of 4.3: e1 = normalise(k x n) with k the axis of smallest |n_k|,
/// e2 = n x e1, so (e1, e2, n) is right-handed.
KOKKOS_INLINE_FUNCTION void cpBasis(const Real n[3], Real e1[3], Real e2[3])
{
  int k = 0;
  if (abs(n[1]) < abs(n[k]))
    k = 1;
  if (abs(n[2]) < abs(n[k]))
    k = 2;
  Real ax[3] = {0, 0, 0};
  ax[k] = 1;
  cross(ax, n, e1);
  const Real l = norm(e1);
  for (int d = 0; d < 3; ++d)
    e1[d] /= l;
  cross(n, e1, e2);
}

KOKKOS_INLINE_FUNCTION Real faceDiameter(const Real x[][3], int nn)
{
  Real h2 = 0;
  for (int i = 0; i < nn; ++i)
    for (int j = i + 1; j < nn; ++j)
    {
      const Real d[3] = {x[j][0] - x[i][0], x[j][1] - x[i][1], x[j][2] - x[i][2]};
      h2 = max(h2, dot(d, d));
    }
  return kmath::sqrt(h2);
}

/// \brief (D7): u0 = s1 - s2, where s_k locates the plane of face k along x_poc + s*n.
KOKKOS_INLINE_FUNCTION Real initialClosure(const CpGeometry &g)
{
  Real s[2];
  for (int f = 0; f < 2; ++f)
  {
    const Real *c = f == 0 ? g.c1 : g.c2;
    const Real *nf = f == 0 ? g.n1 : g.n2;
    const Real d[3] = {c[0] - g.x_poc[0], c[1] - g.x_poc[1], c[2] - g.x_poc[2]};
    s[f] = dot(d, nf) / dot(g.n, nf);
  }
  return s[0] - s[1];
}

} // namespace cp_geometry

/// \brief Face centroid, outward normal, area and diameter (section 4.1).
///
/// Dim = 1 (line2 in uniaxial strain): a point face; `x[0]` is the face node and `x[1]` the
/// element's other node (not a face node: the caller puts it there). n = +-x from x[1] to x[0];
/// area = the 1 m^2 cross-section of the line2 convention (volume = length x 1 m^2); diameter =
/// the element length, which sizes the bins and the default search gap like a 2D face's length.
/// Dim = 2: segment (p, q) with the element on its left, n = (t_y, -t_x)/|t|; area = length x 1 m
/// (plane strain) or (r_p + r_q)/2 x length per radian (axisymmetric, r = x).
/// Dim = 3: triangle, or quadrilateral split into the pallet triangles (x_i, x_i+1, c): the normal
/// is the normalised sum of their area vectors (the vector area, independent of c), the area the
/// sum of their areas. Node order right-handed about the outward normal.
template <int Dim>
KOKKOS_INLINE_FUNCTION FaceGeometry faceGeometry(const Real x[][3], int nn, bool axisym)
{
  using namespace contact_math;
  FaceGeometry f;
  if constexpr (Dim == 1)
  {
    const Real len = x[0][0] - x[1][0];
    for (int d = 0; d < 3; ++d)
      f.c[d] = x[0][d], f.n[d] = 0;
    f.n[0] = len > 0 ? 1.0 : len < 0 ? -1.0 : 0.0;
    f.area = 1.0;
    f.diameter = abs(len);
    f.valid = len != 0 ? 1 : 0;
    (void)nn;
    (void)axisym;
    return f;
  }
  for (int d = 0; d < 3; ++d)
  {
    f.c[d] = 0;
    for (int i = 0; i < nn; ++i)
      f.c[d] += x[i][d];
    f.c[d] /= nn;
  }
  f.diameter = cp_geometry::faceDiameter(x, nn);
  Real vec[3] = {0, 0, 0};
  if constexpr (Dim == 2)
  {
    const Real tx = x[1][0] - x[0][0], ty = x[1][1] - x[0][1];
    const Real len = kmath::sqrt(tx * tx + ty * ty);
    vec[0] = ty, vec[1] = -tx;
    f.area = axisym ? 0.5 * (x[0][0] + x[1][0]) * len : len;
  }
  else
  {
    // a triangle is its own single "pallet"; a quad has four about its centroid
    const bool tri = nn == 3;
    const int ntri = tri ? 1 : nn;
    const Real *o = tri ? x[0] : f.c;
    f.area = 0;
    for (int k = 0; k < ntri; ++k)
    {
      const Real *p = tri ? x[1] : x[k];
      const Real *q = tri ? x[2] : x[cp_geometry::nextVertex(k, nn)];
      const Real a[3] = {p[0] - o[0], p[1] - o[1], p[2] - o[2]};
      const Real b[3] = {q[0] - o[0], q[1] - o[1], q[2] - o[2]};
      Real cr[3];
      cross(a, b, cr);
      for (int d = 0; d < 3; ++d)
        vec[d] += 0.5 * cr[d];
      f.area += 0.5 * norm(cr);
    }
  }
  const Real l = norm(vec);
  f.valid = (l > 0 && f.area > 0) ? 1 : 0;
  for (int d = 0; d < 3; ++d)
    f.n[d] = l > 0 ? vec[d] / l : 0;
  return f;
}

namespace cp_geometry
{
/// \brief Sub-steps C-D on the plane of g.n through g.x_cp (4.3-4.8): basis, projected faces,
/// overlap area Ac and POC, projected areas, area fractions and the closure u0.
template <int Dim>
KOKKOS_INLINE_FUNCTION void projectOnCommonPlane(CpGeometry &g, const Real x1[][3], int n1,
                                                 const Real x2[][3], int n2, bool ax)
{
  using namespace contact_math;
  Real xi_c = 0, eta_c = 0;
  if constexpr (Dim == 1)
  { // the common cross-section; the basis only spans the (unused) shear plane
    cpBasis(g.n, g.e1, g.e2);
    g.Ac = min(g.A1, g.A2);
    g.A1p = g.A1, g.A2p = g.A2;
  }
  else if constexpr (Dim == 2)
  {
    // (4.5, 4.6) project on the CP line: one tangent t_cp = (-n_y, n_x)
    g.e1[0] = -g.n[1], g.e1[1] = g.n[0], g.e2[2] = 1;
    Real lo[2], hi[2];
    for (int f = 0; f < 2; ++f)
    {
      const Real(*x)[3] = f == 0 ? x1 : x2;
      lo[f] = 1e300, hi[f] = -1e300;
      for (int i = 0; i < 2; ++i)
      {
        const Real d[3] = {x[i][0] - g.x_cp[0], x[i][1] - g.x_cp[1], 0};
        const Real xi = dot(d, g.e1);
        lo[f] = min(lo[f], xi), hi[f] = max(hi[f], xi);
      }
    }
    const Real xa = max(lo[0], lo[1]), xb = min(hi[0], hi[1]);
    const Real L = max(0.0, xb - xa);
    if (!ax)
    {
      g.Ac = L;
      g.A1p = hi[0] - lo[0], g.A2p = hi[1] - lo[1];
      xi_c = 0.5 * (xa + xb);
    }
    else
    {
      // (D6b): r along the CP line is linear in xi; trapezoid area and centroid per radian
      const Real r0 = g.x_cp[0], tr = g.e1[0];
      const Real ra = r0 + xa * tr, rb = r0 + xb * tr;
      g.Ac = 0.5 * (ra + rb) * L;
      g.A1p = 0.5 * (2 * r0 + (lo[0] + hi[0]) * tr) * (hi[0] - lo[0]);
      g.A2p = 0.5 * (2 * r0 + (lo[1] + hi[1]) * tr) * (hi[1] - lo[1]);
      xi_c = (L > 0 && ra + rb > 0) ? xa + L * (ra + 2 * rb) / (3 * (ra + rb)) : 0.5 * (xa + xb);
    }
  }
  else
  {
    cpBasis(g.n, g.e1, g.e2);
    Real P[2][4][2];
    const int nv[2] = {n1, n2};
    Real area[2];
    for (int f = 0; f < 2; ++f)
    {
      const Real(*x)[3] = f == 0 ? x1 : x2;
      for (int i = 0; i < nv[f]; ++i)
      {
        const Real d[3] = {x[i][0] - g.x_cp[0], x[i][1] - g.x_cp[1], x[i][2] - g.x_cp[2]};
        P[f][i][0] = dot(d, g.e1), P[f][i][1] = dot(d, g.e2);
      }
      area[f] = polygonSignedArea(P[f], nv[f]);
      if (area[f] < 0) // face 2 projects clockwise (n2 ~ -n)
        reversePolygon(P[f], nv[f]), area[f] = -area[f];
    }
    g.A1p = area[0], g.A2p = area[1];
    if (area[0] > 0 && area[1] > 0)
    {
      Real A, Mx, My;
      overlapMoments(P[0], n1, P[1], n2, A, Mx, My);
      if (A > 0)
      {
        g.Ac = A;
        xi_c = Mx / A, eta_c = My / A;
      }
    }
  }
  for (int d = 0; d < 3; ++d)
    g.x_poc[d] = g.x_cp[d] + xi_c * g.e1[d] + eta_c * g.e2[d];
  g.f1 = g.A1p > 0 ? min(1.0, g.Ac / g.A1p) : 0;
  g.f2 = g.A2p > 0 ? min(1.0, g.Ac / g.A2p) : 0;
  g.u0 = initialClosure(g);
}

/// Cosines of the tilt between the faces (the angle of n1 to -n2), 3 and 10 degrees: below the
/// first the CP normal is the bisector (D1) for every option; above the second the normal of an
/// edge or corner contact stands alone; a blend linear in the cosine keeps it continuous.
constexpr Real kEdgeCosStart = 0.99862953475457387; // cos(3 deg)
constexpr Real kEdgeCosFull = 0.98480775301220806;  // cos(10 deg)

/// \brief The overlap of faces 1 and 2 along a unit direction t that points from body 1 to
/// body 2: max over face 1's vertices of x.t minus min over face 2's of x.t (> 0: they overlap
/// by that much along t; <= 0: t separates them).
KOKKOS_INLINE_FUNCTION Real overlapAlong(const Real t[3], const Real x1[][3], int n1,
                                         const Real x2[][3], int n2)
{
  using namespace contact_math;
  Real hi = -1e300, lo = 1e300;
  for (int i = 0; i < n1; ++i)
    hi = max(hi, dot(x1[i], t));
  for (int i = 0; i < n2; ++i)
    lo = min(lo, dot(x2[i], t));
  return hi - lo;
}

/// \brief The normal of an edge or corner contact (4.2). Faces tilted by more than 3 degrees
/// meet with an edge or a corner of one on the other's face, which pushes along its own normal,
/// not along the bisector. Of the two face normals t1 = n1 and t2 = -n2, the one along which the
/// faces overlap less is the receiving face's (the separating-axis test): n is t1 and t2
/// weighted each by the fourth power of the other's overlap, d2^4 t1 + d1^4 t2 (d clipped at
/// 0), normalised, so equal overlaps give the bisector and swapping the faces reverses n; then
/// blended with the bisector g.n by the tilt. False (the bisector stands) below 3 degrees or
/// when neither normal sees an overlap. The overlaps are of the faces' vertices, not of the
/// bodies: a face that overlaps along neither normal (a gap) keeps the bisector.
KOKKOS_INLINE_FUNCTION bool edgeContactNormal(const CpGeometry &g, const Real x1[][3], int n1,
                                              const Real x2[][3], int n2, Real n_out[3])
{
  using namespace contact_math;
  const Real cos_tilt = -dot(g.n1, g.n2);
  if (cos_tilt >= kEdgeCosStart)
    return false;
  const Real t2[3] = {-g.n2[0], -g.n2[1], -g.n2[2]};
  const Real d1 = max(0.0, overlapAlong(g.n1, x1, n1, x2, n2));
  const Real d2 = max(0.0, overlapAlong(t2, x1, n1, x2, n2));
  if (d1 + d2 <= 0)
    return false;
  // the fourth power: a face whose overlap is a third of the other's takes 99 % of the weight
  const Real r1 = d1 / max(d1, d2), r2 = d2 / max(d1, d2);
  const Real w1 = r2 * r2 * r2 * r2, w2 = r1 * r1 * r1 * r1;
  Real t[3];
  for (int d = 0; d < 3; ++d)
    t[d] = w1 * g.n1[d] + w2 * t2[d];
  const Real lt = norm(t);
  if (!(lt > 0)) // opposite normals with equal weights: no direction to prefer
    return false;
  const Real s = min(1.0, (kEdgeCosStart - cos_tilt) / (kEdgeCosStart - kEdgeCosFull));
  for (int d = 0; d < 3; ++d)
    n_out[d] = (1 - s) * g.n[d] + s * t[d] / lt;
  const Real l = norm(n_out);
  for (int d = 0; d < 3; ++d)
    n_out[d] /= l;
  return true;
}
} // namespace cp_geometry

/// \brief Sub-steps B-D for one face pair (section 4). `x1`, `x2`: half-step node positions of
/// face 1 (smaller global key, 3.5) and face 2; `n1`, `n2` their node counts (1 in 1D, 2 in 2D;
/// 3 or 4 in 3D; in 1D `x1[1]`, `x2[1]` hold the elements' other nodes, see faceGeometry).
/// `axisym` selects the per-radian 2D geometry of 4.6 (ignored in 1D and 3D).
///
/// 1D: two point faces with opposing normals share the whole 1 m^2 cross-section: Ac = A1p =
/// A2p = 1 m^2, f1 = f2 = 1, n = n1, x_poc = the midpoint, u0 = (c1 - c2).n (> 0: overlap).
///
/// The result is valid whenever both faces have positive area and n1 != n2; Ac may then still be
/// zero (no overlap). Activity (3.4) is cpIsActive(). Swapping the faces reverses n and leaves
/// Ac, x_poc and u0 unchanged (to round-off).
template <int Dim>
KOKKOS_INLINE_FUNCTION CpGeometry computeCommonPlane(const Real x1[][3], int n1, const Real x2[][3],
                                                     int n2, bool axisym,
                                                     bool impact_normal = false)
{
  using namespace contact_math;
  static_assert(Dim >= 1 && Dim <= 3, "computeCommonPlane: Dim is 1, 2 or 3");
  CpGeometry g;
  const bool ax = Dim == 2 && axisym;
  const FaceGeometry f1 = faceGeometry<Dim>(x1, n1, ax);
  const FaceGeometry f2 = faceGeometry<Dim>(x2, n2, ax);
  Real dn[3];
  for (int d = 0; d < 3; ++d)
  {
    g.c1[d] = f1.c[d], g.c2[d] = f2.c[d], g.n1[d] = f1.n[d], g.n2[d] = f2.n[d];
    g.x_cp[d] = 0.5 * (f1.c[d] + f2.c[d]);
    dn[d] = f1.n[d] - f2.n[d];
  }
  g.A1 = f1.area, g.A2 = f2.area, g.h1 = f1.diameter, g.h2 = f2.diameter;
  g.Ac = g.A1p = g.A2p = g.f1 = g.f2 = g.u0 = 0;
  const Real ldn = norm(dn);
  g.valid = (f1.valid && f2.valid && ldn > 1e-6) ? 1 : 0;
  for (int d = 0; d < 3; ++d)
  {
    g.n[d] = g.valid ? dn[d] / ldn : 0;
    g.x_poc[d] = g.x_cp[d];
    g.e1[d] = g.e2[d] = 0;
  }
  if (!g.valid)
    return g;
  if constexpr (Dim >= 2)
  { // the edge-contact normal needs only the face normals and vertices: chosen before the
    // projection, which then runs once on the plane it defines
    Real n_edge[3];
    if (impact_normal && cp_geometry::edgeContactNormal(g, x1, n1, x2, n2, n_edge))
      for (int d = 0; d < 3; ++d)
        g.n[d] = n_edge[d];
  }
  cp_geometry::projectOnCommonPlane<Dim>(g, x1, n1, x2, n2, ax);
  return g;
}

/// \brief Shape-function weights of the point of contact on one face (8.2): the face and the POC
/// are projected on the CP; segment (1 - s, s), triangle barycentric, quad inverse bilinear map
/// (Newton, <= 10 iterations); weights clipped to [0, 1] and renormalised.
KOKKOS_INLINE_FUNCTION void pocWeights(const Real x[][3], int nn, const CpGeometry &g, Real w[])
{
  using namespace contact_math;
  if (nn == 1)
  { // a point face (1D)
    w[0] = 1;
    return;
  }
  Real q[4][2], pp[2];
  const Real dp[3] = {g.x_poc[0] - g.x_cp[0], g.x_poc[1] - g.x_cp[1], g.x_poc[2] - g.x_cp[2]};
  pp[0] = dot(dp, g.e1), pp[1] = dot(dp, g.e2);
  for (int i = 0; i < nn; ++i)
  {
    const Real d[3] = {x[i][0] - g.x_cp[0], x[i][1] - g.x_cp[1], x[i][2] - g.x_cp[2]};
    q[i][0] = dot(d, g.e1), q[i][1] = dot(d, g.e2);
  }
  if (nn == 2)
  {
    const Real L = q[1][0] - q[0][0];
    const Real s = L != 0 ? (pp[0] - q[0][0]) / L : 0.5;
    w[0] = 1 - s, w[1] = s;
  }
  else if (nn == 3)
  {
    const Real A = cp_geometry::cross2(q[1][0] - q[0][0], q[1][1] - q[0][1], q[2][0] - q[0][0],
                                       q[2][1] - q[0][1]);
    for (int i = 0; i < 3; ++i)
    {
      const int j = (i + 1) % 3, k = (i + 2) % 3;
      w[i] = A != 0 ? cp_geometry::cross2(q[j][0] - pp[0], q[j][1] - pp[1], q[k][0] - pp[0],
                                          q[k][1] - pp[1]) /
                          A
                    : 1.0 / 3.0;
    }
  }
  else
  {
    Real s = 0.5, t = 0.5;
    for (int it = 0; it < 10; ++it)
    {
      Real N[4] = {(1 - s) * (1 - t), s * (1 - t), s * t, (1 - s) * t};
      Real R[2] = {-pp[0], -pp[1]};
      for (int i = 0; i < 4; ++i)
        R[0] += N[i] * q[i][0], R[1] += N[i] * q[i][1];
      Real Js[2], Jt[2];
      for (int d = 0; d < 2; ++d)
      {
        Js[d] = (1 - t) * (q[1][d] - q[0][d]) + t * (q[2][d] - q[3][d]);
        Jt[d] = (1 - s) * (q[3][d] - q[0][d]) + s * (q[2][d] - q[1][d]);
      }
      const Real det = Js[0] * Jt[1] - Js[1] * Jt[0];
      if (det == 0)
        break;
      const Real ds = (R[0] * Jt[1] - R[1] * Jt[0]) / det, dt = (Js[0] * R[1] - Js[1] * R[0]) / det;
      s -= ds, t -= dt;
      if (abs(ds) + abs(dt) < 1e-14)
        break;
    }
    w[0] = (1 - s) * (1 - t), w[1] = s * (1 - t), w[2] = s * t, w[3] = (1 - s) * t;
  }
  Real sum = 0;
  for (int i = 0; i < nn; ++i)
    w[i] = min(1.0, max(0.0, w[i])), sum += w[i];
  for (int i = 0; i < nn; ++i)
    w[i] = sum > 0 ? w[i] / sum : 1.0 / nn;
}

/// \brief Nodal weights of the CP force on face `face` (1 or 2), section 8. Rule Penetration:
/// node penetrations through the CP, delta_i = max(0, +-(x_i - x_poc).n), (17)-(18), blended with
/// the shape-function weights at the POC (8.2) over the length L = `blend` [m]:
///   w_i = (delta_i + N L w_poc_i) / (sum delta + N L),   N = nn,
/// i.e. penetration weights where the penetrations are large against L, the POC split where
/// they are small (aligned faces), continuously in between. L = 0 gives (17)-(18) exactly.
/// pocWeights() when the rule is Poc or sum(delta) + N L <= 1e-12 h_f (nothing penetrates).
/// Weights sum to 1. Face 1 receives -F*w_i, face 2 +F*w_j with F = Fn n + Fs.
///
/// Why the blend: nodes penetrating by delta +- e get extra forces -+F e/(sum delta): a spring of
/// stiffness F/(sum delta) on the face's rotation (zigzag) mode, seen by neither the implicit
/// update nor the limit (19). For a stiff joint (closure ~ 1e-7 m at GPa) it exceeds the
/// leapfrog's bound k dt^2/m <= 4 by orders of magnitude and the mode grows ~1000x per cycle.
/// The blend caps the stiffness at F/(N L); the runtime uses L = dt^2 |F|/(2 m*)
/// (ContactForces.cpp; docs/theory.md, contact runtime, item 13).
KOKKOS_INLINE_FUNCTION void nodalWeights(const Real x[][3], int nn, const CpGeometry &g, int face,
                                         DistributionRule rule, Real w[], Real blend = 0)
{
  using namespace contact_math;
  if (rule == DistributionRule::Penetration)
  {
    const Real sign = face == 1 ? 1.0 : -1.0;
    Real delta[kMaxFaceNodes], sum = 0;
    for (int i = 0; i < nn; ++i)
    {
      const Real d[3] = {x[i][0] - g.x_poc[0], x[i][1] - g.x_poc[1], x[i][2] - g.x_poc[2]};
      delta[i] = max(0.0, sign * dot(d, g.n));
      sum += delta[i];
    }
    const Real L = nn * max(blend, 0.0);
    if (sum + L > 1e-12 * (face == 1 ? g.h1 : g.h2))
    {
      if (L > 0)
        pocWeights(x, nn, g, w);
      for (int i = 0; i < nn; ++i)
        w[i] = (delta[i] + (L > 0 ? L * w[i] : 0.0)) / (sum + L);
      return;
    }
  }
  pocWeights(x, nn, g, w);
}

/// \brief Tie points of a sticky CP in 2D (docs/theory.md 11.2): the two Gauss points of the
/// overlap segment on the CP line, mid +- L/(2 sqrt 3), and the shape-function weights of both
/// faces at each (w1[q], w2[q], q = 0, 1). Tying V1 = V2 at two points makes two coincident
/// segments move as one (the node-to-node tie of a merged mesh); one point per CP, at the POC,
/// left their relative zig-zag free.
KOKKOS_INLINE_FUNCTION void tieWeights2D(const Real x1[][3], const Real x2[][3],
                                         const CpGeometry &g, Real w1[2][kMaxFaceNodes],
                                         Real w2[2][kMaxFaceNodes])
{
  using namespace contact_math;
  Real lo = -1e300, hi = 1e300;
  for (int f = 0; f < 2; ++f)
  {
    const Real(*x)[3] = f == 0 ? x1 : x2;
    Real flo = 1e300, fhi = -1e300;
    for (int i = 0; i < 2; ++i)
    {
      const Real d[3] = {x[i][0] - g.x_cp[0], x[i][1] - g.x_cp[1], 0};
      const Real xi = dot(d, g.e1);
      flo = min(flo, xi), fhi = max(fhi, xi);
    }
    lo = max(lo, flo), hi = min(hi, fhi);
  }
  const Real half = 0.5 / kmath::sqrt(3.0) * max(0.0, hi - lo);
  for (int q = 0; q < 2; ++q)
  {
    const Real xi = 0.5 * (lo + hi) + (q == 0 ? -half : half);
    CpGeometry gq = g;
    for (int d = 0; d < 3; ++d)
      gq.x_poc[d] = g.x_cp[d] + xi * g.e1[d];
    pocWeights(x1, 2, gq, w1[q]);
    pocWeights(x2, 2, gq, w2[q]);
  }
}

/// \brief Activity test of 3.2/3.4: Ac > epsilon_A * min(A1, A2).
KOKKOS_INLINE_FUNCTION bool cpIsActive(const CpGeometry &g)
{
  return g.valid && g.Ac > kAreaEpsilon * contact_math::min(g.A1, g.A2);
}

} // namespace scpdyn
