#pragma once
/// \file Types.hpp
/// \brief The one place that names Kokkos spaces, scalar types and View aliases.
///
/// Every nodal vector field has 3 components whatever the problem dimension (unused ones stay
/// zero); symmetric tensors are stored in Voigt order xx, yy, zz, xy, yz, zx. In 2D
/// axisymmetric problems x is the radius r, y the axis z, and the zz slot is the hoop (theta)
/// component.
#include <Kokkos_Core.hpp>

namespace scpdyn
{
/// Kokkos math functions (sqrt, cbrt, abs, ...) usable in kernels: Kokkos::Experimental in
/// Kokkos 3.x, Kokkos in 4.x.
#if KOKKOS_VERSION >= 30700
namespace kmath = ::Kokkos;
#else
namespace kmath = ::Kokkos::Experimental;
#endif

using Real = double;
using Index = int; ///< local index of a node, element, face or common plane

using ExecSpace = Kokkos::DefaultExecutionSpace;
using MemSpace = ExecSpace::memory_space;
using HostSpace = Kokkos::HostSpace;
using Layout = Kokkos::LayoutRight;

template <class T>
using DeviceView = Kokkos::View<T, Layout, MemSpace>;

using RealView = DeviceView<Real *>;
using IndexView = DeviceView<Index *>;
using VectorView = DeviceView<Real *[3]>; ///< one 3-vector per node/face/CP
using ConnView = DeviceView<Index **>;    ///< connectivity: entity x local node
using AtomicVectorView =
    Kokkos::View<Real *[3], Layout, MemSpace, Kokkos::MemoryTraits<Kokkos::Atomic>>;

constexpr int kMaxElementNodes = 8; ///< hex8
constexpr int kMaxFaceNodes = 4;    ///< quad face of a hex
constexpr int kHistorySize = 8;     ///< per-element material history slots
constexpr int kHourglassSize = 12;  ///< per-element hourglass resistances (4 modes x 3)

/// Element state with several components per element is component-major (LayoutLeft):
/// component k of consecutive elements is contiguous, so a pack of hexes reads and writes it
/// with one vector load and store (and a GPU warp coalesces it).
template <class T>
using ElementComponentView = Kokkos::View<T, Kokkos::LayoutLeft, MemSpace>;
using SymTensorView = ElementComponentView<Real *[6]>; ///< Voigt xx yy zz xy yz zx
using HistoryView = ElementComponentView<Real *[kHistorySize]>;
using HourglassView = ElementComponentView<Real *[kHourglassSize]>;

/// \brief Element types; the problem dimension follows from the type.
enum class ElementType : int
{
  Line2 = 0, ///< 1D two-node line in uniaxial strain (cross-section 1 m^2)
  Quad4 = 1, ///< 2D bilinear quad, plane strain (per metre) or axisymmetric (per radian)
  Hex8 = 2,  ///< 3D trilinear hex
  Tet4 = 3   ///< 3D linear tet
};

/// \brief Two-dimensional geometry option (ignored in 1D and 3D).
enum class Geometry2D : int
{
  PlaneStrain = 0,
  Axisymmetric = 1
};

KOKKOS_INLINE_FUNCTION constexpr int nodesPerElement(ElementType t)
{
  return t == ElementType::Line2 ? 2 : t == ElementType::Quad4 ? 4 : t == ElementType::Hex8 ? 8 : 4;
}
KOKKOS_INLINE_FUNCTION constexpr int dimensionOf(ElementType t)
{
  return t == ElementType::Line2 ? 1 : t == ElementType::Quad4 ? 2 : 3;
}
/// \brief Nodes on one external face of an element of this type (point, segment, quad, tri).
KOKKOS_INLINE_FUNCTION constexpr int nodesPerFace(ElementType t)
{
  return t == ElementType::Line2 ? 1 : t == ElementType::Quad4 ? 2 : t == ElementType::Hex8 ? 4 : 3;
}

} // namespace scpdyn
