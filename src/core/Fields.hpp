#pragma once
/// \file Fields.hpp
/// \brief Plain structs of Views, one View per field, grouped by entity.
#include "core/Types.hpp"

namespace scpdyn
{

/// \brief Nodal fields. Forces are split so external work can be booked: f_int collects
/// element (internal + hourglass) forces, f_contact the contact forces, f_ext body, node and
/// face loads. Step 12 integrates their sum.
struct NodeFields
{
  VectorView x0;               ///< initial coordinates [m]
  VectorView x;                ///< coordinates at the start of the cycle, x^n [m]
  VectorView v;                ///< velocity v^n [m/s]
  VectorView f_int;            ///< internal + hourglass forces [N]
  VectorView f_contact;        ///< contact forces of step 9 [N] (empty without contact surfaces)
  VectorView f_ext;            ///< external forces [N]
  VectorView external_impulse; ///< last step's (f_ext + constraint reaction) dt [N s]
  /// last step's velocity-constraint reaction per constrained component, m (v^{n+1} - v^n) / dt
  /// - F [N] (written by step 12; empty without velocity BCs)
  VectorView reaction;
  /// last step's settling damping impulse per component [N s] (docs/theory.md 2.4; empty
  /// without a settling stage)
  VectorView damping_impulse;
  RealView mass; ///< lumped mass [kg] (per metre in plane strain, per radian axisymmetric)
  DeviceView<int *[3]> bc; ///< per component: index of the velocity BC value, or -1
  Index count = 0;
};

/// \brief ElementFields::eroded of an element that step 6 of this cycle eroded.
constexpr std::uint8_t kErodingNow = 2;

/// \brief Element fields (every element type; connectivity padded with -1).
struct ElementFields
{
  ConnView conn; ///< element x kMaxElementNodes
  IndexView part;
  IndexView material;
  RealView mass;        ///< constant element mass [kg]
  RealView volume;      ///< current volume (per metre / per radian in 2D) [m^3]
  SymTensorView stress; ///< Cauchy stress without viscosity [Pa]
  RealView energy;      ///< specific internal energy [J/kg]
  RealView plastic_strain;
  RealView q;                ///< artificial viscosity pressure [Pa]
  RealView sound_speed;      ///< last sound speed [m/s]
  RealView hourglass_energy; ///< accumulated hourglass work [J]
  HistoryView history;
  HourglassView hourglass; ///< stiffness-form resistances
  /// 1 if the element is eroded (docs/theory.md 11.6): it contributes no force, stress update
  /// or time-step limit; kErodingNow (2) while step 6 erodes it (ErosionStep books it)
  DeviceView<std::uint8_t *> eroded;
  /// 1 at e if the hexes e .. e + kElementLanes - 1 are a row pack (markRowPacks()), else 0
  DeviceView<std::uint8_t *> row_pack;
  Index count = 0;
};

/// \brief A contiguous range of elements of one type: kernels are launched per group, so
/// every launch is a template on the element type.
struct ElementGroup
{
  ElementType type;
  Index begin, end;
};

/// \brief Deterministic assembly with threads (numerics.scatter gather). Step 6 runs every
/// element group as `chunks` contiguous chunks, one thread each (chunkBegin()); a node whose
/// elements all lie in one chunk gets plain adds in element order, the same sums as one thread.
/// A node that two chunks touch is "shared": its element corners store their forces, and
/// gatherCornerForces() sums them in ascending corner order, again the one-thread order.
struct NodeCorners
{
  int chunks = 1;
  IndexView shared_nodes; ///< the shared nodes
  IndexView offsets;      ///< shared nodes + 1: their corners' slots, in ascending order
  IndexView corners;
  DeviceView<std::uint8_t *> shared_corners; ///< per element: bit a set if node a is shared
  IndexView corner_base;   ///< per element: the slot of its first shared corner (the rest follow)
  VectorView corner_force; ///< per shared corner (slot) [N]
};

} // namespace scpdyn
