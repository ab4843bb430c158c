#pragma once
/// \file Erosion.hpp
/// \brief The element erosion criterion (docs/theory.md 11.6): which limit of a material's
/// ErosionLimits an element's state has passed.
#include "material/Geomaterial.hpp"
#include "material/MaterialParams.hpp"

namespace scpdyn
{

/// \brief Volumetric strain V / V0 - 1 of an element of constant mass: V0 = mass / rho0.
KOKKOS_INLINE_FUNCTION Real volumetricStrain(const MaterialParams &m, Real mass, Real volume)
{
  return volume * m.density / mass - 1;
}

/// \brief Whether an element of these limits erodes: its plastic strain, damage (the
/// geomaterial's, else pass 0) or volumetric strain passed its limit, or its stable time step
/// fell below the floor (stable_dt <= 0, an inverted element, always erodes once any limit
/// is set). Limits that are 0 are off.
KOKKOS_INLINE_FUNCTION bool erosionLimitPassed(const ErosionLimits &l, Real plastic_strain,
                                               Real damage, Real volumetric_strain, Real stable_dt)
{
  if (!l.active)
    return false;
  return !(stable_dt > 0) || (l.time_step > 0 && stable_dt < l.time_step) ||
         (l.plastic_strain > 0 && plastic_strain >= l.plastic_strain) ||
         (l.damage > 0 && damage >= l.damage) ||
         (l.volumetric_strain_min < 0 && volumetric_strain <= l.volumetric_strain_min) ||
         (l.volumetric_strain_max > 0 && volumetric_strain >= l.volumetric_strain_max);
}

/// \brief The damage an erosion limit reads from an element's history: the geomaterial's D,
/// 0 for every other model.
KOKKOS_INLINE_FUNCTION Real erosionDamage(const MaterialParams &m, const Real *history)
{
  return m.model == MaterialModel::Geomaterial ? history[kGeoHistDamage] : Real(0);
}

} // namespace scpdyn
