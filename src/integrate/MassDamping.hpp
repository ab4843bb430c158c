#pragma once
/// \file MassDamping.hpp
/// \brief The settling stage's mass-proportional damping of step 12 (docs/theory.md 2.4): a
/// force -alpha m v on every free node component, with v the step's mean velocity
/// (v^n + v^{n+1}) / 2, so that the update stays explicit and is stable for every alpha dt.
#include "core/Types.hpp"

namespace scpdyn
{

/// \brief The damped leapfrog kick of one step dt with coefficient alpha [1/s]:
/// v^{n+1} = ((1 - a) v^n + dt F / m) / (1 + a), a = alpha dt / 2.
struct MassDamping
{
  Real a = 0;     ///< alpha dt / 2
  Real keep = 1;  ///< (1 - a) / (1 + a): what is left of v^n
  Real scale = 1; ///< 1 / (1 + a): what is left of the undamped kick dt F / m

  /// v^{n+1} from v^n and the undamped velocity change dv = dt F / m.
  KOKKOS_INLINE_FUNCTION Real velocity(const Real v_old, const Real dv) const
  {
    return keep * v_old + scale * dv;
  }
  /// The damping force's impulse over the step, -alpha dt m (v^n + v^{n+1}) / 2 [N s]
  /// (= m (v^{n+1} - v^n) - dt F for the velocity() of the same step).
  KOKKOS_INLINE_FUNCTION Real impulse(const Real m, const Real v_old, const Real v_new) const
  {
    return -a * m * (v_old + v_new);
  }
};

/// \brief The damping of a step dt with coefficient alpha >= 0 [1/s] (alpha 0: the undamped
/// kick, and no impulse).
KOKKOS_INLINE_FUNCTION MassDamping massDamping(const Real alpha, const Real dt)
{
  MassDamping d;
  d.a = 0.5 * alpha * dt;
  d.scale = 1 / (1 + d.a);
  d.keep = (1 - d.a) * d.scale;
  return d;
}

} // namespace scpdyn
