#pragma once
/// \file ElementSolver.hpp
/// \brief The physics of one element for one step, as a device function that the kernel and
/// the unit tests call.
#include "element/Hourglass.hpp"
#include "element/ElementForces.hpp"
#include "material/MaterialUpdate.hpp"

namespace scpdyn
{

/// \brief State of one element carried between steps (R = Real; a lane pack: W elements).
template <class R>
struct ElementStateOf
{
  R stress[6];
  R energy;
  R plastic_strain;
  R volume;
  R mass;
  R sound_speed;
  R q; ///< viscosity pressure of the previous step [Pa]
  R history[kHistorySize];
  R hourglass[kHourglassSize];
};
using ElementState = ElementStateOf<Real>;

/// \brief What one element step produces besides the new state.
template <class R>
struct ElementResultOf
{
  R force[kMaxElementNodes][3]; ///< nodal forces [N]
  R q;                          ///< viscosity pressure [Pa]
  R hourglass_power;            ///< [W]
  R stable_dt;                  ///< h / c; <= 0 if inverted
};
using ElementResult = ElementResultOf<Real>;

/// \brief What the element step carries from its kinematics to the material update and the
/// forces (elementStep() is these three phases; the hex8 lanes call them on packs).
template <ElementType T, class R>
struct ElementKinematicsOf
{
  R B[ElementTraits<T>::nodes][3];
  R measure, V, length;
  R cube_root_V; ///< hex8: V^(1/3), the viscosity length and (squared) the hourglass scale
  R Lh[3][3];    ///< velocity gradient on x^{n+1/2}, sum_a v_a B_a [1/s]
  R D[6];        ///< rate of deformation on the midpoint configuration [1/s]
  R rho_old, rho_new;
  R q_new;  ///< this step's viscosity pressure [Pa]
  R q_mean; ///< 1/2 (q^{n-1/2} + q^{n+1/2}), for the material's heating [Pa]
};

/// \brief Velocity gradient on the midpoint configuration x^n from the one on x^{n+1/2}.
///
/// Between the half steps x^{n-1/2} and x^{n+1/2} the nodes move by dt v^n (constant dt), and
/// their midpoint configuration is x^n to O(dt^2): the strain increment dt v^n belongs to x^n
/// (Hughes-Winget midpoint rule). With
/// x^{n+1/2} = (I + dt/2 L) x^n locally, L = Lh (I - dt/2 Lh)^{-1}: exact for rigid rotation
/// (D = 0, so no spurious stress) and for every linear velocity field.
template <int D, class R>
KOKKOS_INLINE_FUNCTION void midpointVelocityGradient(const R Lh[3][3], Real half_dt, R L[3][3])
{
  const R zero = LaneOps<R>::broadcast(0);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      L[i][j] = zero;
  if constexpr (D == 1)
    L[0][0] = Lh[0][0] / (Real(1) - half_dt * Lh[0][0]);
  else
  {
    R M[3][3], Mi[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
      {
        const Real id = i == j ? 1 : 0;
        M[i][j] = i < D && j < D ? id - half_dt * Lh[i][j] : LaneOps<R>::broadcast(id - 0.0);
      }
    const R det = M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) -
                  M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
                  M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]);
    const R id = Real(1) / det;
    Mi[0][0] = (M[1][1] * M[2][2] - M[1][2] * M[2][1]) * id;
    Mi[0][1] = (M[0][2] * M[2][1] - M[0][1] * M[2][2]) * id;
    Mi[0][2] = (M[0][1] * M[1][2] - M[0][2] * M[1][1]) * id;
    Mi[1][0] = (M[1][2] * M[2][0] - M[1][0] * M[2][2]) * id;
    Mi[1][1] = (M[0][0] * M[2][2] - M[0][2] * M[2][0]) * id;
    Mi[1][2] = (M[0][2] * M[1][0] - M[0][0] * M[1][2]) * id;
    Mi[2][0] = (M[1][0] * M[2][1] - M[1][1] * M[2][0]) * id;
    Mi[2][1] = (M[0][1] * M[2][0] - M[0][0] * M[2][1]) * id;
    Mi[2][2] = (M[0][0] * M[1][1] - M[0][1] * M[1][0]) * id;
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j)
        for (int k = 0; k < D; ++k)
          L[i][j] += Lh[i][k] * Mi[k][j];
  }
}

