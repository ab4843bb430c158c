#pragma once
/// \file SameBits.hpp
/// \brief Bitwise equality of doubles, for the tests that assert "the same bits": unlike ==,
/// 0.0 and -0.0 differ and a NaN equals its own copy.
#include <cstring>

namespace scpdyn
{

inline bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

/// The n doubles from a and from b.
inline bool sameBits(const double *a, const double *b, int n)
{
  return std::memcmp(a, b, size_t(n) * sizeof(double)) == 0;
}

} // namespace scpdyn
