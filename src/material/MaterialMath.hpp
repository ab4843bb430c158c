#pragma once
/// \file MaterialMath.hpp
/// \brief Scalar helpers of the material models: min/max/clamp and a bracketed root finder
/// for the plastic-multiplier equations (device-callable, no allocation).
#include "core/ScalarOps.hpp"
#include "core/Types.hpp"

namespace scpdyn
{

/// \brief The branch helpers of core/ScalarOps.hpp under the name the material models use.
namespace material_math
{
using scalar_ops::abs;
using scalar_ops::clamp;
using scalar_ops::max;
using scalar_ops::min;
} // namespace material_math

/// \brief Root of f on [lo, hi] where f(lo) and f(hi) have opposite signs (or one is zero).
///
/// Illinois variant of regula falsi (Dowell & Jarratt 1971): superlinear on the smooth,
/// monotone functions met here, and it keeps the bracket, so a kink in f (the Johnson-Cook
/// rate term switching on, a strength cap) cannot throw it out of range. Every fourth step is
/// a bisection, which bounds the work on pathological f. Stops when |f| <= ftol or the bracket
/// is narrower than xtol.
template <class F>
KOKKOS_INLINE_FUNCTION Real bracketedRoot(const F &f, Real lo, Real flo, Real hi, Real fhi,
                                          Real xtol, Real ftol)
{
  if (flo == 0)
    return lo;
  if (fhi == 0)
    return hi;
  int side = 0;
  Real x = lo;
  for (int it = 0; it < 200; ++it)
  {
    x = (it % 4 == 3) ? 0.5 * (lo + hi) : (flo * hi - fhi * lo) / (flo - fhi);
    if (!(x > lo && x < hi)) // round-off at a converged bracket
      x = 0.5 * (lo + hi);
    const Real fx = f(x);
    if (material_math::abs(fx) <= ftol)
      return x;
    if ((fx > 0) == (fhi > 0))
    {
      hi = x;
      fhi = fx;
      if (side == -1)
        flo *= 0.5;
      side = -1;
    }
    else
    {
      lo = x;
      flo = fx;
      if (side == +1)
        fhi *= 0.5;
      side = +1;
    }
    if (hi - lo <= xtol)
      break;
  }
  return x;
}

} // namespace scpdyn
