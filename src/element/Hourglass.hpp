#pragma once
/// \file Hourglass.hpp
/// \brief Flanagan-Belytschko hourglass control of the one-point Quad4 and Hex8
/// (Flanagan & Belytschko 1981, IJNME 17:679-706).
///
/// gamma_ka = Gamma_ka - (sum_b Gamma_kb x_bi) B_ai is orthogonal to every linear field, so
/// rigid motion and uniform strain excite no hourglass force. Hourglass rates
/// qdot_ki = sum_a gamma_ka v_ai. Forces f_ai = -sum_k gamma_ka Q_ki with
///  - viscous:   Q_ki = kappa/4 rho c Vs qdot_ki,  Vs = V^(2/3) (3D) or V (2D per metre/radian);
///  - stiffness: Q_ki += kappa M V (B:B) / n_nodes * qdot_ki dt (M = rho c^2), stored per
///    element and rotated with the material (kept in the element's hourglass slots).
#include "core/Types.hpp"
#include "element/ElementKinematics.hpp"

namespace scpdyn
{

enum class HourglassType : int
{
  Viscous = 0,
  Stiffness = 1
};

template <ElementType T>
struct HourglassModes
{
  static constexpr int count = T == ElementType::Hex8 ? 4 : T == ElementType::Quad4 ? 1 : 0;
};

/// \brief Base vector Gamma_k at node a.
template <ElementType T>
KOKKOS_INLINE_FUNCTION Real hourglassBase(int k, int a)
{
  if constexpr (T == ElementType::Quad4)
  {
    (void)k;
    constexpr Real g[4] = {1, -1, 1, -1};
    return g[a];
  }
  else
  {
    constexpr Real g[4][8] = {{1, 1, -1, -1, -1, -1, 1, 1},
                              {1, -1, -1, 1, -1, 1, 1, -1},
                              {1, -1, 1, -1, 1, -1, 1, -1},
                              {-1, 1, -1, 1, 1, -1, 1, -1}};
    return g[k][a];
  }
}

/// \brief Hex8 hourglass forces (hourglassForces() calls it): the arithmetic of the quad's
/// mode loop below, every sum in the same order, with the four modes side by side; the
/// innermost loops run over the modes k, which the compiler turns into vector instructions,
/// and each value is computed once (a mode loop rebuilt the base-vector table on the stack
/// for every lookup: 2.4x the instructions). Q, f and the return value as in hourglassForces().
KOKKOS_INLINE_FUNCTION Real hex8HourglassForces(const Real x[8][3], const Real v[8][3],
                                                const Real B[8][3], Real V, Real rho, Real c,
                                                HourglassType type, Real kappa, Real dt,
                                                Real Q[kHourglassSize], Real f[8][3])
{
  // G[a][k] = Gamma_k at node a (hourglassBase<Hex8>(k, a))
  constexpr Real G[8][4] = {{1, 1, 1, -1}, {1, -1, -1, 1}, {-1, -1, 1, -1}, {-1, 1, -1, 1},
                            {-1, -1, 1, 1},  {-1, 1, -1, -1}, {1, 1, 1, 1},   {1, -1, -1, -1}};
  Real gx[3][4] = {{0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}};
  for (int b = 0; b < 8; ++b)
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 4; ++k)
        gx[i][k] += G[b][k] * x[b][i];
  Real gamma[8][4];
  for (int a = 0; a < 8; ++a)
    for (int k = 0; k < 4; ++k)
      gamma[a][k] = G[a][k] - gx[0][k] * B[a][0] - gx[1][k] * B[a][1] - gx[2][k] * B[a][2];
  Real qdot[3][4] = {{0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}};
  for (int a = 0; a < 8; ++a)
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 4; ++k)
        qdot[i][k] += gamma[a][k] * v[a][i];
  Real Qn[3][4];
  Real power = 0;
  if (type == HourglassType::Viscous)
  {
    const Real visc = 0.25 * kappa * rho * c * kmath::cbrt(V * V);
    for (int k = 0; k < 4; ++k)
      for (int i = 0; i < 3; ++i)
      {
        Qn[i][k] = visc * qdot[i][k];
        power += 0.5 * (Q[3 * k + i] + Qn[i][k]) * qdot[i][k];
        Q[3 * k + i] = Qn[i][k];
      }
  }
  else
  {
    Real BB = 0;
    for (int a = 0; a < 8; ++a)
      for (int i = 0; i < 3; ++i)
        BB += B[a][i] * B[a][i];
    const Real stiff = kappa * rho * c * c * V * BB / 8 * dt;
    for (int k = 0; k < 4; ++k)
      for (int i = 0; i < 3; ++i)
      {
        Qn[i][k] = Q[3 * k + i] + stiff * qdot[i][k];
        power += 0.5 * (Q[3 * k + i] + Qn[i][k]) * qdot[i][k];
        Q[3 * k + i] = Qn[i][k];
      }
  }
  for (int a = 0; a < 8; ++a)
    for (int i = 0; i < 3; ++i)
    {
      Real fa = f[a][i];
      for (int k = 0; k < 4; ++k)
        fa -= gamma[a][k] * Qn[i][k];
      f[a][i] = fa;
    }
  return power;
}

