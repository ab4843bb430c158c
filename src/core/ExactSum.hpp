#pragma once
/// \file ExactSum.hpp
/// \brief Sums whose bits do not depend on the order of their terms: a long accumulator
/// (Kulisch) over the whole double range, and its Kokkos reducer (docs/theory.md 10.8).
///
/// A finite double is m 2^(q - 1074) with an integer 0 <= m < 2^53 and 0 <= q <= 2045. The
/// accumulator holds the exact sum as base-2^32 digits in signed 64-bit limbs, limb i weighing
/// 2^(32 i - 1074); an add puts m's at most three digits (each below 2^32) into three limbs.
/// Integer addition is associative, so any order of the adds, any thread count and any rank
/// count (limbs summed by MPI as integers) give the same limbs, and value() rounds that one
/// exact sum. A limb overflows only after 2^31 adds into it; infinities and NaN are counted and
/// make the value NaN.
#include "core/Types.hpp"

#include <Kokkos_Core.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>

namespace scpdyn
{

/// \brief N exact sums at once (one reduction pass for several dot products).
template <int N>
struct ExactSums
{
  static constexpr int kLimbs = 66;         ///< ceil((2045 + 53) / 32)
  static constexpr int kWords = kLimbs + 1; ///< the limbs and the non-finite count
  std::int64_t word[N][kWords];

  KOKKOS_INLINE_FUNCTION void clear()
  {
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < kWords; ++i)
        word[j][i] = 0;
  }

  /// \brief Sum j += x, exactly.
  KOKKOS_INLINE_FUNCTION void add(int j, Real x)
  {
    std::uint64_t b;
    std::memcpy(&b, &x, sizeof b);
    const int q = int((b >> 52) & 0x7ff);
    std::uint64_t m = b & ((std::uint64_t(1) << 52) - 1);
    if (q == 0x7ff)
    {
      ++word[j][kLimbs];
      return;
    }
    int pos = 0; // subnormal: m 2^-1074
    if (q != 0)
    {
      m |= std::uint64_t(1) << 52;
      pos = q - 1;
    }
    if (m == 0)
      return;
    const std::int64_t sign = (b >> 63) ? -1 : 1;
    const int i = pos >> 5, s = pos & 31;
    const std::uint64_t mask = 0xffffffffu;
    // the digits of m 2^s: bits 0-31, 32-63 and 64-84
    const std::uint64_t lo = (m << s) & mask;
    const std::uint64_t mid = (m >> (32 - s)) & mask;
    const std::uint64_t hi = s == 0 ? 0 : m >> (64 - s);
    word[j][i] += sign * std::int64_t(lo);
    word[j][i + 1] += sign * std::int64_t(mid);
    if (hi != 0)
      word[j][i + 2] += sign * std::int64_t(hi);
  }

  KOKKOS_INLINE_FUNCTION void join(const ExactSums &o)
  {
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < kWords; ++i)
        word[j][i] += o.word[j][i];
  }

  /// \brief Sum j rounded to a double (host; a function of the exact sum alone).
  Real value(int j) const
  {
    if (word[j][kLimbs] != 0)
      return std::nan("");
    std::int64_t a[kLimbs];
    for (int i = 0; i < kLimbs; ++i)
      a[i] = word[j][i];
    // canonical digits 0 <= a_i < 2^32 and the carry out of the top limb: its sign is the sum's
    auto normalise = [&a]() {
      std::int64_t carry = 0;
      for (int i = 0; i < kLimbs; ++i)
      {
        const std::int64_t v = a[i] + carry;
        carry = v >> 32; // floor(v / 2^32)
        a[i] = v - carry * (std::int64_t(1) << 32);
      }
      return carry;
    };
    Real sign = 1;
    std::int64_t carry = normalise();
    if (carry < 0)
    {
      for (int i = 0; i < kLimbs; ++i)
        a[i] = -word[j][i];
      sign = -1;
      carry = normalise();
    }
    if (carry > 0)
      return sign * HUGE_VAL;
    int top = kLimbs - 1;
    while (top >= 0 && a[top] == 0)
      --top;
    if (top < 0)
      return 0.0;
    // the top 64 bits as one integer, the next digit after it: two roundings, always the same
    const std::uint64_t high =
        (std::uint64_t(a[top]) << 32) | std::uint64_t(top > 0 ? a[top - 1] : 0);
    Real r = std::ldexp(Real(high), 32 * (top - 1) - 1074);
    if (top > 1)
      r += std::ldexp(Real(a[top - 2]), 32 * (top - 2) - 1074);
    return sign * r;
  }
};

/// \brief Kokkos reducer of ExactSums<N>: `parallel_reduce(policy, f, ExactSumsReducer<N>(s))`
/// with f(i, ExactSums<N> &acc) calling acc.add(j, term).
template <int N>
struct ExactSumsReducer
{
  using reducer = ExactSumsReducer;
  using value_type = ExactSums<N>;
  using result_view_type = Kokkos::View<value_type, HostSpace, Kokkos::MemoryUnmanaged>;

  explicit ExactSumsReducer(value_type &v) : _value(&v) {}

  KOKKOS_INLINE_FUNCTION void join(value_type &dest, const value_type &src) const
  {
    dest.join(src);
  }
#if KOKKOS_VERSION < 40000
  KOKKOS_INLINE_FUNCTION void join(volatile value_type &dest, const volatile value_type &src) const
  {
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < value_type::kWords; ++i)
        dest.word[j][i] += src.word[j][i];
  }
#endif
  KOKKOS_INLINE_FUNCTION void init(value_type &v) const { v.clear(); }
  KOKKOS_INLINE_FUNCTION value_type &reference() const { return *_value.data(); }
  KOKKOS_INLINE_FUNCTION result_view_type view() const { return _value; }
  KOKKOS_INLINE_FUNCTION bool references_scalar() const { return true; }

private:
  result_view_type _value;
};

} // namespace scpdyn
