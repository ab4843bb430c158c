#pragma once
/// \file Lanes.hpp
/// \brief "SIMD over elements": the element functions are templated on a lane type R, either
/// Real (one element, what the unit tests and the other element types use) or LanePack (W
/// hex8 elements at once, one per vector lane). Every lane does the scalar arithmetic in the
/// scalar order, so a pack gives the bits of W scalar calls (IEEE +, -, *, / and sqrt are
/// correctly rounded in vector registers too; no FMA contraction without -march flags, and
/// SCPDYN_NATIVE adds -ffp-contract=off). cbrt has no bit-identical vector form: one call a lane.
///
/// The pack is a GCC/Clang vector type, host only: device builds (and other compilers) use
/// one lane, i.e. the scalar path. LaneOps<R> is the small interface the templates need.
#include "core/Types.hpp"

namespace scpdyn
{

#if defined(__GNUC__) && !defined(KOKKOS_ENABLE_CUDA) && !defined(KOKKOS_ENABLE_HIP) &&          \
    !defined(KOKKOS_ENABLE_SYCL) && !defined(KOKKOS_ENABLE_OPENMPTARGET)
#if defined(__AVX__)
constexpr int kElementLanes = 4; ///< AVX/AVX-512 (SCPDYN_NATIVE): 4 hexes a pack (8 spill)
#else
constexpr int kElementLanes = 2; ///< x86-64 baseline: SSE2, 2 doubles a register
#endif
#define SCPDYN_ELEMENT_LANES 1
/// kElementLanes doubles, one element each
typedef Real LanePack __attribute__((vector_size(sizeof(Real) * kElementLanes)));
#else
constexpr int kElementLanes = 1;
#endif

/// R with template argument deduction switched off (scalar arguments of the R functions may
/// then be literals of another type, as the unit tests pass them).
template <class R>
struct LaneIdentity
{
  using type = R;
};
template <class R>
using LaneArg = typename LaneIdentity<R>::type;

template <class R>
struct LaneOps;

template <>
struct LaneOps<Real>
{
  static constexpr int width = 1;
  KOKKOS_INLINE_FUNCTION static Real broadcast(Real a) { return a; }
  KOKKOS_INLINE_FUNCTION static Real max(Real a, Real b) { return a > b ? a : b; }
  KOKKOS_INLINE_FUNCTION static Real sqrt(Real a) { return kmath::sqrt(a); }
  KOKKOS_INLINE_FUNCTION static Real cbrt(Real a) { return kmath::cbrt(a); }
};

#ifdef SCPDYN_ELEMENT_LANES
template <>
struct LaneOps<LanePack>
{
  static constexpr int width = kElementLanes;
  static inline LanePack broadcast(Real a)
  {
    LanePack r;
    for (int l = 0; l < width; ++l)
      r[l] = a;
    return r;
  }
  /// a > b ? a : b in every lane (NaN: b, as the scalar form)
  static inline LanePack max(const LanePack &a, const LanePack &b) { return a > b ? a : b; }
  static inline LanePack sqrt(const LanePack &a) // sqrtpd: correctly rounded, as sqrtsd
  {
    LanePack r;
    for (int l = 0; l < width; ++l)
      r[l] = kmath::sqrt(a[l]);
    return r;
  }
  static inline LanePack cbrt(const LanePack &a)
  {
    LanePack r;
    for (int l = 0; l < width; ++l)
      r[l] = kmath::cbrt(a[l]);
    return r;
  }
};

/// \brief kElementLanes consecutive Reals from p (no alignment needed): one vector load.
inline LanePack loadPack(const Real *p)
{
  LanePack r;
  __builtin_memcpy(&r, p, sizeof r);
  return r;
}

/// \brief a to kElementLanes consecutive Reals at p (no alignment needed): one vector store.
inline void storePack(Real *p, const LanePack &a) { __builtin_memcpy(p, &a, sizeof a); }
#endif

} // namespace scpdyn
