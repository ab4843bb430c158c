#pragma once
/// \file ScalarOps.hpp
/// \brief Branch helpers on reals for host and device code: abs, min, max, clamp. Plain
/// compares, the same on every backend (elementary functions: kmath in core/Types.hpp). With a
/// NaN operand min and max return the second one.
#include "core/Types.hpp"

namespace scpdyn
{
namespace scalar_ops
{
KOKKOS_INLINE_FUNCTION Real abs(Real x) { return x < 0 ? -x : x; }
KOKKOS_INLINE_FUNCTION Real min(Real x, Real y) { return x < y ? x : y; }
KOKKOS_INLINE_FUNCTION Real max(Real x, Real y) { return x > y ? x : y; }
KOKKOS_INLINE_FUNCTION Real clamp(Real x, Real lo, Real hi)
{
  return x < lo ? lo : x > hi ? hi : x;
}
} // namespace scalar_ops
} // namespace scpdyn
