#pragma once
/// \file JointGauge.hpp
/// \brief Per-joint histories (gauges of kind `joint`, docs/input.md): sums over the live
/// common planes whose point of contact lies within a radius of a point, from which the
/// driver forms the joint's stresses and mean closure and slip.
#include "contact/ContactData.hpp"

namespace scpdyn
{

/// \brief Sums over the CPs of one joint gauge; additive over ranks (a CP counts on the rank
/// of its face 1, as in the point-set output).
struct JointGaugeSums
{
  Real area = 0;         ///< sum of Ac of the active CPs [m^2]
  Real normal_force = 0; ///< sum of Fn, > 0 compression [N]
  Real shear_force = 0;  ///< sum of |Fs| [N]
  Real closure_area = 0; ///< sum of u Ac (active CPs) [m^3]
  Real slip_area = 0;    ///< sum of slip Ac (active CPs) [m^3]
  Real closure = 0;      ///< sum of u (all CPs in range) [m]
  Real slip = 0;         ///< sum of slip (all CPs in range) [m]
  Real count = 0;        ///< CPs in range

  static constexpr int kCount = 8;
  KOKKOS_INLINE_FUNCTION Real *begin() { return &area; }
  KOKKOS_INLINE_FUNCTION const Real *begin() const { return &area; }
  KOKKOS_INLINE_FUNCTION JointGaugeSums &operator+=(const JointGaugeSums &o)
  {
    for (int k = 0; k < kCount; ++k)
      begin()[k] += o.begin()[k];
    return *this;
  }
  KOKKOS_INLINE_FUNCTION void operator+=(const volatile JointGaugeSums &o) volatile
  {
    volatile Real *mine = &area;
    const volatile Real *theirs = &o.area;
    for (int k = 0; k < kCount; ++k)
      mine[k] += theirs[k];
  }
};

/// \brief The sums over this rank's live CPs (face 1 not a ghost) with |x_poc - point| <=
/// radius [m]. Inactive CPs (no overlap) count in `count`, `closure` and `slip` only.
JointGaugeSums jointGaugeSums(const CommonPlaneData &cp, const ContactFaceData &faces,
                              const Real point[3], Real radius);

/// \brief Quantity `code` (its index in jointGaugeQuantities(), input/Deck.hpp) from the
/// rank-summed sums: `normal_stress`, `shear_stress` (force / active area, Pa, compression
/// positive; 0 without contact area), `normal_force`, `shear_force` (N; per metre in plane
/// strain, per radian axisymmetric), `area` (m^2), `closure`, `slip` (m; means weighted by
/// area over the active CPs, else plain means, else 0), `count` (CPs in range).
Real jointGaugeQuantity(const JointGaugeSums &s, int code);

} // namespace scpdyn

namespace Kokkos
{
template <>
struct reduction_identity<scpdyn::JointGaugeSums>
{
  KOKKOS_FORCEINLINE_FUNCTION static scpdyn::JointGaugeSums sum()
  {
    return scpdyn::JointGaugeSums();
  }
};
} // namespace Kokkos