/// \brief Rotates the stress by the spin w over dt (hughesWingetRotation(), rotateSymmetric()),
/// and the stiffness hourglass resistances with it if `hourglass`.
template <int modes, class R>
KOKKOS_INLINE_FUNCTION void rotateElementState(const R w[3], Real dt, bool hourglass, R stress[6],
                                               R Q[kHourglassSize])
{
  R R_[3][3];
  hughesWingetRotation(w, dt, R_);
  rotateSymmetric(R_, stress);
  if (hourglass)
    for (int k = 0; k < modes; ++k)
    {
      const R q3[3] = {Q[3 * k], Q[3 * k + 1], Q[3 * k + 2]};
      for (int i = 0; i < 3; ++i)
        Q[3 * k + i] = R_[i][0] * q3[0] + R_[i][1] * q3[1] + R_[i][2] * q3[2];
    }
}

/// \brief Phase 1a of elementStep(): gradients, measure, volume and length. The step goes on
/// only if k.V > 0 and k.measure > 0 (an inverted element stops the run).
template <ElementType T, bool Axi, class R>
KOKKOS_INLINE_FUNCTION void elementGeometry(const R x[][3], ElementKinematicsOf<T, R> &k)
{
  k.measure = elementGradientsAndLength<T>(x, k.B, k.length);
  k.V = k.measure;
  if constexpr (Axi)
    k.V = quad4RadialVolume(x);
  if constexpr (T == ElementType::Hex8) // one cube root for q and the hourglass
    k.cube_root_V = LaneOps<R>::cbrt(k.V);
}

/// \brief Phase 1b: velocity gradient on the midpoint configuration, rate of deformation,
/// densities, viscosity pressure, and the rotation of the stress (and stiffness hourglass
/// resistances) by the step's spin.
template <ElementType T, bool Axi, class R>
KOKKOS_INLINE_FUNCTION void elementRates(const R v[][3], const ElementControls &ctl,
                                         ElementStateOf<R> &s, ElementKinematicsOf<T, R> &k)
{
  constexpr int N = ElementTraits<T>::nodes;
  constexpr int D = ElementTraits<T>::dim;
  using Ops = LaneOps<R>;
  const R zero = Ops::broadcast(0);
  velocityGradient<N, D>(v, k.B, k.Lh);
  R L[3][3];
  midpointVelocityGradient<D>(k.Lh, 0.5 * ctl.dt, L);
  k.D[0] = L[0][0];
  k.D[1] = L[1][1];
  k.D[2] = L[2][2];
  k.D[3] = 0.5 * (L[0][1] + L[1][0]);
  k.D[4] = 0.5 * (L[1][2] + L[2][1]);
  k.D[5] = 0.5 * (L[0][2] + L[2][0]);
  if constexpr (Axi)
  {
    // hoop rate v_r / r with r = V / A the area-centroid radius (work-conjugate to the
    // hoop force sigma_tt A / 4 below)
    Real vr = 0;
    for (int a = 0; a < N; ++a)
      vr += v[a][0];
    k.D[2] = vr / N * k.measure / k.V;
  }
  k.rho_old = s.mass / s.volume;
  k.rho_new = s.mass / k.V;

  const R trD = k.D[0] + k.D[1] + k.D[2];
  // the viscosity length (a cube root in 3D) is needed in compression only
  if constexpr (Ops::width == 1)
  {
    k.q_new = zero;
    if (trD < 0)
    {
      R lq;
      if constexpr (T == ElementType::Hex8)
        lq = k.cube_root_V;
      else
        lq = D == 1 ? k.measure : D == 2 ? Ops::sqrt(k.measure) : Ops::cbrt(k.measure);
      k.q_new =
          k.rho_new * lq * (ctl.q_quadratic * lq * trD * trD - ctl.q_linear * s.sound_speed * trD);
    }
  }
  else // lanes (hex8): the same expression in every lane, kept where compressed, 0 elsewhere
  {
    static_assert(T == ElementType::Hex8, "lane packs are hex8");
    const R lq = k.cube_root_V;
    const R q =
        k.rho_new * lq * (ctl.q_quadratic * lq * trD * trD - ctl.q_linear * s.sound_speed * trD);
    k.q_new = trD < 0 ? q : zero;
  }
  // the viscous heating is booked with the step's mean q, as the kinetic energy sees the mean
  // of the forces at n-1/2 and n+1/2 (leapfrog energy balance, see NodeUpdate.cpp)
  k.q_mean = 0.5 * (s.q + k.q_new);

  if constexpr (D > 1)
  {
    const R w[3] = {0.5 * (L[2][1] - L[1][2]), 0.5 * (L[0][2] - L[2][0]),
                    0.5 * (L[1][0] - L[0][1])};
    rotateElementState<HourglassModes<T>::count>(
        w, ctl.dt, ctl.hourglass == HourglassType::Stiffness, s.stress, s.hourglass);
  }
}

