#pragma once
/// \file RealText.hpp
/// \brief Numbers in messages: the shortest decimal text that reads back to exactly the value
/// (7850, 0.25, 2e+11, 1e-06), never std::to_string's fixed six decimals ("0.000000").
#include "core/Types.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace scpdyn
{

inline std::string formatReal(Real x)
{
  if (x == 0 || !std::isfinite(x))
    return x == 0 ? (std::signbit(x) ? "-0" : "0")
                  : (std::isnan(x) ? "nan"
                     : x > 0       ? "inf"
                                   : "-inf");
  char buf[48];
  int digits = 1;
  for (; digits < 17; ++digits)
  {
    std::snprintf(buf, sizeof(buf), "%.*e", digits - 1, x);
    if (std::strtod(buf, nullptr) == x)
      break;
  }
  std::snprintf(buf, sizeof(buf), "%.*e", digits - 1, x);
  const int exponent = std::atoi(std::strchr(buf, 'e') + 1);
  // plain decimals for everyday magnitudes (7850, 0.25), exponent form beyond (2e+11, 1e-06)
  if (exponent >= -4 && exponent < 6)
    std::snprintf(buf, sizeof(buf), "%.*f", std::max(digits - 1 - exponent, 0), x);
  return buf;
}

} // namespace scpdyn
