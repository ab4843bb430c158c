// Common-plane detection: face geometry, sorting bins, candidate pairs (docs/theory.md 3.1-3.2).
#include "contact/ContactSearch.hpp"
#include "contact/ContactChecks.hpp"

#include <cmath>

namespace scpdyn
{
namespace
{

/// Exclusive scan of `counts` (n entries) into `offsets` (n + 1 entries); returns the total.
Index exclusiveScan(const IndexView &counts, const IndexView &offsets, Index n)
{
  Index total = 0;
  Kokkos::parallel_scan(
      "scpdyn::contact::scan", Kokkos::RangePolicy<ExecSpace>(0, n + 1),
      KOKKOS_LAMBDA(const Index i, Index &sum, const bool final) {
        const Index c = i < n ? counts(i) : 0;
        if (final)
          offsets(i) = sum;
        sum += c;
      },
      total);
  return total;
}

/// Ascending insertion sort of each row [offsets(r), offsets(r+1)) of `values` (rows are short).
void sortRows(const IndexView &offsets, const IndexView &values, Index rows)
{
  Kokkos::parallel_for(
      "scpdyn::contact::sortRows", Kokkos::RangePolicy<ExecSpace>(0, rows),
      KOKKOS_LAMBDA(const Index r) {
        const Index b = offsets(r), e = offsets(r + 1);
        for (Index i = b + 1; i < e; ++i)
        {
          const Index key = values(i);
          Index j = i - 1;
          while (j >= b && values(j) > key)
          {
            values(j + 1) = values(j);
            --j;
          }
          values(j + 1) = key;
        }
      });
}

KOKKOS_INLINE_FUNCTION bool shareNode(const ContactFaceData &F, Index f, Index g)
{
  for (int a = 0; a < F.num_nodes(f); ++a)
    for (int b = 0; b < F.num_nodes(g); ++b)
      if (F.nodes(f, a) == F.nodes(g, b))
        return true;
  return false;
}

/// Rule 2 threshold on n_f.n_g: normals at least 120 degrees apart.
constexpr Real kOpposingNormals = -0.5;

/// Candidates a face keeps from the counting pass, so that the fill pass clips nothing again
/// (a face of a jointed grid has 1-2 candidates of higher id; longer rows are searched again).
constexpr int kCachedPairs = 4;

/// Everything the search kernel reads.
struct SearchData
{
  ContactFaceData F;
  FaceGeometryData G;
  FaceBins B;
  VectorView x, v;
  Real half_dt, g_search;
  int dim;
  bool axisym;
  Real r_max; ///< the largest face radius (FaceBins::packed)
  Real a_max; ///< the largest aperture of the surfaces
};

KOKKOS_INLINE_FUNCTION int binOf(Real xc, Real lo, Real size, int n)
{
  const int i = int((xc - lo) / size);
  return i < 0 ? 0 : i >= n ? n - 1 : i;
}

/// cos 14 degrees: see kNormalClasses (14 + 90 + 14 = 118 < 120 degrees, with room for
/// round-off in n_f.n_g)
constexpr Real kAxisCos = 0.9703;

KOKKOS_INLINE_FUNCTION int normalClass(Real n0, Real n1, Real n2)
{
  const Real n[3] = {n0, n1, n2};
  for (int k = 0; k < 3; ++k)
  {
    if (n[k] >= kAxisCos)
      return 2 * k;
    if (n[k] <= -kAxisCos)
      return 2 * k + 1;
  }
  return kNormalClasses - 1;
}

/// Necessary conditions of a candidate from the centroids c, normals n and radii r alone
/// (a = face i, b = face j; packed as in FaceBins::packed). Each rejects only pairs that
/// computeCommonPlane + the gap test would reject (up to round-off far below the margins):
///  (rule 2, nn = n_a.n_b < -1/2, is the caller's;)
///  * lateral distance: every projected vertex of a face lies within r of its projected
///    centroid (the centroid is the vertex average, projection shortens), so the overlap is
///    empty when the centroids are more than r_a + r_b apart in the CP plane;
///  * gap: with n = (n_a - n_b)/L, L = |n_a - n_b|, dc = c_b - c_a and x_poc = x_cp + p,
///    (D7) gives -u0 = dc.n + 2 p.(n_a + n_b)/L exactly; |n_a + n_b|/L = t = sqrt((1+c)/(1-c)),
///    c = n_a.n_b, and the POC lies in both projected discs, |p| <= lat/2 + min(r_a, r_b),
///    so -u0 >= dc.n - t (lat + 2 min(r_a, r_b)) must not exceed g_search.
KOKKOS_INLINE_FUNCTION bool boundsAllowPair(const Real a[8], const Real b[8], Real nn,
                                            Real g_search, Real n_cp[3])
{
  Real dn = 0, dc2 = 0, dn_raw[3];
  for (int d = 0; d < 3; ++d)
    dn_raw[d] = a[3 + d] - b[3 + d];
  const Real L = contact_math::norm(dn_raw);
  for (int d = 0; d < 3; ++d)
  {
    const Real dc = b[d] - a[d];
    n_cp[d] = dn_raw[d] / L;
    dn += dc * n_cp[d];
    dc2 += dc * dc;
  }
  const Real rs = a[6] + b[6];
  const Real lat2 = contact_math::max(0.0, dc2 - dn * dn);
  if (lat2 > rs * rs * (1 + 1e-6))
    return false;
  const Real t = kmath::sqrt(contact_math::max(0.0, (1 + nn) / (1 - nn)));
  const Real lower = dn - t * (kmath::sqrt(lat2) + 2 * contact_math::min(a[6], b[6]));
  return !(lower > g_search + 1e-12 * contact_math::abs(g_search) + 1e-6 * rs);
}

/// 3D: the overlap lies in the intersection of the faces' bounding boxes in the CP plane
/// (basis of cpBasis(n)); a piece of the signed fan split lies in its face's box, so
/// |Ac| <= 16 x that area. False when it is far below eps_A min(A1, A2).
KOKKOS_INLINE_FUNCTION bool boxesOverlap(const Real x1[][3], int n1, const Real x2[][3], int n2,
                                         const Real n[3], Real min_area)
{
  Real e1[3], e2[3];
  cp_geometry::cpBasis(n, e1, e2);
  Real lo[2][2], hi[2][2];
  for (int f = 0; f < 2; ++f)
  {
    const Real(*x)[3] = f == 0 ? x1 : x2;
    const int nv = f == 0 ? n1 : n2;
    for (int k = 0; k < 2; ++k)
      lo[f][k] = 1e300, hi[f][k] = -1e300;
    for (int a = 0; a < nv; ++a)
    {
      const Real p[2] = {contact_math::dot(x[a], e1), contact_math::dot(x[a], e2)};
      for (int k = 0; k < 2; ++k)
        lo[f][k] = contact_math::min(lo[f][k], p[k]), hi[f][k] = contact_math::max(hi[f][k], p[k]);
    }
  }
  Real w[2];
  for (int k = 0; k < 2; ++k)
    w[k] = contact_math::min(hi[0][k], hi[1][k]) - contact_math::max(lo[0][k], lo[1][k]);
  return w[0] > 0 && w[1] > 0 && 16 * w[0] * w[1] > 1e-2 * kAreaEpsilon * min_area;
}

/// Rules of 3.2 for faces i < j that passed boundsAllowPair(); the clipping comes last.
KOKKOS_INLINE_FUNCTION bool isCandidate(const SearchData &S, Index i, Index j, const Real n_cp[3])
{
  const ContactFaceData &F = S.F;
  const FaceGeometryData &G = S.G;
  // ghost-ghost pairs belong to other ranks (2.2, parallel rules)
  if (!G.valid(i) || !G.valid(j) || F.element(i) == F.element(j) || (F.ghost(i) && F.ghost(j)) ||
      !F.active(i) || !F.active(j))
    return false;
  Real side_i = 0, side_j = 0;
  for (int d = 0; d < 3; ++d)
  {
    const Real dc = G.centroid(j, d) - G.centroid(i, d);
    side_i += dc * G.normal(i, d);
    side_j -= dc * G.normal(j, d);
  }
  // rule 5: a joint closes by up to its aperture (beyond it under the cap, 6.2); with half a
  // face alone as the margin, a joint closed by more than h/2 (fine mesh, soft joint) loses its
  // CP at the next search and the blocks pass through each other. (The mean aperture is
  // averageParams(...).a without the rest of the averaging.)
  const Real a = 0.5 * (F.params(F.surface(i)).a + F.params(F.surface(j)).a);
  const Real delta = candidatePenetration(G.diameter(i), G.diameter(j), F.depth(i), F.depth(j), a);
  if (!(side_i > -delta && side_j > -delta) || shareNode(F, i, j))
    return false;
  Real x1[kMaxFaceNodes][3], x2[kMaxFaceNodes][3];
  if (S.dim == 3)
  { // what pairGeometry does, with the box test between the gather and the clipping
    const int n1 = gatherHalfStep(F, i, S.x, S.v, S.half_dt, x1);
    const int n2 = gatherHalfStep(F, j, S.x, S.v, S.half_dt, x2);
    if (!boxesOverlap(x1, n1, x2, n2, n_cp, contact_math::min(G.area(i), G.area(j))))
      return false;
    const CpGeometry g = computeCommonPlane<3>(x1, n1, x2, n2, S.axisym);
    return g.valid && -g.u0 <= S.g_search && cpIsActive(g);
  }
  const CpGeometry g = pairGeometry(F, i, j, S.x, S.v, S.half_dt, S.dim, S.axisym, x1, x2);
  return g.valid && -g.u0 <= S.g_search && cpIsActive(g);
}

/// Bounds of a pair that passes rule 2 (n_f.n_g < -1/2): t = sqrt((1 + c)/(1 - c)) of
/// boundsAllowPair() is below 1/sqrt(3) and |n_f - n_g| above sqrt(3). When both faces are in
/// opposite axis classes (normals within 14.04 degrees of +-e_k, kAxisCos), n_f.n_g <=
/// -cos(28.07 deg), so t <= tan(14.04 deg) and |n_f - n_g| >= 2 kAxisCos; n_cp lies in the same
/// cone about e_k, so its components off e_k are below sin(14.04 deg).
constexpr Real kTiltAny = 0.57736, kBehindAny = 2 / 1.7320;
constexpr Real kTiltAxis = 0.25010, kBehindAxis = 1 / kAxisCos, kAxisSin = 0.24200;

/// Half-widths `hw` per axis of the box about face i's centroid that holds the centroid of
/// every face j of class `cj` that passes boundsAllowPair() and the side test of isCandidate(),
/// from i's radius r_i, diameter h_i and class ci and the largest radius and aperture. With
/// dc = c_j - c_i = lateral + dn n_cp:
///  * lateral: |lateral| <= r_i + r_j (boundsAllowPair's first test);
///  * ahead: dn <= g_search + t (|lateral| + 2 min(r_i, r_j)) (its second test);
///  * behind: dn = (side_i + side_j) / |n_i - n_j| > -2 delta / |n_i - n_j|, since both sides
///    exceed -delta (rule 5, delta <= h_i / 2 + 2a);
/// so |dc| <= sqrt(lateral^2 + dn^2), and for opposite axis classes |dc_k| <= |dn| + s |lateral|
/// along the axis, |lateral| + s |dn| across it. The stencil of a face, not the bins' reach
/// (2 h_max, every face of a grid of equal faces), bounds the faces visited: a face of the
/// Fig. 10 wall visits a third of the faces it did. The same pairs pass (the tests come after).
KOKKOS_INLINE_FUNCTION void pairBox(const SearchData &S, Real r_i, Real h_i, int ci, int cj,
                                    Real hw[3])
{
  const bool axis = ci != kNormalClasses - 1 && cj == (ci ^ 1);
  const Real t = axis ? kTiltAxis : kTiltAny;
  const Real lateral = (r_i + S.r_max) * (1 + 1e-6);
  const Real ahead = S.g_search * (1 + 1e-12) + 1e-6 * lateral + t * (lateral + 2 * r_i);
  const Real behind =
      (axis ? kBehindAxis : kBehindAny) * candidatePenetration(h_i, h_i, h_i, h_i, S.a_max);
  const Real dn = contact_math::max(ahead, behind);
  const Real any = kmath::sqrt(lateral * lateral + dn * dn);
  for (int d = 0; d < 3; ++d)
  {
    const Real w = !axis ? any : d == ci / 2 ? dn + kAxisSin * lateral : lateral + kAxisSin * dn;
    hw[d] = contact_math::min(w, any) * (1 + 1e-9);
  }
}

/// Calls visit(j) for every candidate j > i (in no particular order). The stencil is the block of bins
/// that holds the box |c_j - c_i| <= hw per axis (pairBox() for each class visited, or the
/// bins' reach in 1D); the box itself is tested per face, so the result does not depend on
/// where the bin boundaries fall.
template <class Visit>
KOKKOS_INLINE_FUNCTION void forEachCandidate(const SearchData &S, Index i, Visit &&visit)
{
  // an inactive face (an interior face erosion has not exposed, 11.6) is never a candidate:
  // tested first, so a part's many interior faces cost a load each, not a pair test each
  if (!S.F.active(i))
    return;
  const FaceBins &B = S.B;
  Real a[8];
  for (int d = 0; d < 3; ++d)
    a[d] = S.G.centroid(i, d), a[3 + d] = S.G.normal(i, d);
  a[6] = S.G.radius(i), a[7] = S.G.area(i);
  const int ci = normalClass(a[3], a[4], a[5]);
  const int other = kNormalClasses - 1;
  int visit_class[kNormalClasses], nc = 0;
  for (int k = 0; k < kNormalClasses; ++k)
    if (ci == other || k == other || k == (ci ^ 1))
      visit_class[nc++] = k;
  const Index ncells = Index(B.dims[0]) * B.dims[1] * B.dims[2];
  for (int m = 0; m < nc; ++m)
  {
    Real hw[3] = {B.reach, B.reach, B.reach}; // 1D point faces have no radius: the bins' reach
    if (S.dim > 1)
      pairBox(S, a[6], S.G.diameter(i), ci, visit_class[m], hw);
    int blo[3], bhi[3];
    for (int d = 0; d < 3; ++d)
    {
      blo[d] = binOf(a[d] - hw[d], B.lo[d], B.size, B.dims[d]);
      bhi[d] = binOf(a[d] + hw[d], B.lo[d], B.size, B.dims[d]);
    }
    // rows are class-major, so a run of bins along x is one contiguous range of faces
    for (int cz = blo[2]; cz <= bhi[2]; ++cz)
      for (int cy = blo[1]; cy <= bhi[1]; ++cy)
      {
        const Index r = visit_class[m] * ncells + blo[0] + B.dims[0] * (cy + B.dims[1] * cz);
        const Index q_end = B.offsets(r + bhi[0] - blo[0] + 1);
        for (Index q = B.offsets(r); q < q_end; ++q)
        {
          const Index j = B.faces(q);
          if (j <= i || !S.F.active(j))
            continue;
          const Real nn = a[3] * B.packed(q, 3) + a[4] * B.packed(q, 4) + a[5] * B.packed(q, 5);
          if (!(nn < kOpposingNormals))
            continue;
          Real b[8];
          for (int k = 0; k < 8; ++k)
            b[k] = B.packed(q, k);
          if (contact_math::abs(b[0] - a[0]) > hw[0] || contact_math::abs(b[1] - a[1]) > hw[1] ||
              contact_math::abs(b[2] - a[2]) > hw[2])
            continue;
          Real n_cp[3] = {0, 0, 0};
          // 1D (point faces, a handful of them): rule 2 only, the bounds are not needed
          if ((S.dim == 1 || boundsAllowPair(a, b, nn, S.g_search, n_cp)) &&
              isCandidate(S, i, j, n_cp))
            visit(j);
        }
      }
  }
}

} // namespace

void computeFaceGeometry(const ContactFaceData &F, const NodeFields &nodes, Real dt, int dim,
                         bool axisym, FaceGeometryData &G)
{
  const Index nf = F.count;
  if (G.area.extent(0) != size_t(nf))
  {
    G.centroid = VectorView("contact_face_centroid", size_t(nf));
    G.normal = VectorView("contact_face_normal", size_t(nf));
    G.area = RealView("contact_face_area", size_t(nf));
    G.diameter = RealView("contact_face_diameter", size_t(nf));
    G.radius = RealView("contact_face_radius", size_t(nf));
    G.valid = IndexView("contact_face_valid", size_t(nf));
  }
  auto x = nodes.x, v = nodes.v;
  auto Gd = G;
  const Real half_dt = 0.5 * dt;
  Real h_max = 0;
  Kokkos::parallel_reduce(
      "scpdyn::contact::faceGeometry", Kokkos::RangePolicy<ExecSpace>(0, nf),
      KOKKOS_LAMBDA(const Index f, Real &hm) {
        Real xh[kMaxFaceNodes][3];
        const int nn = gatherHalfStep(F, f, x, v, half_dt, xh);
        if (dim == 1)
          gatherBackNode(F, f, x, v, half_dt, xh);
        const FaceGeometry g = dim == 1   ? faceGeometry<1>(xh, nn, false)
                               : dim == 2 ? faceGeometry<2>(xh, nn, axisym)
                                          : faceGeometry<3>(xh, nn, axisym);
        for (int d = 0; d < 3; ++d)
        {
          Gd.centroid(f, d) = g.c[d];
          Gd.normal(f, d) = g.n[d];
        }
        Gd.area(f) = g.area;
        Gd.diameter(f) = g.diameter;
        Real r2 = 0;
        for (int a = 0; a < nn; ++a)
        {
          const Real d[3] = {xh[a][0] - g.c[0], xh[a][1] - g.c[1], xh[a][2] - g.c[2]};
          r2 = contact_math::max(r2, contact_math::dot(d, d));
        }
        Gd.radius(f) = kmath::sqrt(r2);
        Gd.valid(f) = g.valid;
        if (g.diameter > hm)
          hm = g.diameter;
      },
      Kokkos::Max<Real>(h_max));
  G.h_max = h_max;
}

void sortFacesIntoBins(const FaceGeometryData &G, Index nf, int dim, Real bin_size, FaceBins &bins)
{
  Real lo[3], hi[3];
  for (int d = 0; d < 3; ++d)
  {
    auto c = G.centroid;
    Kokkos::parallel_reduce(
        "scpdyn::contact::binBoxLo", Kokkos::RangePolicy<ExecSpace>(0, nf),
        KOKKOS_LAMBDA(const Index f, Real &m) { m = c(f, d) < m ? c(f, d) : m; },
        Kokkos::Min<Real>(lo[d]));
    Kokkos::parallel_reduce(
        "scpdyn::contact::binBoxHi", Kokkos::RangePolicy<ExecSpace>(0, nf),
        KOKKOS_LAMBDA(const Index f, Real &m) { m = c(f, d) > m ? c(f, d) : m; },
        Kokkos::Max<Real>(hi[d]));
  }
  const Real reach = bin_size > 0 ? bin_size : 1.0;
  Real size = reach / kBinSplit;
  double total = 0;
  for (int pass = 0; pass < 200; ++pass)
  {
    total = 1;
    for (int d = 0; d < dim; ++d)
      total *= std::floor((hi[d] - lo[d]) / size) + 1;
    if (total <= 1.0 * nf + 64)
      break;
    size *= 1.5;
  }
  bins.size = size;
  bins.reach = reach;
  for (int d = 0; d < 3; ++d)
  {
    bins.lo[d] = nf > 0 ? lo[d] : 0;
    bins.dims[d] = d < dim && nf > 0 ? int(std::floor((hi[d] - lo[d]) / size)) + 1 : 1;
  }
  const Index nbins = Index(bins.dims[0]) * bins.dims[1] * bins.dims[2] * kNormalClasses;
  bins.bin_of = IndexView("contact_bin_of", size_t(nf));
  IndexView counts("contact_bin_counts", size_t(nbins));
  bins.offsets = IndexView("contact_bin_offsets", size_t(nbins) + 1);
  bins.faces = IndexView("contact_bin_faces", size_t(nf));
  auto c = G.centroid, nrm = G.normal;
  auto bin_of = bins.bin_of;
  bins.packed = DeviceView<Real *[8]>("contact_bin_packed", size_t(nf));
  const Real l0 = bins.lo[0], l1 = bins.lo[1], l2 = bins.lo[2];
  const int n0 = bins.dims[0], n1 = bins.dims[1], n2 = bins.dims[2];
  const Index ncells = nbins / kNormalClasses;
  Kokkos::parallel_for(
      "scpdyn::contact::binCount", Kokkos::RangePolicy<ExecSpace>(0, nf),
      KOKKOS_LAMBDA(const Index f) {
        const Index cell = binOf(c(f, 0), l0, size, n0) +
                           n0 * (binOf(c(f, 1), l1, size, n1) + n1 * binOf(c(f, 2), l2, size, n2));
        const Index b = normalClass(nrm(f, 0), nrm(f, 1), nrm(f, 2)) * ncells + cell;
        bin_of(f) = b;
        Kokkos::atomic_add(&counts(b), 1);
      });
  exclusiveScan(counts, bins.offsets, nbins);
  IndexView cursor("contact_bin_cursor", size_t(nbins));
  auto offsets = bins.offsets;
  auto faces = bins.faces;
  Kokkos::parallel_for(
      "scpdyn::contact::binFill", Kokkos::RangePolicy<ExecSpace>(0, nf),
      KOKKOS_LAMBDA(const Index f) {
        const Index b = bin_of(f);
        faces(offsets(b) + Kokkos::atomic_fetch_add(&cursor(b), 1)) = f;
      });
  sortRows(bins.offsets, bins.faces, nbins);
  auto packed = bins.packed;
  auto Gd = G;
  Kokkos::parallel_for(
      "scpdyn::contact::binPack", Kokkos::RangePolicy<ExecSpace>(0, nf),
      KOKKOS_LAMBDA(const Index q) {
        const Index f = faces(q);
        for (int d = 0; d < 3; ++d)
          packed(q, d) = Gd.centroid(f, d), packed(q, 3 + d) = Gd.normal(f, d);
        packed(q, 6) = Gd.radius(f), packed(q, 7) = Gd.area(f);
      });
}

CandidatePairs findCandidatePairs(const ContactFaceData &F, const FaceGeometryData &G,
                                  const FaceBins &bins, const NodeFields &nodes, Real dt, int dim,
                                  bool axisym, Real g_search)
{
  const Index nf = F.count;
  Real r_max = 0, a_max = 0;
  auto radius = G.radius;
  Kokkos::parallel_reduce(
      "scpdyn::contact::searchBounds", Kokkos::RangePolicy<ExecSpace>(0, nf),
      KOKKOS_LAMBDA(const Index f, Real &r, Real &a) {
        r = radius(f) > r ? radius(f) : r;
        const Real af = F.params(F.surface(f)).a;
        a = af > a ? af : a;
      },
      Kokkos::Max<Real>(r_max), Kokkos::Max<Real>(a_max));
  const SearchData S{F, G, bins, nodes.x, nodes.v, 0.5 * dt, g_search, dim, axisym, r_max, a_max};
  IndexView row_count("contact_pair_counts", size_t(nf));
  IndexView row_offsets("contact_pair_offsets", size_t(nf) + 1);
  IndexView cache("contact_pair_cache", size_t(nf) * kCachedPairs);
  CandidatePairs P;

  // count, keeping the first kCachedPairs of each row; rows that overflow are searched again
  Kokkos::parallel_for(
      "scpdyn::contact::candidates", Kokkos::RangePolicy<ExecSpace>(0, nf),
      KOKKOS_LAMBDA(const Index i) {
        Index k = 0;
        forEachCandidate(S, i, [&](Index j) {
          if (k < kCachedPairs)
            cache(i * kCachedPairs + k) = j;
          ++k;
        });
        row_count(i) = k;
      });
  P.count = exclusiveScan(row_count, row_offsets, nf);
  IndexView second("contact_pair_face2", size_t(P.count));
  Kokkos::parallel_for(
      "scpdyn::contact::candidatesFill", Kokkos::RangePolicy<ExecSpace>(0, nf),
      KOKKOS_LAMBDA(const Index i) {
        const Index b = row_offsets(i), n = row_offsets(i + 1) - b;
        if (n <= kCachedPairs)
          for (Index k = 0; k < n; ++k)
            second(b + k) = cache(i * kCachedPairs + k);
        else
        {
          Index k = b;
          forEachCandidate(S, i, [&](Index j) { second(k++) = j; });
        }
      });
  sortRows(row_offsets, second, nf);
  P.face2 = second;
  P.face1 = IndexView("contact_pair_face1", size_t(P.count));
  auto first = P.face1;
  Kokkos::parallel_for(
      "scpdyn::contact::pairFirst", Kokkos::RangePolicy<ExecSpace>(0, nf),
      KOKKOS_LAMBDA(const Index i) {
        for (Index q = row_offsets(i); q < row_offsets(i + 1); ++q)
          first(q) = i;
      });
  return P;
}

} // namespace scpdyn
