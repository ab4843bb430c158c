#pragma once
/// \file ContactChecks.hpp
/// \brief The divergence test of step 9 (what stops a run) and the closure limits shared with
/// the candidate rules of detection (docs/theory.md 3.2, 3.4, 6.2). Device-callable.
#include "contact/CommonPlaneState.hpp"

namespace scpdyn
{

/// \brief Closure beyond the joint's zero-force closure u_z, in apertures, past which a joint
/// counts as diverged [-].
///
/// Measured from u_z, not from 0: u_z is where the joint's force line starts (D10-D12), and a CP
/// created on faces that already overlap (D12 forgives the overlap, u_z = u0) or an open joint
/// whose faces moved far (bricks that slid or rotated past each other, and meet again) has
/// u = u_z plus what it has closed since: a large u at zero force is not a diverged joint.
///
/// Not 1: with the modulus cap (6.2, D8) the closure is not bounded by a, and stable
/// explicit runs pass it for a step or two (bar1d.py's explicit Fig. 2 references at C_safe =
/// 0.5 reach u/a = 1.08 at the impact joint). At 2 a the capped law's stress is ~Emax
/// (1e4 E0 by default, TPa for rock joints): only a diverging update gets there.
constexpr Real kDivergedClosure = 2.0;

/// \brief A CP whose contact area is below this fraction of its smaller face is vanishing: its
/// faces slide apart, its force and stored energy scale with Ac (6.6) and its tracked closure
/// takes in the sliding velocity through a tilting normal, so its closure proves nothing [-].
constexpr Real kVanishingArea = 0.1;

/// \brief Net energy the joints (explicit and implicit CPs) and slide lines may give the mesh, as
/// a fraction of the most they ever took in or held, before the contact counts as diverged [-].
///
/// A joint law only stores or dissipates the work done on it (6.7), so the joints' net work W
/// stays >= 0 (>= about -Psi when the leapfrog books the work a step late). Every stable run
/// measured keeps W >= 0 (Fig. 5 implicit S = 0.5 and explicit S = 0.05, 0.1 and with the limit
/// (19) at S = 0.5, the Fig. 2 strips, the Fig. 7 sliding impact); the unstable explicit update
/// of Fig. 5 at S = 0.5 with C_safe off drives W to -11 W_peak at its third cycle. A slide line
/// only dissipates (its forces minimise the kinetic energy left, ContactBoundSolve.cpp), so it
/// is tested the same way. Sticky CPs are left out: ties do no work, and their booked work is
/// round-off and leapfrog lag of either sign.
constexpr Real kEnergyCreation = 1.0;

/// \brief Slide lines: the net work may also dip by this fraction of the contact nodes' kinetic
/// energy [-]. A slide line in persistent contact moves with its faces and books leapfrog lag of
/// either sign (a quasi-static patch: -1.8e-20 J against a peak of 3.3e-22 J); the slide lines
/// that created energy before their solve was bound-constrained gave the mesh many times its
/// kinetic energy within ten cycles.
constexpr Real kSlideLag = 1e-3;

/// \brief Slide lines: the net work may also dip by this fraction of the work they carried from
/// one body to the other, summed over the run [-]. The bound solve stops at 1e-10 of its first
/// residual, so the relative velocity it leaves, and the work booked on it, is round-off of that
/// order of the carried work: the quasi-static patch T4a under 10 MPa carries 2.3e3 J and books
/// noise of either sign up to 1e-6 J (4e-10), different in every run at two threads (the order
/// of the atomic nodal sums), which crossed the slide lines' peak net work in one run of four.
/// The slide lines that created energy gave the mesh many times the work they carried.
constexpr Real kSlideRoundOff = 1e-8;

/// \brief True when the joints have created energy: net joint work `work` below
/// -kEnergyCreation * max(`work_peak`, `stored_peak`) (the largest net work and stored energy
/// so far, this cycle included), beyond the round-off 1e-12 `gross` of the summed |work| [J].
KOKKOS_INLINE_FUNCTION bool contactCreatedEnergy(Real work, Real work_peak, Real stored_peak,
                                                 Real gross)
{
  const Real limit = kEnergyCreation * contact_math::max(work_peak, stored_peak) + 1e-12 * gross;
  return work < -limit || !(work - work == 0);
}

/// \brief Why a CP failed the divergence test.
enum CpCheck : int
{
  CpCheckOk = 0,
  CpCheckNonFinite = 1, ///< a force component or the closure/force history is NaN or infinite
  CpCheckClosure = 2    ///< a joint's closure passed kDivergedClosure apertures
};

/// \brief Divergence test of one CP after its force (step 9). `F`: the CP force [N]; `joint`:
/// explicit or implicit option (the constraint options keep u at the geometric gap); `active`:
/// status != inactive (3.4); `Ac`, `A1`, `A2`: contact and face areas.
KOKKOS_INLINE_FUNCTION int checkCp(const JointParams &p, const CpState &s, const Real F[3],
                                   bool joint, bool active, Real Ac, Real A1, Real A2)
{
  bool finite = s.u - s.u == 0 && s.Fn - s.Fn == 0; // false for NaN and infinity
  for (int d = 0; d < 3; ++d)
    finite = finite && F[d] - F[d] == 0 && s.Fs[d] - s.Fs[d] == 0;
  if (!finite)
    return CpCheckNonFinite;
  const bool vanishing = !(Ac >= kVanishingArea * contact_math::min(A1, A2));
  if (joint && active && !vanishing && s.u - s.u_z > kDivergedClosure * p.a)
    return CpCheckClosure;
  return CpCheckOk;
}

/// \brief Penetration a candidate pair may have and stay a candidate (rule 5 of 3.2, delta_pen):
/// half the smallest of the two face diameters `h` and the two element depths `d` behind them
/// (ContactFaceData::depth), plus the closure the divergence test still accepts, so a joint
/// closed by more than that (a fine mesh, a soft joint) keeps its CP [m]. The depths keep a
/// face from pairing with the far face of its neighbour in a layer of flat elements (a brick
/// course one element high: one element's bottom and the next one's top overlap by the whole
/// thickness, less than half their diameter).
KOKKOS_INLINE_FUNCTION Real candidatePenetration(Real h1, Real h2, Real d1, Real d2, Real a)
{
  const Real size = contact_math::min(contact_math::min(h1, h2), contact_math::min(d1, d2));
  return 0.5 * size + kDivergedClosure * a;
}

} // namespace scpdyn
