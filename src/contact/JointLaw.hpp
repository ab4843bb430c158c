#pragma once
/// \file JointLaw.hpp
/// \brief Per-CP force update of the Simple Common Plane contact (docs/theory.md sections 5-12):
/// hyperbolic normal law with max-closure memory (6.1, 6.2), Coulomb shear with softening and
/// dilation (6.3, 6.4), tension cut-off and re-closing (6.5), traction history (6.6), energy
/// increments (6.7), the explicit update (7) and its time step (19), the quasi-implicit update
/// (10) and the shear rotation (13). Slide line, sticky and sleepy (10.5, 10.8, 11) are in
/// JointConstraints.hpp; the nodal weights of section 8 are geometry and live in
/// CommonPlaneGeometry.hpp. All device-callable free functions on POD data.
///
/// Sign conventions (section 1): n points from face 1 to face 2; Vn = (V1 - V2).n > 0 closing;
/// Vs = tangential part of V1 - V2; the force on face 2 is F = Fn*n + Fs, face 1 gets -F.
#include "contact/CommonPlaneGeometry.hpp"
#include "contact/CommonPlaneState.hpp"

namespace scpdyn
{

/// \brief Kinematics of one active CP for one step (sections 5, 10.2, 10.3).
struct CpKinematics
{
  Real n[3];      ///< current CP normal (D1)
  Real Vn;        ///< relative normal velocity (10), closing > 0 [m/s]
  Real Vs[3];     ///< relative tangential velocity (12) [m/s]; its normal part is ignored
  Real Ac;        ///< contact area [m^2]
  Real dt;        ///< time step [s]
  Real mstar;     ///< reduced mass m* (10.1) [kg]; only options using m* read it
  Real Fint_n;    ///< (21) normal internal-force term [N]; 0 with corrected velocities (10.6)
  Real Fint_s[3]; ///< (21) tangential internal-force term [N]
};

/// \brief Forces and energy increments of one CP update (6.7). Energies in J (per metre or per
/// radian in 2D). dW = dPsi + dD by construction.
struct CpStepResult
{
  Real Fn;      ///< normal force at the end of the step (after dilation) [N]
  Real Fs[3];   ///< shear force on face 2 [N]
  Real dW;      ///< work done on the joint by the faces [J]
  Real dPsi;    ///< change of stored elastic energy [J]
  Real dD;      ///< dissipated energy [J]
  Real dW_area; ///< stored energy booked by the traction rescale of 6.6 (not in dW) [J]
  Real dusp;    ///< plastic slip increment / a [-]
  int slipped;  ///< 1 if the shear force was capped (14)
  int opened;   ///< 1 if the joint opened in this step (D10)
};

// ----------------------------------------------------------------------------------- law ----

/// \brief u_cap = a(1 - sqrt(E0/Emax)), the closure where E reaches Emax (D8) [m].
KOKKOS_INLINE_FUNCTION Real jointCapClosure(const JointParams &p)
{
  return p.a * (1.0 - kmath::sqrt(p.E0 / p.Emax));
}

/// \brief Normal modulus (1) with the cut-off (D8): E0/(1 - max(u,umax)/a)^2, Emax beyond u_cap
/// [Pa].
KOKKOS_INLINE_FUNCTION Real jointModulus(const JointParams &p, Real u, Real umax)
{
  const Real um = contact_math::max(u, umax);
  if (um >= jointCapClosure(p))
    return p.Emax;
  const Real q = 1.0 - um / p.a;
  return p.E0 / (q * q);
}

/// \brief Virgin loading curve (2), sigma = E0 u/(a - u), continued linearly with slope Emax/a
/// beyond u_cap (D8) [Pa].
KOKKOS_INLINE_FUNCTION Real jointLoadingStress(const JointParams &p, Real u)
{
  const Real uc = jointCapClosure(p);
  if (u <= uc)
    return p.E0 * u / (p.a - u);
  return p.E0 * uc / (p.a - uc) + p.Emax * (u - uc) / p.a;
}

/// \brief Friction angle (5): phi1 + (phi0 - phi1)/(1 + usp/usp0) [rad].
KOKKOS_INLINE_FUNCTION Real frictionAngle(const JointParams &p, Real usp)
{
  if (p.usp0 <= 0) // instant softening
    return usp > 0 ? p.phi1 : p.phi0;
  return p.phi1 + (p.phi0 - p.phi1) / (1.0 + usp / p.usp0);
}

/// \brief Dilation tangent of (6): tan(psi0)*max(0, 1 - max(Fn,0)/(sigma_cr Ac)), capped at
/// tan(phi) so that dilation never creates energy (6.7).
KOKKOS_INLINE_FUNCTION Real dilationTangent(const JointParams &p, Real Fn, Real Ac, Real tan_phi)
{
  using namespace contact_math;
  if (p.sigma_cr <= 0)
    return 0;
  const Real decay = max(0.0, 1.0 - max(Fn, 0.0) / (p.sigma_cr * Ac));
  return min(kmath::tan(p.psi0) * decay, max(tan_phi, 0.0));
}

/// \brief Line (unloading/reloading) stiffness E_law(umax)*Ac/a [N/m].
KOKKOS_INLINE_FUNCTION Real lineStiffness(const JointParams &p, Real umax, Real Ac)
{
  return jointModulus(p, umax, umax) * Ac / p.a;
}

/// \brief Stored elastic energy Psi = Fn^2/(2 K_line) + |Fs|^2/(2 K_s) (6.7) [J].
KOKKOS_INLINE_FUNCTION Real storedEnergy(const JointParams &p, Real Fn, const Real Fs[3], Real umax,
                                         Real Ac)
{
  if (Ac <= 0)
    return 0;
  const Real Ks = p.G * Ac / p.a;
  const Real s2 = contact_math::dot(Fs, Fs);
  return 0.5 * Fn * Fn / lineStiffness(p, umax, Ac) + (s2 > 0 ? 0.5 * s2 / Ks : 0.0);
}

/// \brief (13): rotate a vector tangent to n_old into the plane of n by the rotation taking n_old
/// to n (Rodrigues). Below |n_old x n| = 1e-12 only the normal component is removed.
KOKKOS_INLINE_FUNCTION void rotateWithNormal(const Real n_old[3], const Real n[3], Real v[3])
{
  using namespace contact_math;
  Real k[3];
  cross(n_old, n, k);
  const Real s = norm(k), c = dot(n_old, n);
  if (s >= 1e-12)
  {
    for (int d = 0; d < 3; ++d)
      k[d] /= s;
    Real kv[3];
    cross(k, v, kv);
    const Real kd = dot(k, v);
    for (int d = 0; d < 3; ++d)
      v[d] = c * v[d] + s * kv[d] + (1.0 - c) * kd * k[d];
  }
  const Real vn = dot(v, n); // round-off (or a v not tangent to n_old)
  for (int d = 0; d < 3; ++d)
    v[d] -= vn * n[d];
}

/// \brief Reduced mass m* = m1 m2/(m1 + m2) with m_i = f_i M_i (10.1); a rigid face has 1/m = 0.
KOKKOS_INLINE_FUNCTION Real reducedMass(Real f1, Real M1, bool rigid1, Real f2, Real M2,
                                        bool rigid2)
{
  const Real i1 = rigid1 ? 0.0 : 1.0 / (f1 * M1), i2 = rigid2 ? 0.0 : 1.0 / (f2 * M2);
  return i1 + i2 > 0 ? 1.0 / (i1 + i2) : 1e300;
}

/// \brief Areal reduced mass mu* = mu1 mu2/(mu1 + mu2), mu_i = M_i/A_i, of (19) [kg/m^2].
KOKKOS_INLINE_FUNCTION Real arealReducedMass(Real M1, Real A1, bool rigid1, Real M2, Real A2,
                                             bool rigid2)
{
  return reducedMass(1.0, M1 / A1, rigid1, 1.0, M2 / A2, rigid2);
}

/// \brief (21): Fint = m*(abar1 - abar2) from the face-average internal accelerations, split
/// into its normal and tangential parts [N].
KOKKOS_INLINE_FUNCTION void internalForceTerm(const Real abar1[3], const Real abar2[3], Real mstar,
                                              const Real n[3], Real &Fint_n, Real Fint_s[3])
{
  Real f[3];
  for (int d = 0; d < 3; ++d)
    f[d] = mstar * (abar1[d] - abar2[d]);
  Fint_n = contact_math::dot(f, n);
  for (int d = 0; d < 3; ++d)
    Fint_s[d] = f[d] - Fint_n * n[d];
}

/// \brief Explicit contact time-step limit (19), section 9, for the next cycle, from the stored
/// u, umax and the end-of-step Vn; E at the predicted closure u + max(Vn,0)*dt_el. `mu_star`:
/// arealReducedMass() [kg/m^2] (MassSpring form); `rho_bar`: mean density (Paper form).
/// C_safe > 1e30 disables the limit (returns 1e300) [s].
KOKKOS_INLINE_FUNCTION Real contactTimeStep(const JointParams &p, const CpState &s, Real Vn,
                                            Real dt_el, Real mu_star, Real rho_bar)
{
  using namespace contact_math;
  if (p.C_safe > 1e30)
    return 1e300;
  const Real E_pred = jointModulus(p, s.u + max(Vn, 0.0) * dt_el, s.umax);
  if (p.dt_form == DtContactForm::Paper)
    return p.C_safe * p.a * kmath::sqrt(rho_bar / E_pred);
  return 2.0 * p.C_safe * kmath::sqrt(p.a * mu_star / max(E_pred, p.G));
}

// ------------------------------------------------------------------------- update pieces ----

namespace joint_impl
{
using namespace contact_math;

KOKKOS_INLINE_FUNCTION Real tensileLimit(const JointParams &p, const CpState &s, Real Ac)
{
  return p.sigma_t * s.sigma_t_scale * Ac;
}

/// \brief Mark the joint open with zero-force closure u_z (D10); brittle option drops sigma_t.
KOKKOS_INLINE_FUNCTION void openJoint(const JointParams &p, CpState &s, Real u_z)
{
  s.open = 1;
  s.u_z = u_z;
  if (p.brittle_tension)
    s.sigma_t_scale = 0;
}

/// \brief Work along the line of stiffness K from force F to the tensile limit -T, where the
/// joint breaks (D10): (T^2 - F^2)/(2K). The drop to zero then dissipates T^2/(2K).
KOKKOS_INLINE_FUNCTION Real workToBreak(Real F, Real T, Real K)
{
  return 0.5 * (T * T - F * F) / K;
}

/// \brief Explicit normal step, section 7 E3. Returns Fn' (before dilation) and the work done
/// along the law's force path (trapezoid per linear piece; on opening/re-closing steps only the
/// loaded part of the path does work, see docs/theory.md).
KOKKOS_INLINE_FUNCTION Real normalExplicit(const JointParams &p, CpState &s, Real Ac, Real du,
                                           Real &dW, int &opened)
{
  const Real u1 = s.u + du;                             // (7)
  const Real umax1 = max(s.umax, u1);                   // (8)
  const Real K = jointModulus(p, u1, umax1) * Ac / p.a; // (1)+(D8) at the END of the step [P]
  Real F;
  opened = 0;
  if (s.open)
  { // (D11): no force until u' passes u_z, then from zero along the line
    F = K * max(0.0, u1 - s.u_z);
    dW = 0.5 * F * max(0.0, u1 - s.u_z);
    s.open = F > 0 ? 0 : 1;
  }
  else
  {
    F = s.Fn + K * du; // (9)
    dW = 0.5 * (s.Fn + F) * du;
    const Real T = tensileLimit(p, s, Ac);
    if (F < -T)
    { // (D10): u_z = zero-force point of the line through (u, Fn)
      dW = workToBreak(s.Fn, T, K);
      openJoint(p, s, s.u - s.Fn / K);
      F = 0;
      opened = 1;
    }
  }
  s.u = u1;
  s.umax = umax1;
  return F;
}

/// \brief Smaller root of z^2 - S z + P = 0 without cancellation (10.4).
KOKKOS_INLINE_FUNCTION Real smallerRoot(Real S, Real P)
{
  const Real r = kmath::sqrt(max(S * S - 4.0 * P, 0.0));
  return S > 0 ? 2.0 * P / (S + r) : 0.5 * (S - r);
}

/// \brief Quasi-implicit normal step (10.4): closure change B - c*Fn' with the law integrated
/// exactly along its branches (line, hyperbola (22)-(23), capped line). B: free closure change
/// [m]; c = dt^2/m* [m/N] (0 reproduces the law). Returns Fn' before dilation; sets du and the
/// work along the path.
KOKKOS_INLINE_FUNCTION Real normalImplicit(const JointParams &p, CpState &s, Real Ac, Real B,
                                           Real c, Real &du, Real &dW, int &opened)
{
  opened = 0;
  const Real u0 = s.u;
  Real us, Fs, Bs;
  if (s.open)
  {
    if (u0 + B <= s.u_z)
    { // stays open: free motion
      s.u = u0 + B;
      du = B, dW = 0;
      return 0;
    }
    us = s.u_z, Fs = 0, Bs = B - (s.u_z - u0);
  }
  else
    us = u0, Fs = s.Fn, Bs = B;
  // an open joint re-closing beyond the old umax has passed that closure at zero force
  const Real umax = max(s.umax, us);
  const Real ucap = jointCapClosure(p);
  const Real Kl = lineStiffness(p, umax, Ac);
  Real F, x;
  const Real y = (Bs - c * Fs) / (1.0 + c * Kl); // (i) unload/reload line
  if (us + y <= umax || umax >= ucap)
  {
    F = Fs + Kl * y, x = y;
    dW = 0.5 * (Fs + F) * y;
  }
  else
  { // (ii) loading beyond umax on the hyperbola, (22)-(23)
    const Real y1 = umax - us, F1 = Fs + Kl * y1, B2 = Bs - y1;
    const Real D = p.a - umax, Kq = c * Ac * p.E0 * p.a / D, Bp = B2 - c * F1;
    Real z = smallerRoot(D + Bp + Kq, D * Bp);
    if (umax + z > ucap)
    { // redo the part beyond u_cap with the linear modulus Emax (D8)
      const Real z1 = ucap - umax;
      const Real F2 = F1 + Ac * p.E0 * p.a * z1 / (D * (D - z1));
      const Real K3 = p.Emax * Ac / p.a;
      const Real z2 = (B2 - z1 - c * F2) / (1.0 + c * K3);
      z = z1 + z2, F = F2 + K3 * z2;
      dW = 0.5 * (Fs + F1) * y1 + 0.5 * (F1 + F2) * z1 + 0.5 * (F2 + F) * z2;
    }
    else
    {
      F = F1 + Ac * p.E0 * p.a * z / (D * (D - z));
      dW = 0.5 * (Fs + F1) * y1 + 0.5 * (F1 + F) * z;
    }
    x = y1 + z;
  }
  const Real T = tensileLimit(p, s, Ac);
  if (F < -T)
  { // (iv) opens (D10): free motion for the whole step
    dW = s.open ? 0 : workToBreak(Fs, T, Kl);
    if (!s.open)
      openJoint(p, s, us - Fs / Kl);
    opened = 1;
    F = 0;
    du = B;
  }
  else
  {
    du = (us - u0) + x;
    if (F > 0)
      s.open = 0;
  }
  s.u = u0 + du;
  s.umax = max(umax, s.u);
  return F;
}

} // namespace joint_impl

// ----------------------------------------------------------------------------------- shear ----

namespace joint_impl
{

/// \brief Section 7 E4, generalised to the implicit option by (D13): trial force, Coulomb cap
/// (3), slip (4)/(16), softening (5) and dilation (6)/(15). `c` = dt^2/m* (0: explicit formulas);
/// `E` the tangent modulus at the end of the step. Fn is Fn' on entry and Fn'' on return.
/// Writes Fs' into `Fs_new` and returns the work of the shear force on the step.
KOKKOS_INLINE_FUNCTION Real shearUpdate(const JointParams &p, CpState &s, const CpKinematics &k,
                                        const Real Fs_rot[3], const Real Vs[3],
                                        const Real Fint_s[3], Real c, Real E, Real &Fn,
                                        Real Fs_new[3], CpStepResult &r)
{
  const Real Ac = k.Ac;
  const Real Ks = p.G * Ac / p.a, Kn = E * Ac / p.a;
  const Real G_eff = p.G / (1.0 + c * Ks), E_eff = E / (1.0 + c * Kn);
  Real Fst[3], ds[3];
  for (int d = 0; d < 3; ++d)
  { // (11), or (D13) with c*Ks*Fs_stick = Ks*(Vs dt + c Fint_s), finite for m* -> infinity
    Fst[d] = (Fs_rot[d] + Ks * (Vs[d] * k.dt + c * Fint_s[d])) / (1.0 + c * Ks);
  }
  const Real mag = norm(Fst);
  const Real phi = frictionAngle(p, s.usp); // start-of-step usp [A]
  const Real tphi = kmath::tan(phi);
  const Real CA = p.C * Ac;
  const Real Fs_max = max(0.0, CA + Fn * tphi); // (3)
  Real scale = 1.0;
  r.dusp = 0;
  r.slipped = 0;
  if (mag > Fs_max)
  {
    r.slipped = 1;
    if (Fs_max <= 0)
    { // no strength left (tension beyond the apex): full release, no dilation
      r.dusp = mag / (G_eff * Ac);
      scale = 0;
    }
    else
    {
      const Real tpsi = dilationTangent(p, Fn, Ac, tphi);
      Real Fs_max2 = Fs_max;
      if (p.dilation_update == DilationUpdate::Consistent)
      {
        const Real R = E_eff / G_eff;
        Fn = (Fn + R * tpsi * (mag - CA)) / (1.0 + R * tpsi * tphi); // (15)
        r.dusp = (mag - CA - Fn * tphi) / (G_eff * Ac);              // (16)
        Fs_max2 = max(0.0, CA + Fn * tphi);
      }
      else
      {
        r.dusp = (mag - Fs_max) / (G_eff * Ac); // (4)
        Fn += E_eff * Ac * tpsi * r.dusp;       // (6)
      }
      scale = Fs_max2 / mag; // (14)
    }
    s.usp += r.dusp;
  }
  for (int d = 0; d < 3; ++d)
  {
    Fs_new[d] = scale * Fst[d];
    // end-of-step relative slide: Vs' dt = Vs dt + c (Fint_s - Fs')
    ds[d] = Vs[d] * k.dt + c * (Fint_s[d] - Fs_new[d]);
  }
  Real dW = 0;
  for (int d = 0; d < 3; ++d)
    dW += 0.5 * (Fs_rot[d] + Fs_new[d]) * ds[d];
  return dW;
}

/// \brief Common frame of the explicit and implicit updates: rescale (6.6), rotate (13), normal,
/// shear, energy (6.7), store (E5).
KOKKOS_INLINE_FUNCTION CpStepResult jointUpdate(const JointParams &p, CpState &s,
                                                const CpKinematics &k, bool implicit)
{
  CpStepResult r;
  r.dW_area = 0;
  const Real Ac = k.Ac;
  if (p.traction_history && s.Ac_old > 0 && Ac != s.Ac_old)
  { // (6.6): keep tractions, not forces; the stored energy scales with Ac without work
    const Real ratio = Ac / s.Ac_old;
    r.dW_area = (ratio - 1.0) * storedEnergy(p, s.Fn, s.Fs, s.umax, s.Ac_old);
    s.Fn *= ratio;
    for (int d = 0; d < 3; ++d)
      s.Fs[d] *= ratio;
  }
  Real Fs_rot[3] = {s.Fs[0], s.Fs[1], s.Fs[2]};
  rotateWithNormal(s.n_old, k.n, Fs_rot);
  rotateWithNormal(s.n_old, k.n, s.us);
  Real Vs[3], Fint_s[3];
  const Real vn = dot(k.Vs, k.n), fn = dot(k.Fint_s, k.n);
  for (int d = 0; d < 3; ++d)
    Vs[d] = k.Vs[d] - vn * k.n[d], Fint_s[d] = k.Fint_s[d] - fn * k.n[d];
  const Real Psi0 = storedEnergy(p, s.Fn, Fs_rot, s.umax, Ac);

  // normal
  const Real c = implicit ? k.dt * k.dt / k.mstar : 0.0;
  Real du, dWn;
  Real Fn;
  if (implicit)
    Fn = normalImplicit(p, s, Ac, k.Vn * k.dt + c * k.Fint_n, c, du, dWn, r.opened);
  else
  {
    du = k.Vn * k.dt;
    Fn = normalExplicit(p, s, Ac, du, dWn, r.opened);
  }

  // shear
  Real Fs_new[3] = {0, 0, 0};
  Real dWs = 0;
  r.dusp = 0, r.slipped = 0;
  if (!s.open)
  {
    const Real E = jointModulus(p, s.u, s.umax);
    const bool inertial_shear = implicit && p.implicit_shear;
    dWs = shearUpdate(p, s, k, Fs_rot, Vs, Fint_s, inertial_shear ? c : 0.0, E, Fn, Fs_new, r);
  }
  for (int d = 0; d < 3; ++d)
    s.us[d] += Vs[d] * k.dt;

  // energy (6.7) and store (E5)
  r.Fn = Fn;
  for (int d = 0; d < 3; ++d)
    r.Fs[d] = Fs_new[d];
  r.dW = dWn + dWs;
  r.dPsi = storedEnergy(p, Fn, Fs_new, s.umax, Ac) - Psi0;
  r.dD = r.dW - r.dPsi;
  s.Fn = Fn;
  for (int d = 0; d < 3; ++d)
    s.Fs[d] = Fs_new[d], s.n_old[d] = k.n[d];
  s.Ac_old = Ac;
  return r;
}

} // namespace joint_impl

// ---------------------------------------------------------------------------- public API ----

/// \brief Explicit update, section 7 (E1-E5): (7)-(9), (D8)-(D11), (11)-(16), (13), 6.6, 6.7.
/// k.Vn, k.Vs from v^n; m* and Fint unused. Stability needs dt <= contactTimeStep().
KOKKOS_INLINE_FUNCTION CpStepResult updateExplicit(const JointParams &p, CpState &s,
                                                   const CpKinematics &k)
{
  return joint_impl::jointUpdate(p, s, k, false);
}

/// \brief Quasi-implicit update, section 10: normal (20)-(23) with the end-of-step force, shear
/// by (D13) (p.implicit_shear) or literal E4. Velocities v* with Fint = 0 (10.6, recommended) or
/// v^n with Fint from (21): the two give the same B and Fs_stick. m* = infinity (c = 0) gives
/// the joint law itself; m* -> 0 (or a -> 0) the slide-line force (24).
KOKKOS_INLINE_FUNCTION CpStepResult updateImplicit(const JointParams &p, CpState &s,
                                                   const CpKinematics &k)
{
  return joint_impl::jointUpdate(p, s, k, true);
}

} // namespace scpdyn
