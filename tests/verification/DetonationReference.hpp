#pragma once
// Exact solutions of the JWL detonations (verification.md T8a, T8b) and a run recorder shared by
// the detonation tests: the model's CJ state (jwlChapmanJouguet) and CJ isentrope, the planar
// Taylor wave behind a detonation lit at a rigid wall, Taylor's (1950) similarity solution of the
// cylindrical detonation (as scripts/verification/detonation_reference.py computes them), element
// centroids and pressures, and a run to the deck's end with gauge arrival times.
#include "TestUtil.hpp"

#include "material/Jwl.hpp"

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace scpdyn
{
namespace detonation
{

/// The CJ state and the isentrope through it, p_s = A e^{-R1 V} + B e^{-R2 V} + C V^{-(1+w)}.
struct CjIsentrope
{
  Real rho0, A, B, R1, R2, w, C;
  JwlCjState cj;
  explicit CjIsentrope(const MaterialParams &p)
      : rho0(p.density), A(p.model_params[kJwlA]), B(p.model_params[kJwlB]),
        R1(p.model_params[kJwlR1]), R2(p.model_params[kJwlR2]), w(p.model_params[kJwlOmega])
  {
    cj = jwlChapmanJouguet(p.model_params, rho0);
    C = (cj.p - A * std::exp(-R1 * cj.V) - B * std::exp(-R2 * cj.V)) * std::pow(cj.V, 1 + w);
  }
  Real p(Real V) const
  {
    return A * std::exp(-R1 * V) + B * std::exp(-R2 * V) + C * std::pow(V, -(1 + w));
  }
  Real dp(Real V) const
  {
    return -R1 * A * std::exp(-R1 * V) - R2 * B * std::exp(-R2 * V) -
           (1 + w) * C * std::pow(V, -(2 + w));
  }
  Real c(Real V) const { return V * std::sqrt(-dp(V) / rho0); }
};

/// p(s) on a tabulated curve s_k (decreasing) -> p_k; p_inner inside s_min, p_cj ahead of 1.
struct Profile
{
  std::vector<Real> s, p;
  Real p_inner = 0, s_inner = 0;
  Real at(Real x) const
  {
    if (x <= s_inner)
      return p_inner;
    if (x >= s.front())
      return x > 1 ? 0 : p.front();
    if (x <= s.back())
      return p.back();
    // s decreases along the table: bisection for s[hi] <= x < s[lo]
    size_t lo = 0, hi = s.size() - 1;
    while (hi - lo > 1)
    {
      const size_t mid = (lo + hi) / 2;
      (s[mid] > x ? lo : hi) = mid;
    }
    return p[hi] + (x - s[hi]) / (s[lo] - s[hi]) * (p[lo] - p[hi]);
  }
};

/// Planar simple wave: u = u_CJ - int sqrt(-p_s'/rho0) dV, s = (u + c)/D, down to u = 0 (wall).
inline Profile planarWave(const CjIsentrope &h)
{
  Profile pr;
  const Real dV = 1e-5;
  Real V = h.cj.V, u = h.cj.u;
  while (u > 0)
  {
    pr.s.push_back((u + h.c(V)) / h.cj.D);
    pr.p.push_back(h.p(V));
    const Real f0 = std::sqrt(-h.dp(V) / h.rho0), f1 = std::sqrt(-h.dp(V + dV) / h.rho0);
    const Real u1 = u - 0.5 * dV * (f0 + f1);
    if (u1 <= 0) // wall state by linear interpolation of u = 0
    {
      const Real Vw = V + dV * u / (u - u1);
      pr.p_inner = h.p(Vw);
      pr.s_inner = h.c(Vw) / h.cj.D;
    }
    u = u1;
    V += dV;
  }
  return pr;
}

/// Taylor (1950) similarity solution, j = 1 cylinder: RK4 in the parameter tau from the CJ
/// point (xi = 1) until U = u/D -> 0, the quiet core xi < xi0 (verification.md T8b).
inline Profile similarityWave(const CjIsentrope &h, int j)
{
  Profile pr;
  Real y[3] = {1, h.cj.u / h.cj.D, h.cj.V};
  auto rhs = [&](const Real *q, Real *d) {
    const Real cs = h.c(q[2]) / h.cj.D;
    d[0] = q[0] * (cs * cs - (q[1] - q[0]) * (q[1] - q[0]));
    d[1] = -j * q[1] * cs * cs;
    d[2] = j * q[2] * q[1] * (q[0] - q[1]);
  };
  const Real dt = 1e-3;
  while (y[1] > 1e-12 * h.cj.u / h.cj.D)
  {
    pr.s.push_back(y[0]);
    pr.p.push_back(h.p(y[2]));
    Real k1[3], k2[3], k3[3], k4[3], t[3];
    rhs(y, k1);
    for (int i = 0; i < 3; ++i)
      t[i] = y[i] + 0.5 * dt * k1[i];
    rhs(t, k2);
    for (int i = 0; i < 3; ++i)
      t[i] = y[i] + 0.5 * dt * k2[i];
    rhs(t, k3);
    for (int i = 0; i < 3; ++i)
      t[i] = y[i] + dt * k3[i];
    rhs(t, k4);
    for (int i = 0; i < 3; ++i)
      y[i] += dt / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
  }
  pr.s_inner = y[0];
  pr.p_inner = h.p(y[2]);
  return pr;
}

/// Element centroids (current or initial) and pressures of the solver's state.
struct Cells
{
  std::vector<std::array<Real, 3>> c, c0;
  std::vector<Real> p;
};
inline Cells cells(const Solver &s)
{
  auto x = Kokkos::create_mirror_view_and_copy(HostSpace(), s.nodes().x);
  auto x0 = Kokkos::create_mirror_view_and_copy(HostSpace(), s.nodes().x0);
  auto conn = Kokkos::create_mirror_view_and_copy(HostSpace(), s.elements().conn);
  auto st = Kokkos::create_mirror_view_and_copy(HostSpace(), s.elements().stress);
  Cells r;
  for (Index e = 0; e < s.elements().count; ++e)
  {
    std::array<Real, 3> a{0, 0, 0}, a0{0, 0, 0};
    for (int k = 0; k < 4; ++k)
      for (int i = 0; i < 3; ++i)
      {
        a[size_t(i)] += x(conn(e, k), i) / 4;
        a0[size_t(i)] += x0(conn(e, k), i) / 4;
      }
    r.c.push_back(a);
    r.c0.push_back(a0);
    r.p.push_back(-(st(e, 0) + st(e, 1) + st(e, 2)) / 3);
  }
  return r;
}

/// Runs a deck to its end; records the gauge pressures each cycle, the arrival time (first
/// crossing of P_CJ/2, interpolated) per gauge and the largest |energy balance error|.
struct DetonationRun
{
  std::vector<Real> t;
  std::vector<std::vector<Real>> g;
  std::vector<Real> arrival;
  Real balance = 0, ie0 = 0;
  long cycles = 0;
};
inline DetonationRun runToEnd(Solver &s, Real pcj)
{
  DetonationRun r;
  r.ie0 = s.energies().internal;
  const size_t ng = s.gauges().size();
  r.g.resize(ng);
  r.arrival.assign(ng, -1);
  std::vector<Real> prev(ng, 0);
  Real t_prev = 0;
  while (s.time() < s.deck().end_time)
  {
    s.cycle();
    const std::vector<Real> v = s.gaugeValues();
    r.t.push_back(s.time());
    for (size_t k = 0; k < ng; ++k)
    {
      r.g[k].push_back(v[k]);
      if (r.arrival[k] < 0 && v[k] > 0.5 * pcj)
        r.arrival[k] = t_prev + (0.5 * pcj - prev[k]) / (v[k] - prev[k]) * (s.time() - t_prev);
      prev[k] = v[k];
    }
    t_prev = s.time();
    if (s.cycles() % 10 == 0)
      r.balance = std::max(r.balance, std::abs(s.energies().balance_error));
  }
  r.balance = std::max(r.balance, std::abs(s.energies().balance_error));
  r.cycles = s.cycles();
  return r;
}

/// Least-squares slope of r against t.
inline Real slope(const std::vector<Real> &t, const std::vector<Real> &r)
{
  Real mt = 0, mr = 0;
  for (size_t k = 0; k < t.size(); ++k)
  {
    mt += t[k] / t.size();
    mr += r[k] / r.size();
  }
  Real num = 0, den = 0;
  for (size_t k = 0; k < t.size(); ++k)
  {
    num += (t[k] - mt) * (r[k] - mr);
    den += (t[k] - mt) * (t[k] - mt);
  }
  return num / den;
}

inline Real gaugeRadius(const Cells &c, const Solver &s, size_t g)
{
  const auto &a = c.c0[size_t(s.gauges()[g].id)];
  return std::hypot(a[0], a[1]);
}

/// Mean pressure of the cells inside the quiet core, r < 0.4 D t (well inside xi0 = 0.49).
inline Real quietCorePressure(const Cells &c, Real D, Real t, int *count = nullptr)
{
  Real core = 0;
  int n = 0;
  for (size_t e = 0; e < c.p.size(); ++e)
    if (std::hypot(c.c[e][0], c.c[e][1]) / (D * t) < 0.4)
    {
      core += c.p[e];
      ++n;
    }
  if (count)
    *count = n;
  return core / n;
}

} // namespace detonation
} // namespace scpdyn