/// \brief The material's MaterialStep from phase 1: of the element (R = Real), or of lane
/// `lane` of a pack.
template <ElementType T, class R>
KOKKOS_INLINE_FUNCTION MaterialStep materialStep(const ElementKinematicsOf<T, R> &k,
                                                 const ElementControls &ctl, int lane = 0)
{
  MaterialStep st;
  for (int i = 0; i < 6; ++i)
    st.D[i] = laneValue(k.D[i], lane);
  st.dt = ctl.dt;
  st.rho_old = laneValue(k.rho_old, lane);
  st.rho_new = laneValue(k.rho_new, lane);
  st.q = laneValue(k.q_mean, lane);
  st.time = ctl.half_time;
  st.length = laneValue(k.length, lane);
  return st;
}

/// \brief Phase 3, after the material update gave the sound speed c: stress-divergence and
/// hourglass forces, the new state's volume, q and c, and the stable time step.
template <ElementType T, bool Axi, class R>
KOKKOS_INLINE_FUNCTION void elementForces(const R x[][3], const R v[][3],
                                          const ElementControls &ctl,
                                          const ElementKinematicsOf<T, R> &k, const R &c,
                                          ElementStateOf<R> &s, ElementResultOf<R> &r)
{
  constexpr int N = ElementTraits<T>::nodes;
  constexpr int D = ElementTraits<T>::dim;
  s.sound_speed = c;
  s.volume = k.V;
  const R q_new = k.q_new;
  const R sig[3][3] = {{s.stress[0] - q_new, s.stress[3], s.stress[5]},
                       {s.stress[3], s.stress[1] - q_new, s.stress[4]},
                       {s.stress[5], s.stress[4], s.stress[2] - q_new}};
  if constexpr (T == ElementType::Hex8)
  {
    // the hourglass force's B-term joins the stress divergence: f_a = -(V sig - H) B_a - GQ_a
    const R Vs = k.cube_root_V * k.cube_root_V; // hourglassAreaScale(), one cube root a step
    R GQ[8][3], H[3][3];
    r.hourglass_power =
        hex8HourglassResistances<R>(x, v, k.B, k.Lh, k.V, Vs, k.rho_new, c, ctl.hourglass,
                                    ctl.hourglass_coefficient, ctl.dt, s.hourglass, GQ, H);
    R P[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        P[i][j] = k.V * sig[i][j] - H[i][j];
    for (int a = 0; a < 8; ++a)
      for (int i = 0; i < 3; ++i)
        r.force[a][i] =
            -(P[i][0] * k.B[a][0] + P[i][1] * k.B[a][1] + P[i][2] * k.B[a][2]) - GQ[a][i];
  }
  else
  {
    const R zero = LaneOps<R>::broadcast(0);
    for (int a = 0; a < N; ++a)
    {
      for (int i = 0; i < 3; ++i)
      {
        R fi = zero;
        for (int j = 0; j < D; ++j)
          fi -= sig[i][j] * k.B[a][j];
        r.force[a][i] = i < D ? k.V * fi : zero;
      }
      if constexpr (Axi)
        r.force[a][0] -= sig[2][2] * k.measure / N;
    }
    // Vs = V: the quad's hourglassAreaScale() in 2D; tets and lines have no hourglass modes
    r.hourglass_power =
        hourglassForces<T, R>(x, v, k.B, k.V, k.V, k.rho_new, c, ctl.hourglass,
                              ctl.hourglass_coefficient, ctl.dt, s.hourglass, r.force);
  }
  r.q = q_new;
  s.q = q_new;
  // dt = h / c. The viscosity term of h / (Q + sqrt(Q^2 + c^2)) is left out on purpose: it
  // switches on and off as elements load and unload, and a dt that jumps by several percent
  // every few cycles breaks the leapfrog's energy conservation (measured: 0.7 % drift on a
  // vibrating bar with the default linear q). S <= 0.9 leaves the margin the damping needs.
  r.stable_dt = k.length / c;
}

/// \brief One element step. x: half-step positions x^{n+1/2}; v: velocities v^n.
/// The strain increment dt D(v^n) at x^{n+1/2} takes the element from n-1/2 to n+1/2.
template <ElementType T, bool Axi>
KOKKOS_INLINE_FUNCTION void elementStep(const Real x[][3], const Real v[][3],
                                        const MaterialParams &mat, const ElementControls &ctl,
                                        ElementState &s, ElementResult &r)
{
  ElementKinematicsOf<T, Real> k;
  elementGeometry<T, Axi>(x, k);
  if (!(k.V > 0) || !(k.measure > 0))
  {
    r.stable_dt = -1;
    return;
  }
  elementRates<T, Axi>(v, ctl, s, k);
  const MaterialStep st = materialStep<T>(k, ctl);
  const Real c = updateMaterial(mat, st, s.stress, s.energy, s.plastic_strain, s.history);
  elementForces<T, Axi>(x, v, ctl, k, c, s, r);
}

} // namespace scpdyn
