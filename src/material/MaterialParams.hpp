#pragma once
/// \file MaterialParams.hpp
/// \brief POD material parameters used inside kernels. Models are chosen by enum + switch
/// (no virtual calls on the device); a new model adds an enum value, a parameter block in
/// `model_params` (index constants in its own header), a case in updateMaterial() and its
/// keys in MaterialLibrary.cpp.
#include "core/Types.hpp"

namespace scpdyn
{

enum class MaterialModel : int
{
  Elastic = 0,        ///< isotropic hypoelastic (Hughes-Winget objective update)
  ElasticPlastic = 1, ///< J2 plasticity, linear isotropic hardening, radial return
  JohnsonCook = 2,    ///< J2 plasticity, Johnson-Cook (1983) flow stress (JohnsonCook.hpp)
  Geomaterial = 3,    ///< pressure-dependent strength, crush curve, damage (Geomaterial.hpp)
  HighExplosive = 4   ///< JWL products with programmed burn, no strength (Jwl.hpp)
};

enum class EosModel : int
{
  Linear = 0,       ///< hypoelastic pressure: dp = -K tr(D) dt
  MieGruneisen = 1, ///< Us-up Hugoniot reference + Gruneisen (gamma0 + a mu) E
  Jwl = 2           ///< Jones-Wilkins-Lee detonation products (HighExplosive only)
};

/// \brief Element erosion limits of a material (docs/input.md `materials[].erosion`, docs/theory.md
/// 11.6); 0 = that limit is off. An element of the material erodes once one limit is passed
/// (material/Erosion.hpp).
struct ErosionLimits
{
  bool active = false;            ///< any limit set: the material erodes (also when inverted)
  Real plastic_strain = 0;        ///< equivalent plastic strain at erosion [-]
  Real damage = 0;                ///< geomaterial damage D at erosion [-]
  Real volumetric_strain_min = 0; ///< V / V0 - 1 below which the element erodes (< 0) [-]
  Real volumetric_strain_max = 0; ///< V / V0 - 1 above which the element erodes (> 0) [-]
  Real time_step = 0;             ///< stable time step below which the element erodes [s]
};

constexpr int kModelParams = 32; ///< model-specific parameter slots (Johnson-Cook, JWL, cap...)

struct MaterialParams
{
  MaterialModel model = MaterialModel::Elastic;
  EosModel eos = EosModel::Linear;
  Real density = 0;           ///< reference density rho0 [kg/m^3]
  Real bulk = 0;              ///< K [Pa]
  Real shear = 0;             ///< G [Pa]
  Real yield_stress = 0;      ///< initial yield stress [Pa] (ElasticPlastic)
  Real hardening_modulus = 0; ///< plastic modulus H = d sigma_y / d eps_p [Pa]
  Real mg_c0 = 0, mg_s = 0, mg_gamma0 = 0, mg_a = 0; ///< Mie-Gruneisen
  Real model_params[kModelParams] = {};              ///< layout owned by each later model's header
  ErosionLimits erosion;
};

/// \brief P-wave (uniaxial-strain) modulus K + 4G/3 [Pa]: rho c^2 of the elastic sound speed.
/// Every sound speed and time-step estimate of a model's elastic part takes it from here
/// (c^2 = pWaveModulus / rho).
KOKKOS_INLINE_FUNCTION Real pWaveModulus(Real bulk, Real shear) { return bulk + 4.0 / 3.0 * shear; }

/// \brief Floor of c^2 (1e-6 of the reference P-modulus over rho0) [m^2/s^2]: a tensile state
/// of the nonlinear EOS must not give c = 0 (the time step is h / c).
KOKKOS_INLINE_FUNCTION Real soundSpeedSquaredFloor(const MaterialParams &p)
{
  return 1e-6 * pWaveModulus(p.bulk, p.shear) / p.density;
}

/// \brief Everything a material needs about one element for one step.
struct MaterialStep
{
  Real D[6];    ///< rate of deformation (Voigt, tensor components) [1/s]
  Real dt;      ///< time step [s]
  Real rho_old; ///< density at the previous half step [kg/m^3]
  Real rho_new; ///< density now [kg/m^3]
  Real q;       ///< artificial bulk viscosity pressure of this step [Pa]
  Real time;    ///< time at the half step [s] (programmed burn)
  Real length;  ///< element characteristic length [m] (programmed burn width)
};

} // namespace scpdyn
