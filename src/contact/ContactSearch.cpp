// Common-plane detection: face geometry, sorting bins, candidate pairs (scp-method.md 3.1-3.2).
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

/// Candidate rules of 3.2 for faces i < j.
KOKKOS_INLINE_FUNCTION bool isCandidate(const ContactFaceData &F, const FaceGeometryData &G,
                                        const VectorView &x, const VectorView &v, Real half_dt,
                                        int dim, bool axisym, Real g_search, Index i, Index j)
{
  // ghost-ghost pairs belong to other ranks (2.2, parallel rules)
  if (!G.valid(i) || !G.valid(j) || F.element(i) == F.element(j) || (F.ghost(i) && F.ghost(j)))
    return false;
  Real nn = 0, side_i = 0, side_j = 0;
  for (int d = 0; d < 3; ++d)
  {
    const Real dc = G.centroid(j, d) - G.centroid(i, d);
    nn += G.normal(i, d) * G.normal(j, d);
    side_i += dc * G.normal(i, d);
    side_j -= dc * G.normal(j, d);
  }
  // rule 2, with a margin: faces at right angles (block corners, brick T-junctions) flip the
  // sign of n_f.n_g with round-off and would get a CP at 45 degrees
  if (!(nn < kOpposingNormals))
    return false;
  // rule 5: a joint closes by up to its aperture (beyond it under the cap, 6.2); with half a
  // face alone as the margin, a joint closed by more than h/2 (fine mesh, soft joint) loses its
  // CP at the next search and the blocks pass through each other
  const Real a = averageParams(F.params(F.surface(i)), F.params(F.surface(j))).a;
  const Real delta = candidatePenetration(G.diameter(i), G.diameter(j), a);
  if (!(side_i > -delta && side_j > -delta) || shareNode(F, i, j))
    return false;
  Real x1[kMaxFaceNodes][3], x2[kMaxFaceNodes][3];
  const CpGeometry g = pairGeometry(F, i, j, x, v, half_dt, dim, axisym, x1, x2);
  return g.valid && -g.u0 <= g_search && cpIsActive(g);
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
  Real size = bin_size > 0 ? bin_size : 1.0;
  double total = 0;
  for (int pass = 0; pass < 200; ++pass)
  {
    total = 1;
    for (int d = 0; d < dim; ++d)
      total *= std::floor((hi[d] - lo[d]) / size) + 1;
    if (total <= 4.0 * nf + 64)
      break;
    size *= 1.5;
  }
  bins.size = size;
  for (int d = 0; d < 3; ++d)
  {
    bins.lo[d] = nf > 0 ? lo[d] : 0;
    bins.dims[d] = d < dim && nf > 0 ? int(std::floor((hi[d] - lo[d]) / size)) + 1 : 1;
  }
  const Index nbins = Index(bins.dims[0]) * bins.dims[1] * bins.dims[2];
  bins.bin_of = IndexView("contact_bin_of", size_t(nf));
  IndexView counts("contact_bin_counts", size_t(nbins));
  bins.offsets = IndexView("contact_bin_offsets", size_t(nbins) + 1);
  bins.faces = IndexView("contact_bin_faces", size_t(nf));
  auto c = G.centroid;
  auto bin_of = bins.bin_of;
  const Real l0 = bins.lo[0], l1 = bins.lo[1], l2 = bins.lo[2];
  const int n0 = bins.dims[0], n1 = bins.dims[1], n2 = bins.dims[2];
  Kokkos::parallel_for(
      "scpdyn::contact::binCount", Kokkos::RangePolicy<ExecSpace>(0, nf),
      KOKKOS_LAMBDA(const Index f) {
        auto cell = [&](Real xc, Real l, int n) {
          const int i = int((xc - l) / size);
          return i < 0 ? 0 : i >= n ? n - 1 : i;
        };
        const Index b = cell(c(f, 0), l0, n0) + n0 * (cell(c(f, 1), l1, n1) + n1 * cell(c(f, 2), l2, n2));
        bin_of(f) = b;
        Kokkos::atomic_add(&counts(b), 1);
      });
  exclusiveScan(counts, bins.offsets, nbins);
  IndexView cursor("contact_bin_cursor", size_t(nbins));
  auto offsets = bins.offsets;
  auto faces = bins.faces;
  Kokkos::parallel_for(
      "scpdyn::contact::binFill", Kokkos::RangePolicy<ExecSpace>(0, nf), KOKKOS_LAMBDA(const Index f) {
        const Index b = bin_of(f);
        faces(offsets(b) + Kokkos::atomic_fetch_add(&cursor(b), 1)) = f;
      });
  sortRows(bins.offsets, bins.faces, nbins);
}

CandidatePairs findCandidatePairs(const ContactFaceData &F, const FaceGeometryData &G,
                                  const FaceBins &bins, const NodeFields &nodes, Real dt, int dim,
                                  bool axisym, Real g_search)
{
  const Index nf = F.count;
  auto x = nodes.x, v = nodes.v;
  const Real half_dt = 0.5 * dt;
  const int n0 = bins.dims[0], n1 = bins.dims[1], n2 = bins.dims[2];
  auto offsets = bins.offsets, faces = bins.faces, bin_of = bins.bin_of;
  IndexView row_count("contact_pair_counts", size_t(nf));
  IndexView row_offsets("contact_pair_offsets", size_t(nf) + 1);
  CandidatePairs P;
  IndexView second; // filled on the second pass

  // Both passes walk the same stencil; the first counts, the second writes.
  for (int pass = 0; pass < 2; ++pass)
  {
    Kokkos::parallel_for(
        "scpdyn::contact::candidates", Kokkos::RangePolicy<ExecSpace>(0, nf),
        KOKKOS_LAMBDA(const Index i) {
          const Index b = bin_of(i);
          const int bx = b % n0, by = (b / n0) % n1, bz = b / (n0 * n1);
          Index k = pass == 0 ? 0 : row_offsets(i);
          for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
              for (int dx = -1; dx <= 1; ++dx)
              {
                const int cx = bx + dx, cy = by + dy, cz = bz + dz;
                if (cx < 0 || cy < 0 || cz < 0 || cx >= n0 || cy >= n1 || cz >= n2)
                  continue;
                const Index c = cx + n0 * (cy + n1 * cz);
                for (Index q = offsets(c); q < offsets(c + 1); ++q)
                {
                  const Index j = faces(q);
                  if (j <= i || !isCandidate(F, G, x, v, half_dt, dim, axisym, g_search, i, j))
                    continue;
                  if (pass == 1)
                    second(k) = j;
                  ++k;
                }
              }
          if (pass == 0)
            row_count(i) = k;
        });
    if (pass == 0)
    {
      P.count = exclusiveScan(row_count, row_offsets, nf);
      second = IndexView("contact_pair_face2", size_t(P.count));
    }
  }
  sortRows(row_offsets, second, nf);
  P.face2 = second;
  P.face1 = IndexView("contact_pair_face1", size_t(P.count));
  auto first = P.face1;
  Kokkos::parallel_for(
      "scpdyn::contact::pairFirst", Kokkos::RangePolicy<ExecSpace>(0, nf), KOKKOS_LAMBDA(const Index i) {
        for (Index q = row_offsets(i); q < row_offsets(i + 1); ++q)
          first(q) = i;
      });
  return P;
}

} // namespace scpdyn
