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
/// R: Real, or a lane pack of hexes (Lanes.hpp; then the modes are not vectorised, the
/// elements are).
template <class R>
KOKKOS_INLINE_FUNCTION R hex8HourglassForces(const R x[8][3], const R v[8][3], const R B[8][3],
                                             LaneArg<R> V, LaneArg<R> rho, LaneArg<R> c,
                                             HourglassType type, Real kappa, Real dt,
                                             R Q[kHourglassSize], R f[8][3])
{
  // G[a][k] = Gamma_k at node a (hourglassBase<Hex8>(k, a))
  constexpr Real G[8][4] = {{1, 1, 1, -1}, {1, -1, -1, 1}, {-1, -1, 1, -1}, {-1, 1, -1, 1},
                            {-1, -1, 1, 1},  {-1, 1, -1, -1}, {1, 1, 1, 1},   {1, -1, -1, -1}};
  const R zero = LaneOps<R>::broadcast(0);
  R gx[3][4];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 4; ++k)
      gx[i][k] = zero;
  for (int b = 0; b < 8; ++b)
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 4; ++k)
        gx[i][k] += G[b][k] * x[b][i];
  R gamma[8][4];
  for (int a = 0; a < 8; ++a)
    for (int k = 0; k < 4; ++k)
      gamma[a][k] = G[a][k] - gx[0][k] * B[a][0] - gx[1][k] * B[a][1] - gx[2][k] * B[a][2];
  R qdot[3][4];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 4; ++k)
      qdot[i][k] = zero;
  for (int a = 0; a < 8; ++a)
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 4; ++k)
        qdot[i][k] += gamma[a][k] * v[a][i];
  R Qn[3][4];
  R power = zero;
  if (type == HourglassType::Viscous)
  {
    const R visc = 0.25 * kappa * rho * c * LaneOps<R>::cbrt(V * V);
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
    R BB = zero;
    for (int a = 0; a < 8; ++a)
      for (int i = 0; i < 3; ++i)
        BB += B[a][i] * B[a][i];
    const R stiff = kappa * rho * c * c * V * BB / Real(8) * dt;
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
      R fa = f[a][i];
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
/// R: Real, or a lane pack for the hex8 (Lanes.hpp).
template <ElementType T, class R>
KOKKOS_INLINE_FUNCTION R hourglassForces(const R x[][3], const R v[][3], const R B[][3],
                                         LaneArg<R> V, LaneArg<R> rho, LaneArg<R> c,
                                         HourglassType type, Real kappa, Real dt,
                                         R Q[kHourglassSize], R f[][3])
{
  constexpr int N = ElementTraits<T>::nodes;
  constexpr int M = HourglassModes<T>::count;
  constexpr int D = ElementTraits<T>::dim;
  if constexpr (T == ElementType::Hex8)
    return hex8HourglassForces<R>(x, v, B, V, rho, c, type, kappa, dt, Q, f);
  R power = LaneOps<R>::broadcast(0);
  if constexpr (M > 0 && T != ElementType::Hex8) // the quad's single mode
  {
    Real BB = 0;
    for (int a = 0; a < N; ++a)
      for (int i = 0; i < D; ++i)
        BB += B[a][i] * B[a][i];
    const Real Vs = D == 3 ? LaneOps<Real>::cbrt(V * V) : V;
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
