#pragma once
/// \file ContactSearch.hpp
/// \brief Detection of common planes (docs/theory.md 3.1-3.2): half-step face geometry, global
/// sorting bins (a uniform grid, compressed rows built by count -> scan -> fill) and the
/// candidate face pairs with positive overlap. Device kernels; results are deterministic (every
/// bin and every row is sorted).
#include "contact/CommonPlaneGeometry.hpp"
#include "contact/ContactData.hpp"
#include "core/Fields.hpp"

namespace scpdyn
{

/// \brief Bins per search reach along an axis: finer bins make the searched region (the bins a
/// face's stencil covers) approach the cube of edge 2 reach; 3 is the cheapest on a jointed grid.
constexpr int kBinSplit = 3;

/// \brief Faces in a bin are grouped by normal: classes 2k / 2k+1 hold normals within 14 degrees
/// of +e_k / -e_k, class 6 the rest. Two faces of classes on the same or perpendicular axes are
/// at most 28 or 118 degrees apart and fail rule 2 (normals at least 120 degrees apart), so a
/// face of class c only visits classes c^1 and 6 (a face of class 6 visits all).
constexpr int kNormalClasses = 7;

/// \brief Centroid, outward normal, area and diameter of every contact face at x^{n+1/2}.
struct FaceGeometryData
{
  VectorView centroid, normal;
  RealView area, diameter;
  RealView radius; ///< largest centroid-vertex distance [m] (bounds the projected face)
  IndexView valid;
  Real h_max = 0; ///< largest face diameter [m]
};

/// \brief Faces sorted into a uniform grid of cubic bins of edge `size` (compressed rows). The
/// search reach `reach` (the bin_size asked for) spans several bins, so that the stencil of a
/// face hugs the cube |x_j - x_i| <= reach (per axis) that findCandidatePairs searches.
struct FaceBins
{
  Real lo[3] = {0, 0, 0};
  Real size = 1;
  Real reach = 1;
  int dims[3] = {1, 1, 1};
  IndexView offsets; ///< kNormalClasses x bins + 1 (row of a face: class x bins + bin)
  IndexView faces;   ///< face ids, ascending within a row
  IndexView bin_of;  ///< row of every face
  /// centroid, normal, radius, area of faces(q), in row order: the inner search loop streams
  /// them instead of gathering four arrays at random face ids
  DeviceView<Real *[8]> packed;
};

/// \brief Candidate face pairs (face1 < face2), sorted by (face1, face2).
struct CandidatePairs
{
  Index count = 0;
  IndexView face1, face2;
};

/// \brief Half-step positions of the nodes of face `f`: x + half_dt v (sub-step A) [m].
KOKKOS_INLINE_FUNCTION int gatherHalfStep(const ContactFaceData &F, Index f, const VectorView &x,
                                          const VectorView &v, Real half_dt, Real xh[][3])
{
  const int nn = F.num_nodes(f);
  for (int a = 0; a < nn; ++a)
  {
    const Index k = F.nodes(f, a);
    for (int d = 0; d < 3; ++d)
      xh[a][d] = x(k, d) + half_dt * v(k, d);
  }
  return nn;
}

/// \brief 1D: half-step position of the element's other node behind point face `f` into
/// `xh[1]` (after the face node in `xh[0]`), the layout faceGeometry<1> reads.
KOKKOS_INLINE_FUNCTION void gatherBackNode(const ContactFaceData &F, Index f, const VectorView &x,
                                           const VectorView &v, Real half_dt, Real xh[][3])
{
  const Index k = F.back(f);
  for (int d = 0; d < 3; ++d)
    xh[1][d] = x(k, d) + half_dt * v(k, d);
}

/// \brief Sub-steps A-D for the face pair (f1, f2) in dimension `dim` (1, 2 or 3); `x1`, `x2`
/// receive the half-step node positions (1D: and the elements' other nodes in slot 1).
KOKKOS_INLINE_FUNCTION CpGeometry pairGeometry(const ContactFaceData &F, Index f1, Index f2,
                                               const VectorView &x, const VectorView &v,
                                               Real half_dt, int dim, bool axisym, Real x1[][3],
                                               Real x2[][3])
{
  const int n1 = gatherHalfStep(F, f1, x, v, half_dt, x1);
  const int n2 = gatherHalfStep(F, f2, x, v, half_dt, x2);
  if (dim == 1)
  {
    gatherBackNode(F, f1, x, v, half_dt, x1);
    gatherBackNode(F, f2, x, v, half_dt, x2);
    return computeCommonPlane<1>(x1, n1, x2, n2, false);
  }
  return dim == 2 ? computeCommonPlane<2>(x1, n1, x2, n2, axisym)
                  : computeCommonPlane<3>(x1, n1, x2, n2, axisym);
}

/// \brief Face geometry at x^{n+1/2} = x + dt/2 v for every contact face; sets h_max.
void computeFaceGeometry(const ContactFaceData &F, const NodeFields &nodes, Real dt, int dim,
                         bool axisym, FaceGeometryData &G);

/// \brief Step 3: sort the faces by their centroids into bins of edge bin_size / kBinSplit, for
/// a search of reach `bin_size` per axis, grouped by normal class (kNormalClasses). The grid is
/// coarsened when it would have more bins than faces (+64).
void sortFacesIntoBins(const FaceGeometryData &G, Index num_faces, int dim, Real bin_size,
                       FaceBins &bins);

/// \brief Candidate pairs of 3.2 among faces whose centroids are within `bins.reach` of each
/// other along every axis: opposing normals, different elements, no shared node, each face on
/// the right side of the other (within candidatePenetration(): half the smaller face plus the
/// closure the divergence check accepts), gap -u0 <= g_search, and overlap
/// Ac > eps_A min(A1, A2) at the half step. Cheap bounds (lateral distance of the centroids,
/// gap, projected bounding boxes) reject before the polygon clipping only pairs the clipping
/// would reject (see ContactSearch.cpp); each pair is clipped once.
CandidatePairs findCandidatePairs(const ContactFaceData &F, const FaceGeometryData &G,
                                  const FaceBins &bins, const NodeFields &nodes, Real dt, int dim,
                                  bool axisym, Real g_search);

} // namespace scpdyn
