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
#include <limits>
#include <map>
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

/// Replace the first occurrence of `what` (which must exist) in `text`.
inline std::string replaced(std::string text, const std::string &what, const std::string &with)
{
  const auto at = text.find(what);
  EXPECT_NE(at, std::string::npos) << "deck text lacks: " << what;
  if (at != std::string::npos)
    text.replace(at, what.size(), with);
  return text;
}

/// The incline of the friction tests: a soft 0.2 x 0.1 m block (4 x 2 quads, c = 100 m/s) on a
/// fixed 0.8 x 0.1 m base, gravity tilted by theta so the interface is the incline, the block
/// thrown along it at v0; the contact surfaces are `surfaces` (YAML list items), 0.12 s.
inline std::string inclineDeck(double theta_deg, const std::string &surfaces, double v0 = 0)
{
  const double th = theta_deg * M_PI / 180, g = 9.81;
  std::string deck = R"(dimension: 2
geometry: plane_strain
time: {end: 0.12, courant: 0.5}
gravity: [GX, GY]
materials:
  - {name: soft, model: elastic, density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.25}
parts:
  - {name: base, material: soft, mesh: {elements: [8, 2], origin: [0.0, 0.0], size: [0.8, 0.1]}}
  - name: block
    material: soft
    mesh: {elements: [4, 2], origin: [0.2, 0.1], size: [0.2, 0.1]}
    initial_velocity: [V0, 0.0]
node_sets:
  - {name: base_all, part: base}
boundary_conditions:
  - {type: velocity, node_set: base_all, component: x, value: 0.0}
  - {type: velocity, node_set: base_all, component: y, value: 0.0}
contact:
  search_interval: 1
  surfaces:
SURFACES)";
  deck = replaced(deck, "GX", std::to_string(g * std::sin(th)));
  deck = replaced(deck, "GY", std::to_string(-g * std::cos(th)));
  deck = replaced(deck, "V0", std::to_string(v0));
  return replaced(deck, "SURFACES", surfaces);
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

/// node ids of `b` matched to `a` by initial position (x, y to 0.1 um; y = 0 in 1D)
inline std::vector<Index> matchNodes(const Solver &a, const Solver &b)
{
  auto xa = Kokkos::create_mirror_view_and_copy(HostSpace(), a.nodes().x0);
  auto xb = Kokkos::create_mirror_view_and_copy(HostSpace(), b.nodes().x0);
  std::map<std::pair<long, long>, Index> at;
  for (Index n = 0; n < a.nodes().count; ++n)
    at[{std::lround(xa(n, 0) * 1e7), std::lround(xa(n, 1) * 1e7)}] = n;
  std::vector<Index> m(size_t(b.nodes().count));
  for (Index n = 0; n < b.nodes().count; ++n)
    m[size_t(n)] = at.at({std::lround(xb(n, 0) * 1e7), std::lround(xb(n, 1) * 1e7)});
  return m;
}

/// A tied run against its merged one-mesh twin (T6a), x-velocities over the whole run.
struct TiedComparison
{
  double worst = 0;   ///< largest |v_tied - v_merged| of any node and cycle [m/s]
  double vmax = 0;    ///< largest |v_merged| [m/s]
  double tension = 0; ///< most tensile CP normal force seen (< 0: tension crossed the tie) [N]
  Index min_cps = std::numeric_limits<Index>::max(), max_cps = 0; ///< CPs alive, over cycles
};

/// Cycles both Solvers together to the merged deck's end time; their steps must be equal
/// (fatal failure otherwise: call it inside ASSERT_NO_FATAL_FAILURE).
inline void compareTiedToMerged(Solver &merged, Solver &tied, TiedComparison &c)
{
  const std::vector<Index> map = matchNodes(merged, tied);
  while (merged.time() < merged.deck().end_time)
  {
    merged.cycle();
    tied.cycle();
    ASSERT_EQ(merged.dt(), tied.dt());
    auto va = Kokkos::create_mirror_view_and_copy(HostSpace(), merged.nodes().v);
    auto vb = Kokkos::create_mirror_view_and_copy(HostSpace(), tied.nodes().v);
    for (Index n = 0; n < tied.nodes().count; ++n)
    {
      c.worst = std::max(c.worst, std::fabs(vb(n, 0) - va(map[size_t(n)], 0)));
      c.vmax = std::max(c.vmax, std::fabs(va(map[size_t(n)], 0)));
    }
    const Index cps = tied.contact()->count();
    c.min_cps = std::min(c.min_cps, cps), c.max_cps = std::max(c.max_cps, cps);
    auto state = Kokkos::create_mirror_view_and_copy(HostSpace(), tied.contact()->planes().state);
    for (Index p = 0; p < cps; ++p)
      c.tension = std::min(c.tension, state(p).Fn);
  }
}

} // namespace scpdyn::test
