#pragma once
/// \file Lanes.hpp
/// \brief "SIMD over elements": the element functions are templated on a lane type R, either
/// Real (one element, what the unit tests and the other element types use) or LanePack (W
/// hex8 elements at once, one per vector lane). Every lane does the scalar arithmetic in the
/// scalar order, so a pack gives the bits of W scalar calls (IEEE +, -, *, / and sqrt are
/// correctly rounded in vector registers too) where both are compiled alike: SCPDYN_NATIVE
/// keeps -ffp-contract=off everywhere but in the files that instantiate the element kernels
/// (ElementLaunch.hpp), whose hexes all run as packs (chunks start on pack boundaries), so
/// their bits do not depend on the thread count either.
/// The cube root is laneCbrt, vector arithmetic too.
///
/// The pack is a GCC/Clang vector type, host only: device builds (and other compilers) use
/// one lane, i.e. the scalar path. LaneOps<R> is the small interface the templates need.
#include "core/Types.hpp"

#include <cfloat>
#include <cstdint>
#include <cstring>
#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace scpdyn
{

#if defined(__GNUC__) && !defined(KOKKOS_ENABLE_CUDA) && !defined(KOKKOS_ENABLE_HIP) &&            \
    !defined(KOKKOS_ENABLE_SYCL) && !defined(KOKKOS_ENABLE_OPENMPTARGET)
#if defined(__AVX512F__)
constexpr int kElementLanes =
    8; ///< AVX-512 (SCPDYN_NATIVE): 8 hexes a pack (the cycle 12 % faster than packs of 4: perf/results/log.md)
#elif defined(__AVX__)
constexpr int kElementLanes = 4; ///< AVX2: 4 hexes a pack
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
// perf/results/log.md), and it is not correctly rounded (3 ulp off at worst, off by one or more ulp
// for half of all arguments: tests/element/test_lane_cbrt.cpp). This one is vector arithmetic
// only (~5 ns a value on AVX-512) and rounds correctly but for ~0.03 % of the arguments, which
// are 1 ulp off:
// - start: the exponent divided by three through the bit pattern read as an integer
//   (`bits/3 + 682·2^52` is 2^(e/3)·(1 + m/3) for x = 2^e (1 + m): within 6 %);
// - two Halley steps y ← y (y³ + 2x)/(2y³ + x) (cubic: 6 % → 1e-4 → 1e-12);
// - one Newton step y − (y³ − x)/(3y²) with the residual y³ − x formed almost exactly by
//   Dekker's splitting (exact products without FMA: the accuracy figures above are for code
//   compiled so, as in the tests; in the element step, compiled with FMA contraction, the
//   last rounding may differ).
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

/// \brief Lane `lane` of a pack; a Real is its own only lane.
KOKKOS_INLINE_FUNCTION Real laneValue(const Real &r, int) { return r; }
#ifdef SCPDYN_ELEMENT_LANES
inline Real laneValue(const LanePack &r, int lane) { return r[lane]; }
#endif

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
  /// vsqrtpd: correctly rounded, so the bits of sqrt lane by lane. A loop of kmath::sqrt
  /// becomes one scalar vsqrtsd a lane, each behind its errno check.
  static inline LanePack sqrt(const LanePack &a)
  {
#if defined(__AVX512F__) // (the all-lanes mask: _mm512_sqrt_pd trips GCC 12's -Wuninitialized)
    return LanePack(_mm512_mask_sqrt_pd(__m512d(a), __mmask8(0xFF), __m512d(a)));
#elif defined(__AVX__)
    return LanePack(_mm256_sqrt_pd(__m256d(a)));
#elif defined(__SSE2__)
    return LanePack(_mm_sqrt_pd(__m128d(a)));
#else
    LanePack r;
    for (int l = 0; l < width; ++l)
      r[l] = kmath::sqrt(a[l]);
    return r;
#endif
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

/// \brief The 3-vectors p[3 n[l] .. 3 n[l] + 2] of the lanes l (a nodal x or v, LayoutRight) as
/// three packs, one per component.
inline void loadTriples(const Real *p, const Index n[kElementLanes], LanePack out[3])
{
#if defined(__AVX512F__) && defined(__AVX512VL__)
  static_assert(kElementLanes == 8, "the AVX-512 transpose is for packs of 8");
  // One masked 256-bit load a lane (the mask keeps it inside the array), then an 8 x 3
  // transpose in registers. What GCC makes of lane inserts here is 48 vgatherqpd a pack,
  // about 14 cycles each on the AVX-512 host of perf/results/log.md.
  typedef Real Quad __attribute__((vector_size(4 * sizeof(Real))));
  Quad t[8];
  for (int l = 0; l < 8; ++l)
    t[l] = Quad(_mm256_maskz_loadu_pd(0x7, p + 3 * std::size_t(n[l])));
  const LanePack t01 = __builtin_shufflevector(t[0], t[1], 0, 1, 2, 3, 4, 5, 6, 7);
  const LanePack t23 = __builtin_shufflevector(t[2], t[3], 0, 1, 2, 3, 4, 5, 6, 7);
  const LanePack t45 = __builtin_shufflevector(t[4], t[5], 0, 1, 2, 3, 4, 5, 6, 7);
  const LanePack t67 = __builtin_shufflevector(t[6], t[7], 0, 1, 2, 3, 4, 5, 6, 7);
  // x0 x2 z0 z2 x1 x3 z1 z3 and y0 y2 0 0 y1 y3 0 0, then the same for lanes 4-7
  const LanePack xz03 = __builtin_shufflevector(t01, t23, 0, 8, 2, 10, 4, 12, 6, 14);
  const LanePack y03 = __builtin_shufflevector(t01, t23, 1, 9, 3, 11, 5, 13, 7, 15);
  const LanePack xz47 = __builtin_shufflevector(t45, t67, 0, 8, 2, 10, 4, 12, 6, 14);
  const LanePack y47 = __builtin_shufflevector(t45, t67, 1, 9, 3, 11, 5, 13, 7, 15);
  out[0] = __builtin_shufflevector(xz03, xz47, 0, 4, 1, 5, 8, 12, 9, 13);
  out[1] = __builtin_shufflevector(y03, y47, 0, 4, 1, 5, 8, 12, 9, 13);
  out[2] = __builtin_shufflevector(xz03, xz47, 2, 6, 3, 7, 10, 14, 11, 15);
#else
  for (int l = 0; l < kElementLanes; ++l)
    for (int i = 0; i < 3; ++i)
      out[i][l] = p[3 * std::size_t(n[l]) + std::size_t(i)];
#endif
}

/// \brief Adds the N nodal 3-vectors f[a] of every lane l to p[3 n[a][l] ..], lane after lane
/// and node after node: the order of the scalar element loop, so a node two lanes share sums
/// its contributions in element order (what the corner gather does too).
template <int N>
inline void addTriples(Real *p, const Index n[N][kElementLanes], const LanePack f[N][3])
{
#if defined(__AVX512F__) && defined(__AVX512VL__)
  // (x, y) as one 128-bit add and z as a scalar, from a transposed copy: each store has the
  // size and address of a later lane's load of the same node, so it forwards
  typedef Real Pair __attribute__((vector_size(2 * sizeof(Real))));
  alignas(64) Real xy[N][2][8], z[N][8];
  for (int a = 0; a < N; ++a)
  {
    const LanePack even = __builtin_shufflevector(f[a][0], f[a][1], 0, 8, 2, 10, 4, 12, 6, 14);
    const LanePack odd = __builtin_shufflevector(f[a][0], f[a][1], 1, 9, 3, 11, 5, 13, 7, 15);
    storePack(xy[a][0], even); // x0 y0 x2 y2 x4 y4 x6 y6
    storePack(xy[a][1], odd);  // x1 y1 x3 y3 ...
    storePack(z[a], f[a][2]);
  }
  for (int l = 0; l < 8; ++l)
    for (int a = 0; a < N; ++a)
    {
      Real *q = p + 3 * std::size_t(n[a][l]);
      Pair sum, add;
      std::memcpy(&sum, q, sizeof sum);
      std::memcpy(&add, &xy[a][l & 1][2 * (l >> 1)], sizeof add);
      sum += add;
      std::memcpy(q, &sum, sizeof sum);
      q[2] += z[a][l];
    }
#else
  for (int l = 0; l < kElementLanes; ++l)
    for (int a = 0; a < N; ++a)
      for (int i = 0; i < 3; ++i)
        p[3 * std::size_t(n[a][l]) + std::size_t(i)] += f[a][i][l];
#endif
}

/// \brief Row packs: lane l's two corners of one mesh row are nodes base + l ("minus") and
/// base + l + 1 ("plus"), so the row's W + 1 nodes are 3 (W + 1) consecutive Reals from
/// p + 3 base (x or v, LayoutRight). Reads them once and gives both corners, component by
/// component: the bits of loadTriples() with n[l] = base + l and base + l + 1.
inline void loadRowTriples(const Real *p, Index base, LanePack minus[3], LanePack plus[3])
{
  const Real *q = p + 3 * std::size_t(base);
#if defined(__AVX512F__) && defined(__AVX512VL__)
  static_assert(kElementLanes == 8, "the AVX-512 row transpose is for packs of 8");
  // nodes 0-7 as r0 r1 r2 (x0 y0 z0 x1 ...), node 8 in r3's first three slots
  const LanePack r0 = loadPack(q), r1 = loadPack(q + 8), r2 = loadPack(q + 16);
  const LanePack r3 = LanePack(_mm512_maskz_loadu_pd(0x7, q + 24));
  const LanePack x05 = __builtin_shufflevector(r0, r1, 0, 3, 6, 9, 12, 15, 0, 0);
  const LanePack y04 = __builtin_shufflevector(r0, r1, 1, 4, 7, 10, 13, 0, 0, 0);
  const LanePack z04 = __builtin_shufflevector(r0, r1, 2, 5, 8, 11, 14, 0, 0, 0);
  minus[0] = __builtin_shufflevector(x05, r2, 0, 1, 2, 3, 4, 5, 10, 13);
  minus[1] = __builtin_shufflevector(y04, r2, 0, 1, 2, 3, 4, 8, 11, 14);
  minus[2] = __builtin_shufflevector(z04, r2, 0, 1, 2, 3, 4, 9, 12, 15);
  plus[0] = __builtin_shufflevector(minus[0], r3, 1, 2, 3, 4, 5, 6, 7, 8);
  plus[1] = __builtin_shufflevector(minus[1], r3, 1, 2, 3, 4, 5, 6, 7, 9);
  plus[2] = __builtin_shufflevector(minus[2], r3, 1, 2, 3, 4, 5, 6, 7, 10);
#else
  for (int l = 0; l < kElementLanes; ++l)
    for (int i = 0; i < 3; ++i)
    {
      minus[i][l] = q[3 * l + i];
      plus[i][l] = q[3 * l + 3 + i];
    }
#endif
}

/// \brief Adds the forces of a row pack's two corners (loadRowTriples()) to p: node base + j
/// gets lane j - 1's plus corner, then lane j's minus corner. That is element order, so the
/// bits of addTriples() with n[l] = base + l and base + l + 1; one read and one write of the
/// row instead of 2 W.
inline void addRowTriples(Real *p, Index base, const LanePack minus[3], const LanePack plus[3])
{
  Real *q = p + 3 * std::size_t(base);
#if defined(__AVX512F__) && defined(__AVX512VL__)
  const LanePack &X = minus[0], &Y = minus[1], &Z = minus[2];
  const LanePack &U = plus[0], &V = plus[1], &W = plus[2];
  // the minus corners interleaved: x0 y0 z0 x1 y1 z1 x2 y2 | z2 x3 ... x5 | y5 z5 ... z7
  const LanePack m0 = __builtin_shufflevector(
      __builtin_shufflevector(X, Y, 0, 8, 0, 1, 9, 0, 2, 10), Z, 0, 1, 8, 3, 4, 9, 6, 7);
  const LanePack m1 = __builtin_shufflevector(
      __builtin_shufflevector(X, Y, 0, 3, 11, 0, 4, 12, 0, 5), Z, 10, 1, 2, 11, 4, 5, 12, 7);
  const LanePack m2 = __builtin_shufflevector(
      __builtin_shufflevector(X, Y, 13, 0, 6, 14, 0, 7, 15, 0), Z, 0, 13, 2, 3, 14, 5, 6, 15);
  // the plus corners one node on: - - - u0 v0 w0 u1 v1 | w1 u2 ... u4 | v4 w4 ... w6 | u7 v7 w7
  const LanePack p0 = __builtin_shufflevector(__builtin_shufflevector(U, V, 0, 0, 0, 0, 8, 0, 1, 9),
                                              W, 0, 1, 2, 3, 4, 8, 6, 7);
  const LanePack p1 = __builtin_shufflevector(
      __builtin_shufflevector(U, V, 0, 2, 10, 0, 3, 11, 0, 4), W, 9, 1, 2, 10, 4, 5, 11, 7);
  const LanePack p2 = __builtin_shufflevector(
      __builtin_shufflevector(U, V, 12, 0, 5, 13, 0, 6, 14, 0), W, 0, 12, 2, 3, 13, 5, 6, 14);
  const LanePack p3 = __builtin_shufflevector(
      __builtin_shufflevector(U, V, 7, 15, 0, 0, 0, 0, 0, 0), W, 0, 1, 15, 3, 4, 5, 6, 7);
  // node 0 has no plus term: a masked add, so its sum is f + minus as in addTriples
  __m512d s0 = _mm512_mask_add_pd(_mm512_loadu_pd(q), 0xF8, _mm512_loadu_pd(q), __m512d(p0));
  __m512d s1 = _mm512_add_pd(_mm512_loadu_pd(q + 8), __m512d(p1));
  __m512d s2 = _mm512_add_pd(_mm512_loadu_pd(q + 16), __m512d(p2));
  const __m512d s3 = _mm512_add_pd(_mm512_maskz_loadu_pd(0x7, q + 24), __m512d(p3));
  s0 = _mm512_add_pd(s0, __m512d(m0));
  s1 = _mm512_add_pd(s1, __m512d(m1));
  s2 = _mm512_add_pd(s2, __m512d(m2));
  _mm512_storeu_pd(q, s0);
  _mm512_storeu_pd(q + 8, s1);
  _mm512_storeu_pd(q + 16, s2);
  _mm512_mask_storeu_pd(q + 24, 0x7, s3);
#else
  for (int l = 0; l < kElementLanes; ++l)
    for (int i = 0; i < 3; ++i)
    {
      q[3 * l + i] += minus[i][l];
      q[3 * l + 3 + i] += plus[i][l];
    }
#endif
}
#endif

} // namespace scpdyn
