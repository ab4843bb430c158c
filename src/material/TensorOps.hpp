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

/// \brief sigma <- Q sigma Q^T for a rotation Q (row-major 3x3). R: Real, or any type with
/// + and * (the element lanes' LanePack, element/Lanes.hpp: the same arithmetic per lane).
template <class R>
KOKKOS_INLINE_FUNCTION void rotateSymmetric(const R Q[3][3], R s[6])
{
  const R S[3][3] = {{s[0], s[3], s[5]}, {s[3], s[1], s[4]}, {s[5], s[4], s[2]}};
  R QS[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      QS[i][j] = Q[i][0] * S[0][j] + Q[i][1] * S[1][j] + Q[i][2] * S[2][j];
  R out[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j)
      out[i][j] = QS[i][0] * Q[j][0] + QS[i][1] * Q[j][1] + QS[i][2] * Q[j][2];
  s[0] = out[0][0];
  s[1] = out[1][1];
  s[2] = out[2][2];
  s[3] = out[0][1];
  s[4] = out[1][2];
  s[5] = out[0][2];
}

/// \brief Hughes-Winget incremental rotation Q = (I - W dt/2)^{-1} (I + W dt/2) for a spin
/// W given by its axial components w = (W32, W13, W21). Q is exactly orthogonal, so a rigid
/// rotation leaves the stress invariants unchanged (Hughes & Winget 1980, IJNME 15:1862).
/// R as in rotateSymmetric().
template <class R>
KOKKOS_INLINE_FUNCTION void hughesWingetRotation(const R w[3], Real dt, R Q[3][3])
{
  // Cayley transform of the skew matrix A = W dt/2 with axial vector a:
  // Q = I + 2/(1+|a|^2) (A + A^2), and A^2 = a a^T - |a|^2 I (no products with A's zeros)
  const R a[3] = {0.5 * dt * w[0], 0.5 * dt * w[1], 0.5 * dt * w[2]};
  const R zero = R(); // 0, in every lane
  const R A[3][3] = {{zero, -a[2], a[1]}, {a[2], zero, -a[0]}, {-a[1], a[0], zero}};
  const R aa = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
  const R scale = Real(2) / (Real(1) + aa);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      Q[i][j] = i == j ? Real(1) + scale * (a[i] * a[i] - aa) : scale * (A[i][j] + a[i] * a[j]);
}

} // namespace scpdyn
