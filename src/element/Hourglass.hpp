#pragma once
/// \file Hourglass.hpp
/// \brief Flanagan-Belytschko hourglass control of the one-point Quad4 and Hex8
/// (Flanagan & Belytschko 1981, IJNME 17:679-706).
///
/// gamma_ka = Gamma_ka - (sum_b Gamma_kb x_bi) B_ai is orthogonal to every linear field, so
/// rigid motion and uniform strain excite no hourglass force. Hourglass rates
/// qdot_ki = sum_a gamma_ka v_ai. Forces f_ai = -sum_k gamma_ka Q_ki with
///  - viscous:   Q_ki = kappa/4 rho c Vs qdot_ki,  Vs = V^(2/3) (3D) or V (2D per metre/radian),
///    hourglassAreaScale();
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

/// \brief Vs of the viscous form: V^(2/3) in 3D (the square of the cube root, which the element
/// step has already taken for its viscosity length), V in 2D. R: Real or a lane pack.
template <ElementType T, class R>
KOKKOS_INLINE_FUNCTION R hourglassAreaScale(const R &V)
{
  if constexpr (dimensionOf(T) == 3)
  {
    const R cube_root = LaneOps<R>::cbrt(V);
    return cube_root * cube_root;
  }
  else
    return V;
}

/// \brief The four mode sums m_k = sum_a G_ak y_a of eight nodal values y_a (G as
/// hourglassBase<Hex8>). With the nodes at the natural coordinates (xi, eta, zeta) = (-,-,-),
/// (+,-,-), (+,+,-), (-,+,-), then the same four at zeta = +, the four modes are eta zeta,
/// xi zeta, xi eta and xi eta zeta: a Walsh-Hadamard butterfly forms them from shared pair sums,
/// 18 additions instead of 28. R: Real or a lane pack.
template <class R>
KOKKOS_FORCEINLINE_FUNCTION void hex8ModeSums(const R &y0, const R &y1, const R &y2, const R &y3,
                                              const R &y4, const R &y5, const R &y6, const R &y7,
                                              R m[4])
{
  // pairs along xi (same eta, zeta): differences (xi-odd) and sums (xi-even)
  const R d0 = y1 - y0, d1 = y2 - y3, d2 = y5 - y4, d3 = y6 - y7;
  const R s0 = y0 + y1, s1 = y3 + y2, s2 = y4 + y5, s3 = y7 + y6;
  const R xi_eta_minus = d1 - d0, xi_eta_plus = d3 - d2; // xi eta at zeta = -, +
  m[0] = (s3 - s2) - (s1 - s0);                          // eta zeta
  m[1] = (d2 + d3) - (d0 + d1);                          // xi zeta
  m[2] = xi_eta_minus + xi_eta_plus;                     // xi eta
  m[3] = xi_eta_plus - xi_eta_minus;                     // xi eta zeta
}

/// \brief The inverse direction: y_a = sum_k G_ak m_k for the eight nodes, 12 additions
/// instead of 24 (same coordinates as hex8ModeSums()).
template <class R>
KOKKOS_FORCEINLINE_FUNCTION void hex8ModeSpread(const R m[4], R y[8])
{
  const R p = m[2] + m[3], q = m[2] - m[3]; // xi eta coefficient at zeta = +, -
  const R u = m[0] + m[1], w = m[1] - m[0]; // eta m0 + xi m1 at (xi, eta) = (+,+) and (+,-)
  y[6] = u + p;
  y[4] = p - u;
  y[5] = w - p;
  y[7] = -(w + p);
  y[2] = q - u;
  y[0] = u + q;
  y[1] = -(w + q);
  y[3] = w - q;
}

