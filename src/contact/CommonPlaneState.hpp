#pragma once
/// \file CommonPlaneState.hpp
/// \brief Joint (common-plane contact) parameters and per-CP history, both POD so they can live
/// in Views and be copied into kernels. Equation numbers refer to docs/theory.md.
#include "core/ScalarOps.hpp"
#include "core/Types.hpp"

namespace scpdyn
{

/// \brief Small vector helpers usable on host and device (square roots and trigonometry come
/// from the project-wide `kmath` alias of core/Types.hpp).
namespace contact_math
{
using scalar_ops::abs;
using scalar_ops::max;
using scalar_ops::min;
KOKKOS_INLINE_FUNCTION Real dot(const Real x[3], const Real y[3])
{
  return x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
}
KOKKOS_INLINE_FUNCTION void cross(const Real x[3], const Real y[3], Real r[3])
{
  r[0] = x[1] * y[2] - x[2] * y[1];
  r[1] = x[2] * y[0] - x[0] * y[2];
  r[2] = x[0] * y[1] - x[1] * y[0];
}
KOKKOS_INLINE_FUNCTION Real norm(const Real x[3]) { return kmath::sqrt(dot(x, x)); }
} // namespace contact_math

/// \brief Contact option of a CP (docs/theory.md section 11).
enum class ContactOption : int
{
  SlideLine = 0, ///< (24)/(D14): normal stop force, no shear
  Sticky = 1,    ///< (24) unclamped + (25): tied interface
  Explicit = 2,  ///< section 7: incremental joint law, time-step limit (19)
  Implicit = 3,  ///< section 10: quasi-implicit joint law, no time-step limit
  Sleepy = 4     ///< (D15): sticky until `failed`, then slide line with residual friction
};

/// \brief What switches a sleepy CP from tied to sliding (11.4): a failure measure of the elements
/// behind its faces, or the time.
enum class FailureMeasure : int
{
  None = 0,
  PlasticStrain = 1, ///< equivalent plastic strain of the element [-]
  Damage = 2,        ///< damage D of a geomaterial element [-] (0 for other models)
  Time = 3           ///< the time [s]: a switch forced at a prescribed moment
};

/// \brief How the CP force is spread over the face nodes (section 8).
enum class DistributionRule : int
{
  Penetration = 0, ///< (17)-(18), shape-function fallback of 8.2 when nothing penetrates
  Poc = 1          ///< shape-function weights at the POC always
};

/// \brief Face velocities V1, V2 of (10), (12).
enum class VelocityRule : int
{
  Weighted = 0, ///< nodal velocities weighted like the CP force (work-conjugate; default)
  Average = 1   ///< plain average of the nodal velocities (the paper's wording, section 5)
};

/// \brief Dilation coupling on a slipping step (section 7, E4).
enum class DilationUpdate : int
{
  Consistent = 0, ///< (15)-(16): ends exactly on the updated yield surface (default)
  Explicit = 1    ///< (4) then (6): the paper's dashed-line variant (ends inside the surface)
};

/// \brief Form of the explicit contact time-step limit (19), section 9.
enum class DtContactForm : int
{
  MassSpring = 0, ///< 2*C_safe*sqrt(a*mu*/max(E_pred,G)) (normative)
  Paper = 1       ///< C_safe*a*sqrt(rho_bar/E_pred)
};

/// \brief Joint parameters of one face BC, or the average used by one CP (SI units, radians).
///
/// Defaults are Table 1 of the paper plus the [A] defaults of section 13. `Emax < 0` and
/// `sigma_t < 0` mean "derive the default" (1e4*E0 and C/tan(phi0)); call resolveParams() once
/// after the deck is read.
struct JointParams
{
  Real a = 1.0e-4;                 ///< aperture = asymptotic closure [m]
  Real E0 = 5.0e7;                 ///< initial normal modulus, E0 = Kn*a [Pa]
  Real G = 5.0e7;                  ///< shear modulus, G = Ks*a [Pa]
  Real C = 1.0e6;                  ///< cohesion [Pa]
  Real phi0 = 0.6981317007977318;  ///< initial friction angle [rad] (40 deg)
  Real phi1 = 0.17453292519943295; ///< residual friction angle [rad] (10 deg)
  Real usp0 = 100.0;               ///< characteristic slip of softening, in apertures [-]
  Real psi0 = 0.0;                 ///< initial dilation angle [rad] (Table 1: 0-15 deg)
  Real sigma_cr = 1.0e8;           ///< no dilation above this normal stress [Pa]
  Real Emax = -1.0;                ///< modulus cut-off [Pa]; < 0: 1e4*E0 (D8)
  Real sigma_t = -1.0;             ///< tensile strength [Pa]; < 0: C/tan(phi0) (D9)
  Real C_safe = 0.5;               ///< safety factor of (19); infinity disables the limit
  ContactOption option = ContactOption::Implicit;
  DilationUpdate dilation_update = DilationUpdate::Consistent;
  DtContactForm dt_form = DtContactForm::MassSpring;
  DistributionRule distribution = DistributionRule::Penetration;
  VelocityRule velocity = VelocityRule::Weighted;
  bool traction_history = true; ///< rescale stored forces with Ac (6.6)
  bool implicit_shear = true;   ///< (D13) in the implicit option (10.7)
  bool brittle_tension = false; ///< sigma_t (and C) -> 0 for a CP after it first opens (6.5)
  int bc_id = 0;                ///< face-BC id: decides non-numeric fields in averageParams()
  // slide line: Coulomb friction mu = mu_k + (mu_s - mu_k) exp(-mu_dc |Vs|)
  Real mu_s = 0;  ///< static coefficient [-]
  Real mu_k = 0;  ///< kinetic coefficient [-]
  Real mu_dc = 0; ///< decay coefficient [s/m]
  // sleepy: the switch to sliding (11.4)
  FailureMeasure failure_measure = FailureMeasure::None;
  Real failure_threshold = 0; ///< the measure's value that fails the tie [its unit]
  bool failure_both = false;  ///< the elements of both faces must fail, not either
};

/// \brief Fill the derived defaults (Emax = 1e4*E0, sigma_t = C/tan(phi0), or 0 when phi0 = 0).
KOKKOS_INLINE_FUNCTION JointParams resolveParams(JointParams p)
{
  if (p.Emax < 0)
    p.Emax = 1.0e4 * p.E0;
  if (p.sigma_t < 0)
    p.sigma_t = p.phi0 > 0 ? p.C / kmath::tan(p.phi0) : 0.0;
  return p;
}

/// \brief Parameters of a CP whose faces carry different BCs (section 3.6): arithmetic mean of
/// every numerical joint parameter (resolved first, so derived defaults are averaged as values);
/// option, flags and the sleepy switch (measure, threshold, sides) from the BC with
/// the smaller id; C_safe the smaller of the two.
///
/// Angles are stored in radians: their mean equals the mean in degrees converted. The result is
/// symmetric in its arguments, so both ranks of a cross-rank CP get bitwise-identical values.
KOKKOS_INLINE_FUNCTION JointParams averageParams(const JointParams &p1_in, const JointParams &p2_in)
{
  const JointParams p1 = resolveParams(p1_in);
  const JointParams p2 = resolveParams(p2_in);
  JointParams r = p1.bc_id <= p2.bc_id ? p1 : p2;
  r.a = 0.5 * (p1.a + p2.a);
  r.E0 = 0.5 * (p1.E0 + p2.E0);
  r.G = 0.5 * (p1.G + p2.G);
  r.C = 0.5 * (p1.C + p2.C);
  r.phi0 = 0.5 * (p1.phi0 + p2.phi0);
  r.phi1 = 0.5 * (p1.phi1 + p2.phi1);
  r.usp0 = 0.5 * (p1.usp0 + p2.usp0);
  r.psi0 = 0.5 * (p1.psi0 + p2.psi0);
  r.sigma_cr = 0.5 * (p1.sigma_cr + p2.sigma_cr);
  r.Emax = 0.5 * (p1.Emax + p2.Emax);
  r.sigma_t = 0.5 * (p1.sigma_t + p2.sigma_t);
  r.C_safe = p1.C_safe < p2.C_safe ? p1.C_safe : p2.C_safe;
  r.mu_s = 0.5 * (p1.mu_s + p2.mu_s);
  r.mu_k = 0.5 * (p1.mu_k + p2.mu_k);
  r.mu_dc = 0.5 * (p1.mu_dc + p2.mu_dc);
  return r;
}

/// \brief The contact law of self-contact (11.5): two faces of one part meeting (a crushing or
/// folding body) are not a joint and not a tie, whatever the surface's option: they meet as a
/// frictional slide line. Its Coulomb coefficient is the surface's own `mu_*` (slide line,
/// sleepy), tan(phi1) for the joint options (rock on rock at residual friction), 0 for sticky.
KOKKOS_INLINE_FUNCTION JointParams selfContactParams(JointParams p)
{
  if (p.option == ContactOption::Explicit || p.option == ContactOption::Implicit)
  {
    p.mu_s = p.mu_k = kmath::tan(p.phi1);
    p.mu_dc = 0;
  }
  p.option = ContactOption::SlideLine;
  p.failure_measure = FailureMeasure::None;
  return p;
}

/// \brief Parameters of the CP between faces of surfaces with parameters p1, p2 (3.6), of one
/// mesh part when `same_part` (self-contact, 11.5).
KOKKOS_INLINE_FUNCTION JointParams planeParams(const JointParams &p1, const JointParams &p2,
                                               bool same_part)
{
  const JointParams p = averageParams(p1, p2);
  return same_part ? selfContactParams(p) : p;
}

/// \brief History of one common plane (section 12). Forces are those acting on face 2
/// (`F = Fn*n + Fs`); face 1 receives `-F`.
struct CpState
{
  Real u = 0;                  ///< normal closure, > 0 closed/overlapped [m]
  Real umax = 0;               ///< largest closure so far [m]
  Real Fn = 0;                 ///< normal force, > 0 compression [N]
  Real Fs[3] = {0, 0, 0};      ///< shear force on face 2 [N]
  Real usp = 0;                ///< accumulated plastic slip / a [-]
  Real us[3] = {0, 0, 0};      ///< accumulated shear displacement (diagnostic) [m]
  Real n_old[3] = {0, 0, 1};   ///< CP normal of the previous cycle
  Real u_z = 0;                ///< zero-force closure while open (D10, D11) [m]
  Real Ac_old = 0;             ///< contact area of the previous active cycle [m^2]
  int open = 0;                ///< 1: joint open (no force until u > u_z)
  int failed = 0;              ///< sleepy option: 1 after the failure switch (irreversible)
  Real sigma_t_scale = 1;      ///< 0 after first opening with brittle_tension (6.5)
  Real V_model[3] = {0, 0, 0}; ///< implicit option: end-of-step V1 - V2 its model predicted [m/s]
  Real dt_model = 0;           ///< implicit option: the step of that prediction (0: none) [s]
};

/// \brief History of a new CP (section 12 and D12): u = u0 from (D7), umax = max(u0, 0); a gap
/// starts open with u_z = 0, an overlap starts closed at zero force with u_z = u0 ("forgiven").
KOKKOS_INLINE_FUNCTION CpState initialCpState(Real u0, const Real n[3], Real Ac)
{
  CpState s;
  s.u = u0;
  s.umax = u0 > 0 ? u0 : 0;
  s.open = u0 < 0 ? 1 : 0;
  s.u_z = u0 < 0 ? 0 : u0;
  for (int d = 0; d < 3; ++d)
    s.n_old[d] = n[d];
  s.Ac_old = Ac;
  return s;
}

} // namespace scpdyn
