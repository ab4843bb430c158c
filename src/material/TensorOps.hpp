#pragma once
/// \file TensorOps.hpp
/// \brief Small symmetric-tensor helpers on Voigt arrays (xx yy zz xy yz zx, tensor shear
/// components, not engineering strains).
#include "core/Types.hpp"

namespace scpdyn
{

KOKKOS_INLINE_FUNCTION Real trace(const Real a[6]) { return a[0] + a[1] + a[2]; }

/// \brief a : b for symmetric tensors in Voigt storage (off-diagonals count twice).
KOKKOS_INLINE_FUNCTION Real contract(const Real a[6], const Real b[6])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + 2 * (a[3] * b[3] + a[4] * b[4] + a[5] * b[5]);
}

/// \brief Deviatoric part in place; returns the mean (trace/3).
KOKKOS_INLINE_FUNCTION Real makeDeviatoric(Real a[6])
{
  const Real m = trace(a) / 3;
  a[0] -= m;
  a[1] -= m;
  a[2] -= m;
  return m;
}

/// \brief von Mises equivalent of a deviator s: sqrt(3/2 s:s).
KOKKOS_INLINE_FUNCTION Real vonMises(const Real s[6]) { return kmath::sqrt(1.5 * contract(s, s)); }

/// \brief sigma <- R sigma R^T for a rotation R (row-major 3x3).
KOKKOS_INLINE_FUNCTION void rotateSymmetric(const Real R[3][3], Real s[6])
{
  const Real S[3][3] = {{s[0], s[3], s[5]}, {s[3], s[1], s[4]}, {s[5], s[4], s[2]}};
  Real RS[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      RS[i][j] = R[i][0] * S[0][j] + R[i][1] * S[1][j] + R[i][2] * S[2][j];
  Real out[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j)
      out[i][j] = RS[i][0] * R[j][0] + RS[i][1] * R[j][1] + RS[i][2] * R[j][2];
  s[0] = out[0][0];
  s[1] = out[1][1];
  s[2] = out[2][2];
  s[3] = out[0][1];
  s[4] = out[1][2];
  s[5] = out[0][2];
}

/// \brief Hughes-Winget incremental rotation R = (I - W dt/2)^{-1} (I + W dt/2) for a spin
/// W given by its axial components w = (W32, W13, W21). R is exactly orthogonal, so a rigid
/// rotation leaves the stress invariants unchanged (Hughes & Winget 1980, IJNME 15:1862).
KOKKOS_INLINE_FUNCTION void hughesWingetRotation(const Real w[3], Real dt, Real R[3][3])
{
  // Cayley transform of the skew matrix A = W dt/2 with axial vector a:
  // R = I + 2/(1+|a|^2) (A + A^2)
  const Real a0 = 0.5 * dt * w[0], a1 = 0.5 * dt * w[1], a2 = 0.5 * dt * w[2];
  const Real A[3][3] = {{0, -a2, a1}, {a2, 0, -a0}, {-a1, a0, 0}};
  const Real scale = 2 / (1 + a0 * a0 + a1 * a1 + a2 * a2);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
    {
      Real A2 = A[i][0] * A[0][j] + A[i][1] * A[1][j] + A[i][2] * A[2][j];
      R[i][j] = (i == j ? 1 : 0) + scale * (A[i][j] + A2);
    }
}

} // namespace scpdyn
