#pragma once
/// \file MaterialLibrary.hpp
/// \brief Deck-side view of the material models: which keys each model takes, their checks
/// (validateMaterialSpec, MaterialSpec.hpp), and the conversion from MaterialSpec (deck) to
/// MaterialParams (kernels).
#include "material/MaterialParams.hpp"
#include "material/MaterialSpec.hpp"

#include <string>
#include <vector>

namespace scpdyn
{

/// \brief Validated conversion to the kernel parameters (calls validateMaterialSpec).
MaterialParams makeMaterialParams(const MaterialSpec &spec);

/// \brief Reference P-wave (uniaxial-strain) sound speed sqrt((K + 4G/3)/rho0) [m/s].
Real referenceSoundSpeed(const MaterialParams &p);

/// \brief Output names of the kHistorySize history slots of this material (e.g. "damage",
/// "tensile_strength", "burn_fraction", "temperature"); empty for internal slots.
std::vector<std::string> historyNames(const MaterialParams &p);

/// \brief Specific internal energy an element of this material starts with [J/kg]: E0/rho0
/// for a high explosive (its detonation energy), 0 otherwise. The driver sets e = this at t = 0.
Real initialSpecificEnergy(const MaterialParams &p);

} // namespace scpdyn
