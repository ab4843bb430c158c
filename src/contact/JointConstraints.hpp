#pragma once
/// \file JointConstraints.hpp
/// \brief The velocity-constraint options of the Simple Common Plane contact (docs/theory.md
/// 10.5, 10.8, 11): slide line (24)/(D14), sticky (25), sleepy (D15), the option dispatcher
/// updateCp() and the inactive-CP update (3.4). Same conventions as JointLaw.hpp: F = Fn*n + Fs
/// acts on face 2, -F on face 1.
#include "contact/JointLaw.hpp"

namespace scpdyn
{

namespace joint_impl
{
using namespace contact_math;

/// \brief Slide-line normal force with gaps (D14), clamped >= 0; advances u with the end-of-step
/// relative velocity. Returns Fn and sets the end-of-step Vn'.
KOKKOS_INLINE_FUNCTION Real slideLineNormal(CpState &s, const CpKinematics &k, Real &Vn1)
{
  const Real g = max(0.0, -s.u);
  const Real Fn = max(0.0, k.mstar * (k.Vn - g / k.dt) / k.dt + k.Fint_n);
  Vn1 = k.Vn + k.dt * (k.Fint_n - Fn) / k.mstar;
  s.u += k.dt * Vn1;
  s.umax = max(s.umax, s.u);
  return Fn;
}

/// \brief Velocity-constraint options store nothing: the energy they take out is the work of the
/// force on the mean of the start and end relative velocities of the model masses.
KOKKOS_INLINE_FUNCTION void constraintFinish(CpState &s, const CpKinematics &k, const Real V0[3],
                                             const Real F[3], CpStepResult &r)
{
  r.dW = 0;
  for (int d = 0; d < 3; ++d)
  {
    const Real V1 = V0[d] + k.dt * ((k.Fint_n * k.n[d] + k.Fint_s[d]) - F[d]) / k.mstar;
    r.dW += 0.5 * F[d] * (V0[d] + V1) * k.dt;
  }
  r.dPsi = 0, r.dD = r.dW, r.dW_area = 0, r.dusp = 0, r.opened = 0;
  r.Fn = dot(F, k.n);
  for (int d = 0; d < 3; ++d)
    r.Fs[d] = F[d] - r.Fn * k.n[d];
  s.Fn = r.Fn;
  for (int d = 0; d < 3; ++d)
    s.Fs[d] = r.Fs[d], s.n_old[d] = k.n[d];
  s.Ac_old = k.Ac;
}

} // namespace joint_impl

/// \brief Slide line (24) with gaps (D14): Fn >= 0 stops the normal approach by the end of the
/// step, no shear. Needs a finite m*.
KOKKOS_INLINE_FUNCTION CpStepResult updateSlideLine(CpState &s, const CpKinematics &k)
{
  CpStepResult r;
  Real Vn1;
  const Real Fn = joint_impl::slideLineNormal(s, k, Vn1);
  Real V0[3], F[3];
  for (int d = 0; d < 3; ++d)
    V0[d] = k.Vn * k.n[d] + k.Vs[d], F[d] = Fn * k.n[d];
  r.slipped = 0;
  joint_impl::constraintFinish(s, k, V0, F, r);
  return r;
}

/// \brief Sticky (24) unclamped + (25): F = m*(V1 - V2)/dt + Fint, so the model masses end the
/// step with V1' = V2'. No tension or Coulomb limit. A node shared by several CPs is
/// over-corrected by one pass of independent CPs (10.8): this is the single-CP form; the
/// runtime solves all the ties of a cycle together (contact/ContactConstraints.cpp).
KOKKOS_INLINE_FUNCTION CpStepResult updateSticky(CpState &s, const CpKinematics &k)
{
  CpStepResult r;
  Real V0[3], F[3];
  for (int d = 0; d < 3; ++d)
  {
    V0[d] = k.Vn * k.n[d] + k.Vs[d];
    F[d] = k.mstar * V0[d] / k.dt + k.Fint_n * k.n[d] + k.Fint_s[d];
  }
  // V_n' = 0 by construction, so the tracked closure u stays as it is
  r.slipped = 0;
  joint_impl::constraintFinish(s, k, V0, F, r);
  return r;
}

/// \brief Sleepy (D15): sticky while s.failed == 0; afterwards slide line (D14) with residual
/// Coulomb friction Fs_max = tan(phi1) Fn (C = 0). The caller sets s.failed irreversibly.
KOKKOS_INLINE_FUNCTION CpStepResult updateSleepy(const JointParams &p, CpState &s,
                                                 const CpKinematics &k)
{
  using namespace contact_math;
  if (!s.failed)
    return updateSticky(s, k);
  CpStepResult r;
  Real Vn1;
  const Real Fn = joint_impl::slideLineNormal(s, k, Vn1);
  Real Fst[3], V0[3], F[3];
  for (int d = 0; d < 3; ++d)
    Fst[d] = k.mstar * k.Vs[d] / k.dt + k.Fint_s[d]; // (25)
  const Real mag = norm(Fst), Fs_max = kmath::tan(p.phi1) * Fn;
  const Real scale = mag > Fs_max ? Fs_max / mag : 1.0;
  r.slipped = mag > Fs_max ? 1 : 0;
  for (int d = 0; d < 3; ++d)
    V0[d] = k.Vn * k.n[d] + k.Vs[d], F[d] = Fn * k.n[d] + scale * Fst[d];
  joint_impl::constraintFinish(s, k, V0, F, r);
  return r;
}

/// \brief Whether the CP is a tie this cycle: sticky, or sleepy before its switch (11.4).
KOKKOS_INLINE_FUNCTION bool isTie(const JointParams &p, const CpState &s)
{
  return p.option == ContactOption::Sticky || (p.option == ContactOption::Sleepy && !s.failed);
}

/// \brief Whether the CP is a slide line this cycle: a slide line, or sleepy after its switch.
KOKKOS_INLINE_FUNCTION bool isSlide(const JointParams &p, const CpState &s)
{
  return p.option == ContactOption::SlideLine || (p.option == ContactOption::Sleepy && s.failed);
}

/// \brief The sleepy switch (11.4): whether the failure measures m1, m2 of the elements behind
/// faces 1 and 2 (or the time t, for FailureMeasure::Time) fail the tie of p: either element at
/// or past the threshold, or both with `failure_both`.
KOKKOS_INLINE_FUNCTION bool sleepyFails(const JointParams &p, Real m1, Real m2, Real t)
{
  using namespace contact_math;
  switch (p.failure_measure)
  {
  case FailureMeasure::None:
    return false;
  case FailureMeasure::Time:
    return t >= p.failure_threshold;
  default:
    return (p.failure_both ? min(m1, m2) : max(m1, m2)) >= p.failure_threshold;
  }
}

/// \brief One active CP step with the option of p (section 11, Appendix A).
KOKKOS_INLINE_FUNCTION CpStepResult updateCp(const JointParams &p, CpState &s,
                                             const CpKinematics &k)
{
  switch (p.option)
  {
  case ContactOption::Explicit:
    return updateExplicit(p, s, k);
  case ContactOption::Implicit:
    return updateImplicit(p, s, k);
  case ContactOption::SlideLine:
    return updateSlideLine(s, k);
  case ContactOption::Sticky:
    return updateSticky(s, k);
  default:
    return updateSleepy(p, s, k);
  }
}

/// \brief Inactive CP (3.4): no force, history frozen except n_old <- n and u <- u + Vn dt.
KOKKOS_INLINE_FUNCTION void updateInactiveCp(CpState &s, const Real n[3], Real Vn, Real dt)
{
  s.u += Vn * dt;
  for (int d = 0; d < 3; ++d)
    s.n_old[d] = n[d];
}

} // namespace scpdyn
