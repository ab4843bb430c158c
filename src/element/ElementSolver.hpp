#pragma once
/// \file ElementSolver.hpp
/// \brief The physics of one element for one step, as a device function that the kernel and
/// the unit tests call.
#include "element/Hourglass.hpp"
#include "element/InternalForce.hpp"
#include "material/MaterialUpdate.hpp"

namespace scpdyn
{

/// \brief State of one element carried between steps.
struct ElementState
{
  Real stress[6];
  Real energy;
  Real plastic_strain;
  Real volume;
  Real mass;
  Real sound_speed;
  Real q; ///< viscosity pressure of the previous step [Pa]
  Real history[kHistorySize];
  Real hourglass[kHourglassSize];
};

/// \brief What one element step produces besides the new state.
struct ElementResult
{
  Real force[kMaxElementNodes][3]; ///< nodal forces [N]
  Real q;                          ///< viscosity pressure [Pa]
  Real hourglass_power;            ///< [W]
  Real stable_dt;                  ///< h / c; <= 0 if inverted
};

/// \brief Velocity gradient on the midpoint configuration x^n from the one on x^{n+1/2}.
///
/// Between the half steps x^{n-1/2} and x^{n+1/2} the nodes move by dt v^n (constant dt), and
/// their midpoint configuration is x^n to O(dt^2): the strain increment dt v^n belongs to x^n
/// (Hughes-Winget midpoint rule). With
/// x^{n+1/2} = (I + dt/2 L) x^n locally, L = Lh (I - dt/2 Lh)^{-1}: exact for rigid rotation
/// (D = 0, so no spurious stress) and for every linear velocity field.
template <int D>
KOKKOS_INLINE_FUNCTION void midpointVelocityGradient(const Real Lh[3][3], Real half_dt, Real L[3][3])
{
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      L[i][j] = 0;
  if constexpr (D == 1)
    L[0][0] = Lh[0][0] / (1 - half_dt * Lh[0][0]);
  else
  {
    Real M[3][3], Mi[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        M[i][j] = (i == j ? 1 : 0) - (i < D && j < D ? half_dt * Lh[i][j] : 0);
    const Real det = M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) -
                     M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
                     M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]);
    const Real id = 1 / det;
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

/// \brief One element step. x: half-step positions x^{n+1/2}; v: velocities v^n.
/// The strain increment dt D(v^n) at x^{n+1/2} takes the element from n-1/2 to n+1/2.
template <ElementType T, bool Axi>
KOKKOS_INLINE_FUNCTION void elementStep(const Real x[][3], const Real v[][3],
                                        const MaterialParams &mat, const ElementControls &ctl,
                                        ElementState &s, ElementResult &r)
{
  constexpr int N = ElementTraits<T>::nodes;
  constexpr int D = ElementTraits<T>::dim;
  Real B[N][3];
  Real length;
  const Real measure = elementGradientsAndLength<T>(x, B, length);
  Real V = measure;
  if constexpr (Axi)
    V = quad4RadialVolume(x);
  if (!(V > 0) || !(measure > 0))
  {
    r.stable_dt = -1;
    return;
  }

  Real Lh[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  for (int a = 0; a < N; ++a)
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j)
        Lh[i][j] += v[a][i] * B[a][j];
  Real L[3][3];
  midpointVelocityGradient<D>(Lh, 0.5 * ctl.dt, L);
  MaterialStep st;
  st.D[0] = L[0][0];
  st.D[1] = L[1][1];
  st.D[2] = L[2][2];
  st.D[3] = 0.5 * (L[0][1] + L[1][0]);
  st.D[4] = 0.5 * (L[1][2] + L[2][1]);
  st.D[5] = 0.5 * (L[0][2] + L[2][0]);
  if constexpr (Axi)
  {
    // hoop rate v_r / r with r = V / A the area-centroid radius (work-conjugate to the
    // hoop force sigma_tt A / 4 below)
    Real vr = 0;
    for (int a = 0; a < N; ++a)
      vr += v[a][0];
    st.D[2] = vr / N * measure / V;
  }
  st.dt = ctl.dt;
  st.rho_old = s.mass / s.volume;
  st.rho_new = s.mass / V;
  st.time = ctl.half_time;
  st.length = length;

  const Real trD = st.D[0] + st.D[1] + st.D[2];
  Real q_new = 0;
  if (trD < 0) // the viscosity length (a cbrt call in 3D) is needed in compression only
  {
    const Real lq = D == 1 ? measure : D == 2 ? kmath::sqrt(measure) : kmath::cbrt(measure);
    const Real c_old = s.sound_speed;
    q_new = st.rho_new * lq * (ctl.q_quadratic * lq * trD * trD - ctl.q_linear * c_old * trD);
  }
  // the viscous heating is booked with the step's mean q, as the kinetic energy sees the mean
  // of the forces at n-1/2 and n+1/2 (leapfrog energy balance, see NodeUpdate.cpp)
  st.q = 0.5 * (s.q + q_new);

  if constexpr (D > 1)
  {
    const Real w[3] = {0.5 * (L[2][1] - L[1][2]), 0.5 * (L[0][2] - L[2][0]),
                       0.5 * (L[1][0] - L[0][1])};
    Real R[3][3];
    hughesWingetRotation(w, ctl.dt, R);
    rotateSymmetric(R, s.stress);
    if (ctl.hourglass == HourglassType::Stiffness)
      for (int k = 0; k < HourglassModes<T>::count; ++k)
      {
        Real q3[3] = {s.hourglass[3 * k], s.hourglass[3 * k + 1], s.hourglass[3 * k + 2]};
        for (int i = 0; i < 3; ++i)
          s.hourglass[3 * k + i] = R[i][0] * q3[0] + R[i][1] * q3[1] + R[i][2] * q3[2];
      }
  }

  const Real c = updateMaterial(mat, st, s.stress, s.energy, s.plastic_strain, s.history);
  s.sound_speed = c;
  s.volume = V;

  const Real sig[3][3] = {{s.stress[0] - q_new, s.stress[3], s.stress[5]},
                          {s.stress[3], s.stress[1] - q_new, s.stress[4]},
                          {s.stress[5], s.stress[4], s.stress[2] - q_new}};
  for (int a = 0; a < N; ++a)
  {
    for (int i = 0; i < 3; ++i)
    {
      Real fi = 0;
      for (int j = 0; j < D; ++j)
        fi -= sig[i][j] * B[a][j];
      r.force[a][i] = i < D ? V * fi : 0;
    }
    if constexpr (Axi)
      r.force[a][0] -= sig[2][2] * measure / N;
  }
  r.hourglass_power = hourglassForces<T>(x, v, B, V, st.rho_new, c, ctl.hourglass,
                                         ctl.hourglass_coefficient, ctl.dt, s.hourglass, r.force);
  r.q = q_new;
  s.q = q_new;
  // dt = h / c. The viscosity term of h / (Q + sqrt(Q^2 + c^2)) is left out on purpose: it
  // switches on and off as elements load and unload, and a dt that jumps by several percent
  // every few cycles breaks the leapfrog's energy conservation (measured: 0.7 % drift on a
  // vibrating bar with the default linear q). S <= 0.9 leaves the margin the damping needs.
  r.stable_dt = st.length / c;
}

} // namespace scpdyn
