#pragma once
/// \file Lanes.hpp
/// \brief "SIMD over elements": the element functions are templated on a lane type R, either
/// Real (one element, what the unit tests and the other element types use) or LanePack (W
/// hex8 elements at once, one per vector lane). Every lane does the scalar arithmetic in the
/// scalar order, so a pack gives the bits of W scalar calls (IEEE +, -, *, / and sqrt are
/// correctly rounded in vector registers too; no FMA contraction without -march flags, and
/// SCPDYN_NATIVE adds -ffp-contract=off). The cube root is laneCbrt, vector arithmetic too.
///
/// The pack is a GCC/Clang vector type, host only: device builds (and other compilers) use
/// one lane, i.e. the scalar path. LaneOps<R> is the small interface the templates need.
#include "core/Types.hpp"

#include <cfloat>
#include <cstdint>
#include <cstring>

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

#ifdef SCPDYN_ELEMENT_LANES
// laneCbrt: the cube root of the element step, the same arithmetic on one double or a pack.
// Why not glibc's cbrt: it is a library call per lane (about 30 ns, ~8 % of the hex8 cycle:
// perf/README.md), and it is not correctly rounded (3 ulp off at worst, off by one or more ulp
// for half of all arguments: tests/element/test_lane_cbrt.cpp). This one is vector arithmetic
// only (~5 ns a value on AVX-512) and rounds correctly but for ~0.03 % of the arguments, which
// are 1 ulp off:
// - start: the exponent divided by three through the bit pattern read as an integer
//   (`bits/3 + 682·2^52` is 2^(e/3)·(1 + m/3) for x = 2^e (1 + m): within 6 %);
// - two Halley steps y ← y (y³ + 2x)/(2y³ + x) (cubic: 6 % → 1e-4 → 1e-12);
// - one Newton step y − (y³ − x)/(3y²) with the residual y³ − x formed almost exactly by
//   Dekker's splitting (exact products without FMA, so -ffp-contract=off keeps the bits).
// Arguments that are not positive normal numbers (0, negatives, subnormals, inf, NaN) take
// kmath::cbrt lane by lane.
namespace lane_cbrt
{

/// The start value's exponent offset, 682 = 1023 - 1023/3 (see the start step above).
constexpr std::int64_t kStartOffset = std::int64_t(682) << 52;

/// The start value of one double: its bit pattern read as an integer, divided by three (in
/// double arithmetic, as the pack's conversions do), plus the offset, read back as a double.
inline Real start(Real x)
{
  std::int64_t b;
  std::memcpy(&b, &x, sizeof b);
  const std::int64_t g = std::int64_t(Real(b) * (1.0 / 3.0)) + kStartOffset;
  Real y;
  std::memcpy(&y, &g, sizeof y);
  return y;
}

/// Dekker's exact product a·b = p + e (Veltkamp split at 27 bits), valid without FMA.
template <class R>
inline void twoProduct(const R &a, const R &b, R &p, R &e)
{
  const Real split = 134217729.0; // 2^27 + 1
  const R ca = split * a, ah = ca - (ca - a), al = a - ah;
  const R cb = split * b, bh = cb - (cb - b), bl = b - bh;
  p = a * b;
  e = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
}

/// The refinement from a start value within ~6 % (the same operations for any R).
template <class R>
inline R refine(const R &x, R y)
{
  for (int k = 0; k < 2; ++k)
  {
    const R y3 = y * y * y;
    y = y * ((y3 + 2 * x) / (2 * y3 + x)); // the ratio first: y·(y³ + 2x) under/overflows
  }
  R p2, e2, p3, e3;
  twoProduct(y, y, p2, e2);
  twoProduct(y, p2, p3, e3);
  const R residual = ((p3 - x) + e3) + y * e2; // y³ − x; p3 − x is exact (Sterbenz)
  return y - residual / (3 * p2);
}

inline bool positiveNormal(Real x) { return x >= DBL_MIN && x <= DBL_MAX; }

} // namespace lane_cbrt

/// \brief Cube root of a positive normal x, correctly rounded but for ~0.03 % of arguments
/// (1 ulp); other x as kmath::cbrt.
inline Real laneCbrt(Real x)
{
  if (!lane_cbrt::positiveNormal(x))
    return kmath::cbrt(x);
  return lane_cbrt::refine(x, lane_cbrt::start(x));
}

/// \brief The same, lane by lane bit-identical to laneCbrt(Real), in vector arithmetic.
inline LanePack laneCbrt(const LanePack &x)
{
  typedef std::int64_t LaneInt __attribute__((vector_size(sizeof(LanePack))));
  bool normal = true;
  for (int l = 0; l < kElementLanes; ++l)
    normal = normal && lane_cbrt::positiveNormal(x[l]);
  if (!normal)
  {
    LanePack r;
    for (int l = 0; l < kElementLanes; ++l)
      r[l] = laneCbrt(x[l]);
    return r;
  }
  LaneInt bits;
  std::memcpy(&bits, &x, sizeof bits);
  const LaneInt g =
      __builtin_convertvector(__builtin_convertvector(bits, LanePack) * (1.0 / 3.0), LaneInt) +
      lane_cbrt::kStartOffset;
  LanePack y;
  std::memcpy(&y, &g, sizeof y);
  return lane_cbrt::refine(x, y);
}

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
  KOKKOS_INLINE_FUNCTION static Real cbrt(Real a)
  {
#ifdef SCPDYN_ELEMENT_LANES
    return laneCbrt(a);
#else
    return kmath::cbrt(a);
#endif
  }
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
  static inline LanePack cbrt(const LanePack &a) { return laneCbrt(a); }
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
