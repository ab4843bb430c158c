#pragma once
// Helpers of the contact system tests: run a deck in-process into a work directory, read its
// CSV outputs, compare time histories.
#include "../TestUtil.hpp"
#include "contact/ContactSystem.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace scpdyn::test
{

inline std::string contactWorkDir(const std::string &name)
{
  const std::string dir = std::string(SCPDYN_TEST_WORKDIR) + "/contact/" + name;
  std::filesystem::create_directories(dir);
  return dir;
}

inline std::string readText(const std::string &path)
{
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Replace the first occurrence of `what` (which must exist) in `text`.
inline std::string replaced(std::string text, const std::string &what, const std::string &with)
{
  const auto at = text.find(what);
  EXPECT_NE(at, std::string::npos) << "deck text lacks: " << what;
  if (at != std::string::npos)
    text.replace(at, what.size(), with);
  return text;
}

/// Runs a deck given as YAML text in-process; returns the output directory.
inline std::string runDeck(const std::string &yaml, const std::string &name)
{
  const std::string dir = contactWorkDir(name);
  Solver s(deckFromText(yaml, name));
  s.run(dir);
  return dir;
}

/// A number for RecordProperty, in scientific notation.
inline std::string sci(double x)
{
  char b[32];
  std::snprintf(b, sizeof b, "%.4e", x);
  return b;
}

/// Value of a sampled history at time t (linear interpolation, constant beyond the ends).
inline double interpolate(const std::vector<double> &t, const std::vector<double> &q, double at)
{
  if (t.empty())
    return 0;
  if (at <= t.front())
    return q.front();
  if (at >= t.back())
    return q.back();
  const size_t k = size_t(std::upper_bound(t.begin(), t.end(), at) - t.begin());
  const double w = (at - t[k - 1]) / (t[k] - t[k - 1]);
  return (1 - w) * q[k - 1] + w * q[k];
}

/// Time-history norm of verification.md 0.3 over [t0, t1]: sqrt(int (a - r)^2 / int r^2), both
/// histories interpolated on a fine uniform grid.
inline double historyE2(const std::vector<double> &ta, const std::vector<double> &qa,
                        const std::vector<double> &tr, const std::vector<double> &qr, double t0,
                        double t1)
{
  const int n = 4000;
  double num = 0, den = 0;
  for (int i = 0; i <= n; ++i)
  {
    const double t = t0 + (t1 - t0) * i / n;
    const double a = interpolate(ta, qa, t), r = interpolate(tr, qr, t);
    num += (a - r) * (a - r);
    den += r * r;
  }
  return den > 0 ? std::sqrt(num / den) : std::sqrt(num);
}

/// Mean square of the difference of two histories over [t0, t1] (per unit time).
inline double meanSquareDifference(const std::vector<double> &ta, const std::vector<double> &qa,
                                   const std::vector<double> &tr, const std::vector<double> &qr,
                                   double t0, double t1)
{
  const int n = 4000;
  double s = 0;
  for (int i = 0; i <= n; ++i)
  {
    const double t = t0 + (t1 - t0) * i / n;
    const double d = interpolate(ta, qa, t) - interpolate(tr, qr, t);
    s += d * d;
  }
  return s / (n + 1);
}

/// Mean of a history over [t0, t1] (samples inside the window).
inline double windowMean(const std::vector<double> &t, const std::vector<double> &q, double t0,
                         double t1)
{
  double s = 0;
  int n = 0;
  for (size_t k = 0; k < t.size(); ++k)
    if (t[k] >= t0 && t[k] <= t1)
      s += q[k], ++n;
  return n ? s / n : 0.0;
}

/// Total momentum and mass of the nodes (host copy).
inline void nodeMomentum(const Solver &s, double p[3], double *mass = nullptr)
{
  auto v = Kokkos::create_mirror_view_and_copy(HostSpace(), s.nodes().v);
  auto m = Kokkos::create_mirror_view_and_copy(HostSpace(), s.nodes().mass);
  p[0] = p[1] = p[2] = 0;
  double M = 0;
  for (Index n = 0; n < s.nodes().count; ++n)
  {
    for (int d = 0; d < 3; ++d)
      p[d] += m(n) * v(n, d);
    M += m(n);
  }
  if (mass)
    *mass = M;
}

} // namespace scpdyn::test