/// \brief Hex8 hourglass resistances in split form. With gx_jk = sum_b G_bk x_bj and
/// gamma_ak = G_ak - sum_j gx_jk B_aj (the FB vectors, orthogonal to linear fields):
///  - rates:  qdot_ik = sum_a gamma_ak v_ai = sum_a G_ak v_ai - sum_j gx_jk Lh_ij, with
///    Lh_ij = sum_a v_ai B_aj the velocity gradient the element step has already formed;
///  - forces: -sum_k gamma_ak Q_ik = -GQ_ai + sum_j B_aj H_ij, with GQ_ai = sum_k G_ak Q_ik
///    and H_ij = sum_k gx_jk Q_ik, so the B-term joins the stress divergence (elementForces()).
/// gamma is never formed: of its three 8 x 4 x 3 products only 2 x 36 remain.
/// Q (updated), the power returned and the modes as in hourglassForces(); G as
/// hourglassBase<Hex8>. R: Real, or a lane pack of hexes (Lanes.hpp).
template <class R>
KOKKOS_INLINE_FUNCTION R hex8HourglassResistances(const R x[8][3], const R v[8][3], const R B[8][3],
                                                  const R Lh[3][3], LaneArg<R> V, LaneArg<R> Vs,
                                                  LaneArg<R> rho, LaneArg<R> c, HourglassType type,
                                                  Real kappa, Real dt, R Q[kHourglassSize],
                                                  R GQ[8][3], R H[3][3])
{
  const R zero = LaneOps<R>::broadcast(0);
  R gx[3][4], gv[3][4];
  for (int i = 0; i < 3; ++i)
  {
    hex8ModeSums(x[0][i], x[1][i], x[2][i], x[3][i], x[4][i], x[5][i], x[6][i], x[7][i], gx[i]);
    hex8ModeSums(v[0][i], v[1][i], v[2][i], v[3][i], v[4][i], v[5][i], v[6][i], v[7][i], gv[i]);
  }
  R qdot[3][4];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 4; ++k)
      qdot[i][k] = gv[i][k] - (gx[0][k] * Lh[i][0] + gx[1][k] * Lh[i][1] + gx[2][k] * Lh[i][2]);
  R Qn[3][4];
  R power = zero;
  if (type == HourglassType::Viscous)
  {
    const R visc = 0.25 * kappa * rho * c * Vs;
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
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      H[i][j] =
          gx[j][0] * Qn[i][0] + gx[j][1] * Qn[i][1] + gx[j][2] * Qn[i][2] + gx[j][3] * Qn[i][3];
  for (int i = 0; i < 3; ++i)
  {
    R spread[8];
    hex8ModeSpread(Qn[i], spread);
    for (int a = 0; a < 8; ++a)
      GQ[a][i] = spread[a];
  }
  return power;
}

/// \brief Hex8 hourglass forces added to f (hourglassForces() calls it): the split form's
/// resistances, and its two force terms applied here.
template <class R>
KOKKOS_INLINE_FUNCTION R hex8HourglassForces(const R x[8][3], const R v[8][3], const R B[8][3],
                                             LaneArg<R> V, LaneArg<R> Vs, LaneArg<R> rho,
                                             LaneArg<R> c, HourglassType type, Real kappa, Real dt,
                                             R Q[kHourglassSize], R f[8][3])
{
  R Lh[3][3];
  velocityGradient<8, 3>(v, B, Lh);
  R GQ[8][3], H[3][3];
  const R power =
      hex8HourglassResistances<R>(x, v, B, Lh, V, Vs, rho, c, type, kappa, dt, Q, GQ, H);
  for (int a = 0; a < 8; ++a)
    for (int i = 0; i < 3; ++i)
      f[a][i] += (B[a][0] * H[i][0] + B[a][1] * H[i][1] + B[a][2] * H[i][2]) - GQ[a][i];
  return power;
}

/// \brief Hourglass forces (added to f) for one element. Q holds the resistances of the
/// previous step (count x 3; accumulated in the stiffness form), updated in place. Returns the
/// hourglass power with the step's mean resistance 1/2 (Q_old + Q_new) . qdot [W], as the
/// leapfrog's kinetic energy sees the mean of the forces at n-1/2 and n+1/2. Vs: the viscous
/// form's hourglassAreaScale(V). R: Real, or a lane pack for the hex8 (Lanes.hpp).
template <ElementType T, class R>
KOKKOS_INLINE_FUNCTION R hourglassForces(const R x[][3], const R v[][3], const R B[][3],
                                         LaneArg<R> V, LaneArg<R> Vs, LaneArg<R> rho, LaneArg<R> c,
                                         HourglassType type, Real kappa, Real dt,
                                         R Q[kHourglassSize], R f[][3])
{
  constexpr int N = ElementTraits<T>::nodes;
  constexpr int M = HourglassModes<T>::count;
  constexpr int D = ElementTraits<T>::dim;
  if constexpr (T == ElementType::Hex8)
    return hex8HourglassForces<R>(x, v, B, V, Vs, rho, c, type, kappa, dt, Q, f);
  R power = LaneOps<R>::broadcast(0);
  if constexpr (M > 0 && T != ElementType::Hex8) // the quad's single mode
  {
    Real BB = 0;
    for (int a = 0; a < N; ++a)
      for (int i = 0; i < D; ++i)
        BB += B[a][i] * B[a][i];
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
