#pragma once
/// \file Fields.hpp
/// \brief Plain structs of Views, one View per field, grouped by entity.
#include "core/Types.hpp"
#include "material/MaterialParams.hpp"

namespace scpdyn
{

/// \brief Nodal fields. Forces are split so external work can be booked: f_int collects
/// element (internal + hourglass) and later contact forces, f_ext body, node and face loads.
struct NodeFields
{
  VectorView x0;    ///< initial coordinates [m]
  VectorView x;     ///< coordinates at the start of the cycle, x^n [m]
  VectorView v;     ///< velocity v^n [m/s]
  VectorView f_int; ///< internal + hourglass (+ contact) forces [N]
  VectorView f_ext; ///< external forces [N]
  VectorView external_impulse; ///< last step's (f_ext + constraint reaction) dt [N s]
  RealView mass;    ///< lumped mass [kg] (per metre in plane strain, per radian axisymmetric)
  DeviceView<int * [3]> bc; ///< per component: index of the velocity BC value, or -1
  Index count = 0;
};

/// \brief Element fields (every element type; connectivity padded with -1).
struct ElementFields
{
  ConnView conn;        ///< element x kMaxElementNodes
  IndexView part;
  IndexView material;
  RealView mass;        ///< constant element mass [kg]
  RealView volume;      ///< current volume (per metre / per radian in 2D) [m^3]
  SymTensorView stress; ///< Cauchy stress without viscosity [Pa]
  RealView energy;      ///< specific internal energy [J/kg]
  RealView plastic_strain;
  RealView q;           ///< artificial viscosity pressure [Pa]
  RealView sound_speed; ///< last sound speed [m/s]
  RealView hourglass_energy; ///< accumulated hourglass work [J]
  DeviceView<Real * [kHistorySize]> history;
  DeviceView<Real * [kHourglassSize]> hourglass; ///< stiffness-form resistances
  Index count = 0;
};

/// \brief A contiguous range of elements of one type: kernels are launched per group, so
/// every launch is a template on the element type.
struct ElementGroup
{
  ElementType type;
  Index begin, end;
};

/// \brief Deterministic assembly: for every node, the element corners (e * 8 + k) that touch
/// it, in ascending order (compressed rows).
struct NodeCorners
{
  IndexView offsets; ///< nodes + 1
  IndexView corners;
  DeviceView<Real * [kMaxElementNodes][3]> corner_force; ///< per element corner [N]
};

} // namespace scpdyn
