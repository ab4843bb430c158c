#pragma once
/// \file ElementKinematics.hpp
/// \brief Mean shape-function gradients, measures and characteristic lengths of the
/// one-point elements. B[a][i] = (1/V) dV/dx_ai (Flanagan & Belytschko 1981, IJNME 17:679):
/// for any element shape sum_a B[a][i] x_aj = delta_ij exactly, so a linear velocity field
/// gives its exact uniform strain rate (the patch test) on distorted meshes too.
#include "core/Types.hpp"
#include "element/Lanes.hpp"

namespace scpdyn
{

template <ElementType T>
struct ElementTraits
{
  static constexpr int nodes = nodesPerElement(T);
  static constexpr int dim = dimensionOf(T);
};

template <class R>
KOKKOS_INLINE_FUNCTION void cross3(const R a[3], const R b[3], R c[3])
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

/// \brief Line2 in uniaxial strain (cross-section 1 m^2): returns the length (= volume).
KOKKOS_INLINE_FUNCTION Real line2Gradients(const Real x[2][3], Real B[2][3])
{
  const Real L = x[1][0] - x[0][0];
  B[0][0] = -1 / L;
  B[1][0] = 1 / L;
  B[0][1] = B[0][2] = B[1][1] = B[1][2] = 0;
  return L;
}

/// \brief Quad4 (counter-clockwise): returns the area; B in the x-y plane.
KOKKOS_INLINE_FUNCTION Real quad4Gradients(const Real x[4][3], Real B[4][3])
{
  const Real A =
      0.5 * ((x[2][0] - x[0][0]) * (x[3][1] - x[1][1]) - (x[3][0] - x[1][0]) * (x[2][1] - x[0][1]));
  const Real s = 0.5 / A;
  B[0][0] = s * (x[1][1] - x[3][1]);
  B[1][0] = s * (x[2][1] - x[0][1]);
  B[2][0] = s * (x[3][1] - x[1][1]);
  B[3][0] = s * (x[0][1] - x[2][1]);
  B[0][1] = s * (x[3][0] - x[1][0]);
  B[1][1] = s * (x[0][0] - x[2][0]);
  B[2][1] = s * (x[1][0] - x[3][0]);
  B[3][1] = s * (x[2][0] - x[0][0]);
  for (int a = 0; a < 4; ++a)
    B[a][2] = 0;
  return A;
}

/// \brief Axisymmetric volume per radian of a quad (r = x): exact integral of r over the
/// straight-edged quad, from its two triangles (0,1,2) and (0,2,3).
KOKKOS_INLINE_FUNCTION Real quad4RadialVolume(const Real x[4][3])
{
  auto tri = [&](int a, int b, int c) {
    const Real A = 0.5 * ((x[b][0] - x[a][0]) * (x[c][1] - x[a][1]) -
                          (x[c][0] - x[a][0]) * (x[b][1] - x[a][1]));
    return A * (x[a][0] + x[b][0] + x[c][0]) / 3;
  };
  return tri(0, 1, 2) + tri(0, 2, 3);
}

/// \brief Tet4: returns the volume.
KOKKOS_INLINE_FUNCTION Real tet4Gradients(const Real x[4][3], Real B[4][3])
{
  Real e1[3], e2[3], e3[3];
  for (int i = 0; i < 3; ++i)
  {
    e1[i] = x[1][i] - x[0][i];
    e2[i] = x[2][i] - x[0][i];
    e3[i] = x[3][i] - x[0][i];
  }
  cross3(e2, e3, B[1]);
  cross3(e3, e1, B[2]);
  cross3(e1, e2, B[3]);
  const Real six_v = e1[0] * B[1][0] + e1[1] * B[1][1] + e1[2] * B[1][2];
  const Real inv = 1 / six_v;
  for (int i = 0; i < 3; ++i)
  {
    B[1][i] *= inv;
    B[2][i] *= inv;
    B[3][i] *= inv;
    B[0][i] = -(B[1][i] + B[2][i] + B[3][i]);
  }
  return six_v / 6;
}

/// \brief Outward, right-handed faces of the hex (bottom 0-1-2-3 counter-clockwise from +z).
KOKKOS_INLINE_FUNCTION int hexFaceNode(int face, int k)
{
  constexpr int faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                               {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  return faces[face][k];
}

/// \brief One face's share of hex8Gradients(): adds dT/dx to B (unscaled), S.(PxQ) to vol24
/// and keeps the largest squared face area |PxQ|^2 / 4 in amax2. Force-inlined with literal
/// node numbers, so no index table is built or read at run time. R: Real or a lane pack.
template <class R>
KOKKOS_FORCEINLINE_FUNCTION void hex8FaceTerm(const R x[8][3], const R c[3], int ia, int ib, int ic,
                                              int id, R B[8][3], R &vol24, R &amax2)
{
  R S[3], P[3], Q[3], PxQ[3], QxS[3], SxP[3];
  for (int i = 0; i < 3; ++i)
  {
    S[i] = x[ia][i] + x[ib][i] + x[ic][i] + x[id][i] - Real(4) * c[i];
    P[i] = x[ic][i] - x[ia][i];
    Q[i] = x[id][i] - x[ib][i];
  }
  cross3(P, Q, PxQ);
  cross3(Q, S, QxS);
  cross3(S, P, SxP);
  vol24 += S[0] * PxQ[0] + S[1] * PxQ[1] + S[2] * PxQ[2];
  for (int i = 0; i < 3; ++i)
  {
    B[ia][i] += PxQ[i] - QxS[i];
    B[ic][i] += PxQ[i] + QxS[i];
    B[ib][i] += PxQ[i] - SxP[i];
    B[id][i] += PxQ[i] + SxP[i];
  }
  const R a2 = 0.25 * (PxQ[0] * PxQ[0] + PxQ[1] * PxQ[1] + PxQ[2] * PxQ[2]);
  amax2 = LaneOps<R>::max(a2, amax2);
}

/// \brief Hex8: exact trilinear volume and its gradient; also the largest squared face area
/// [m^4] (the characteristic length is V / sqrt(max_face_area2)), which costs nothing here.
///
/// By the divergence theorem V = 1/3 sum_faces int x.n dA, and for a bilinear face (a,b,c,d)
/// int x.n dA = 1/8 S.(P x Q) exactly (warped or not), with S = a+b+c+d, P = c-a, Q = d-b
/// (derived in docs/theory.md). Differentiating T = S.(PxQ) = P.(QxS) = Q.(SxP):
/// dT/da = PxQ - QxS, dT/dc = PxQ + QxS, dT/db = PxQ - SxP, dT/dd = PxQ + SxP.
/// Coordinates are taken relative to the centroid to keep round-off small. The faces are
/// those of hexFaceNode(), in its order. R: Real, or a lane pack of hexes (Lanes.hpp).
template <class R>
KOKKOS_INLINE_FUNCTION R hex8Gradients(const R x[8][3], R B[8][3], R &max_face_area2)
{
  const R zero = LaneOps<R>::broadcast(0);
  R c[3] = {zero, zero, zero};
  for (int a = 0; a < 8; ++a)
    for (int i = 0; i < 3; ++i)
      c[i] += 0.125 * x[a][i];
  for (int a = 0; a < 8; ++a)
    for (int i = 0; i < 3; ++i)
      B[a][i] = zero;
  R vol24 = zero, amax2 = zero;
  hex8FaceTerm(x, c, 0, 3, 2, 1, B, vol24, amax2);
  hex8FaceTerm(x, c, 4, 5, 6, 7, B, vol24, amax2);
  hex8FaceTerm(x, c, 0, 1, 5, 4, B, vol24, amax2);
  hex8FaceTerm(x, c, 1, 2, 6, 5, B, vol24, amax2);
  hex8FaceTerm(x, c, 2, 3, 7, 6, B, vol24, amax2);
  hex8FaceTerm(x, c, 3, 0, 4, 7, B, vol24, amax2);
  max_face_area2 = amax2;
  const R V = vol24 / Real(24);
  const R s = Real(1) / vol24; // (1/24 dT) / V
  for (int a = 0; a < 8; ++a)
    for (int i = 0; i < 3; ++i)
      B[a][i] *= s;
  return V;
}

/// \brief Hex8: exact trilinear volume and its gradient (see above).
template <class R>
KOKKOS_INLINE_FUNCTION R hex8Gradients(const R x[8][3], R B[8][3])
{
  R amax2;
  return hex8Gradients(x, B, amax2);
}

/// \brief Dispatch on the element type: B and measure (length, area or volume).
template <ElementType T>
KOKKOS_INLINE_FUNCTION Real elementGradients(const Real x[][3], Real B[][3])
{
  if constexpr (T == ElementType::Line2)
    return line2Gradients(x, B);
  else if constexpr (T == ElementType::Quad4)
    return quad4Gradients(x, B);
  else if constexpr (T == ElementType::Hex8)
    return hex8Gradients(x, B);
  else
    return tet4Gradients(x, B);
}

KOKKOS_INLINE_FUNCTION Real dist2(const Real a[3], const Real b[3])
{
  const Real d0 = a[0] - b[0], d1 = a[1] - b[1], d2 = a[2] - b[2];
  return d0 * d0 + d1 * d1 + d2 * d2;
}

/// \brief Characteristic length for the Courant limit: Line2 length; Quad4 area / longest
/// side; Hex8 volume / largest face area; Tet4 smallest altitude (3V / largest face area).
/// A cube or square of side h gives h, so S = c dt / h as in the deck.
template <ElementType T>
KOKKOS_INLINE_FUNCTION Real characteristicLength(const Real x[][3], Real measure)
{
  if constexpr (T == ElementType::Line2)
    return measure;
  else if constexpr (T == ElementType::Quad4)
  {
    Real m = 0;
    for (int a = 0; a < 4; ++a)
    {
      const Real d = dist2(x[a], x[(a + 1) % 4]);
      m = d > m ? d : m;
    }
    return measure / kmath::sqrt(m);
  }
  else if constexpr (T == ElementType::Hex8)
  {
    Real amax = 0;
    for (int f = 0; f < 6; ++f)
    {
      Real P[3], Q[3], n[3];
      for (int i = 0; i < 3; ++i)
      {
        P[i] = x[hexFaceNode(f, 2)][i] - x[hexFaceNode(f, 0)][i];
        Q[i] = x[hexFaceNode(f, 3)][i] - x[hexFaceNode(f, 1)][i];
      }
      cross3(P, Q, n);
      const Real a2 = 0.25 * (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      amax = a2 > amax ? a2 : amax;
    }
    return measure / kmath::sqrt(amax);
  }
  else
  {
    constexpr int faces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
    Real amax = 0;
    for (int f = 0; f < 4; ++f)
    {
      Real P[3], Q[3], n[3];
      for (int i = 0; i < 3; ++i)
      {
        P[i] = x[faces[f][1]][i] - x[faces[f][0]][i];
        Q[i] = x[faces[f][2]][i] - x[faces[f][0]][i];
      }
      cross3(P, Q, n);
      const Real a2 = 0.25 * (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      amax = a2 > amax ? a2 : amax;
    }
    return 3 * measure / kmath::sqrt(amax);
  }
}

/// \brief Velocity gradient Lh_ij = sum_a v_ai B_aj of an element with N nodes in dimension D
/// (the components past D are 0). R: Real or a lane pack.
template <int N, int D, class R>
KOKKOS_INLINE_FUNCTION void velocityGradient(const R v[][3], const R B[][3], R Lh[3][3])
{
  const R zero = LaneOps<R>::broadcast(0);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      Lh[i][j] = zero;
  for (int a = 0; a < N; ++a)
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j)
        Lh[i][j] += v[a][i] * B[a][j];
}

/// \brief elementGradients() and characteristicLength() together: the hex8 reuses its face
/// normals (same arithmetic, so the same bits as the two calls). Returns the measure.
/// R: Real, or a lane pack for the hex8 (Lanes.hpp).
template <ElementType T, class R>
KOKKOS_INLINE_FUNCTION R elementGradientsAndLength(const R x[][3], R B[][3], R &length)
{
  if constexpr (T == ElementType::Hex8)
  {
    R amax2;
    const R V = hex8Gradients(x, B, amax2);
    length = V / LaneOps<R>::sqrt(amax2);
    return V;
  }
  else
  {
    const Real measure = elementGradients<T>(x, B);
    length = characteristicLength<T>(x, measure);
    return measure;
  }
}

} // namespace scpdyn