/// \brief Hourglass forces (added to f) for one element. Q holds the resistances of the
/// previous step (count x 3; accumulated in the stiffness form), updated in place. Returns the
/// hourglass power with the step's mean resistance 1/2 (Q_old + Q_new) . qdot [W], as the
/// leapfrog's kinetic energy sees the mean of the forces at n-1/2 and n+1/2.
template <ElementType T>
KOKKOS_INLINE_FUNCTION Real hourglassForces(const Real x[][3], const Real v[][3], const Real B[][3],
                                            Real V, Real rho, Real c, HourglassType type,
                                            Real kappa, Real dt, Real Q[kHourglassSize],
                                            Real f[][3])
{
  constexpr int N = ElementTraits<T>::nodes;
  constexpr int M = HourglassModes<T>::count;
  constexpr int D = ElementTraits<T>::dim;
  if constexpr (T == ElementType::Hex8)
    return hex8HourglassForces(x, v, B, V, rho, c, type, kappa, dt, Q, f);
  Real power = 0;
  if constexpr (M > 0 && T != ElementType::Hex8) // the quad's single mode
  {
    Real BB = 0;
    for (int a = 0; a < N; ++a)
      for (int i = 0; i < D; ++i)
        BB += B[a][i] * B[a][i];
    const Real Vs = D == 3 ? kmath::cbrt(V * V) : V;
    const Real visc = 0.25 * kappa * rho * c * Vs;
    const Real stiff = kappa * rho * c * c * V * BB / N * dt;
    for (int k = 0; k < M; ++k)
    {
      Real gx[D];
      for (int i = 0; i < D; ++i)
      {
        gx[i] = 0;
        for (int b = 0; b < N; ++b)
          gx[i] += hourglassBase<T>(k, b) * x[b][i];
      }
      Real gamma[N];
      for (int a = 0; a < N; ++a)
      {
        gamma[a] = hourglassBase<T>(k, a);
        for (int i = 0; i < D; ++i)
          gamma[a] -= gx[i] * B[a][i];
      }
      for (int i = 0; i < D; ++i)
      {
        Real qdot = 0;
        for (int a = 0; a < N; ++a)
          qdot += gamma[a] * v[a][i];
        const Real Q_old = Q[3 * k + i];
        const Real Qki = type == HourglassType::Viscous ? visc * qdot : Q_old + stiff * qdot;
        Q[3 * k + i] = Qki;
        // trapezoidal work: exact 1/2 k q^2 for the stiffness form; without it the one-sided
        // Q_new qdot books k (dq)^2 extra every step and the hourglass "energy" grows forever
        power += 0.5 * (Q_old + Qki) * qdot;
        for (int a = 0; a < N; ++a)
          f[a][i] -= gamma[a] * Qki;
      }
    }
  }
  return power;
}

} // namespace scpdyn
