// Prototype: the two costliest parts of the hex8 element step (hex8Gradients and the viscous
// hex8HourglassForces, ~45 % of its time) evaluated for W elements at once, one element per
// vector lane ("SIMD over elements"), against the library's one-element functions. Each lane
// does the scalar arithmetic in the scalar order, so the results are bit-for-bit those of the
// library (checked before timing). Built twice by perf/CMakeLists.txt: with the project's
// flags (x86-64 baseline, SSE2) and as bench_simd_lanes_native (-march=native
// -ffp-contract=off, no FMA contraction so the bits stay the same). Evidence for the design
// question in perf/README.md, not used by the solver.
#include "element/Hourglass.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <vector>

namespace
{
using scpdyn::Real;

/// W doubles, one element each: a GCC/Clang vector type, so the operators are the machine's
/// vector instructions (split into SSE2 halves on the x86-64 baseline) and values stay in
/// registers.
template <int W>
struct PackOf
{
  typedef Real type __attribute__((vector_size(sizeof(Real) * W)));
};
template <int W>
using Pack = typename PackOf<W>::type;

inline Real laneMax(Real a, Real b) { return a > b ? a : b; }
inline Real laneCbrt(Real a) { return std::cbrt(a); }
inline Real lit(Real a, Real) { return a; }
template <class P>
inline P laneMax(const P &a, const P &b)
{
  return a > b ? a : b;
}
template <class P>
inline P laneCbrt(const P &a) // no vector cbrt with the same bits: one call a lane
{
  P r = a;
  for (int l = 0; l < int(sizeof(P) / sizeof(Real)); ++l)
    r[l] = std::cbrt(a[l]);
  return r;
}
/// a literal as an R (broadcast to every lane)
template <class P>
inline P lit(Real a, const P &)
{
  return P{} + a;
}

// ---- the library's arithmetic, templated on the scalar type R ---------------------------

template <class R>
inline void cross3T(const R a[3], const R b[3], R c[3])
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

template <class R>
__attribute__((always_inline)) inline void faceTermT(const R x[8][3], const R c[3], int ia, int ib,
                                                     int ic, int id, R B[8][3], R &vol24, R &amax2)
{
  R S[3], P[3], Q[3], PxQ[3], QxS[3], SxP[3];
  for (int i = 0; i < 3; ++i)
  {
    S[i] = x[ia][i] + x[ib][i] + x[ic][i] + x[id][i] - 4 * c[i];
    P[i] = x[ic][i] - x[ia][i];
    Q[i] = x[id][i] - x[ib][i];
  }
  cross3T(P, Q, PxQ);
  cross3T(Q, S, QxS);
  cross3T(S, P, SxP);
  vol24 += S[0] * PxQ[0] + S[1] * PxQ[1] + S[2] * PxQ[2];
  for (int i = 0; i < 3; ++i)
  {
    B[ia][i] += PxQ[i] - QxS[i];
    B[ic][i] += PxQ[i] + QxS[i];
    B[ib][i] += PxQ[i] - SxP[i];
    B[id][i] += PxQ[i] + SxP[i];
  }
  const R a2 = 0.25 * (PxQ[0] * PxQ[0] + PxQ[1] * PxQ[1] + PxQ[2] * PxQ[2]);
  amax2 = laneMax(a2, amax2);
}

template <class R>
inline R hex8GradientsT(const R x[8][3], R B[8][3], R &max_face_area2)
{
  const R zero = lit(0.0, x[0][0]);
  R c[3] = {zero, zero, zero};
  for (int a = 0; a < 8; ++a)
    for (int i = 0; i < 3; ++i)
      c[i] += 0.125 * x[a][i];
  for (int a = 0; a < 8; ++a)
    for (int i = 0; i < 3; ++i)
      B[a][i] = zero;
  R vol24 = zero, amax2 = zero;
  faceTermT(x, c, 0, 3, 2, 1, B, vol24, amax2);
  faceTermT(x, c, 4, 5, 6, 7, B, vol24, amax2);
  faceTermT(x, c, 0, 1, 5, 4, B, vol24, amax2);
  faceTermT(x, c, 1, 2, 6, 5, B, vol24, amax2);
  faceTermT(x, c, 2, 3, 7, 6, B, vol24, amax2);
  faceTermT(x, c, 3, 0, 4, 7, B, vol24, amax2);
  max_face_area2 = amax2;
  const R V = vol24 / 24;
  const R s = 1 / vol24;
  for (int a = 0; a < 8; ++a)
    for (int i = 0; i < 3; ++i)
      B[a][i] *= s;
  return V;
}

template <class R>
inline R hex8ViscousHourglassT(const R x[8][3], const R v[8][3], const R B[8][3], const R &V,
                               const R &rho, const R &c, Real kappa, R Q[12], R f[8][3])
{
  constexpr Real G[8][4] = {{1, 1, 1, -1}, {1, -1, -1, 1}, {-1, -1, 1, -1}, {-1, 1, -1, 1},
                            {-1, -1, 1, 1},  {-1, 1, -1, -1}, {1, 1, 1, 1},   {1, -1, -1, -1}};
  const R zero = lit(0.0, V);
  R gx[3][4];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 4; ++k)
      gx[i][k] = zero;
  for (int b = 0; b < 8; ++b)
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 4; ++k)
        gx[i][k] += G[b][k] * x[b][i];
  R gamma[8][4];
  for (int a = 0; a < 8; ++a)
    for (int k = 0; k < 4; ++k)
      gamma[a][k] = G[a][k] - gx[0][k] * B[a][0] - gx[1][k] * B[a][1] - gx[2][k] * B[a][2];
  R qdot[3][4];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 4; ++k)
      qdot[i][k] = zero;
  for (int a = 0; a < 8; ++a)
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 4; ++k)
        qdot[i][k] += gamma[a][k] * v[a][i];
  R Qn[3][4];
  R power = zero;
  const R visc = 0.25 * kappa * rho * c * laneCbrt(V * V);
  for (int k = 0; k < 4; ++k)
    for (int i = 0; i < 3; ++i)
    {
      Qn[i][k] = visc * qdot[i][k];
      power += 0.5 * (Q[3 * k + i] + Qn[i][k]) * qdot[i][k];
      Q[3 * k + i] = Qn[i][k];
    }
  for (int a = 0; a < 8; ++a)
    for (int i = 0; i < 3; ++i)
    {
      R fa = f[a][i];
      for (int k = 0; k < 4; ++k)
        fa -= gamma[a][k] * Qn[i][k];
      f[a][i] = fa;
    }
  return power;
}

// ---- test data: distorted, moving hexes ---------------------------------------------------

struct Data
{
  int n = 0;
  std::vector<Real> x, v; // element-major [e][8][3]
  std::vector<Real> out;  // [e][28]: V, amax2, power, f[8][3], spare
};

Data &data()
{
  static Data d;
  if (d.n == 0)
  {
    const char *env = std::getenv("SCPDYN_BENCH_CELLS");
    const int cells = env && std::atoi(env) > 0 ? std::atoi(env) : 32;
    d.n = cells * cells * cells;
    d.x.resize(size_t(d.n) * 24);
    d.v.resize(size_t(d.n) * 24);
    d.out.resize(size_t(d.n) * 28);
    constexpr Real unit[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                 {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<Real> jitter(-0.15, 0.15), vel(-10, 10);
    for (int e = 0; e < d.n; ++e)
      for (int a = 0; a < 8; ++a)
        for (int i = 0; i < 3; ++i)
        {
          d.x[size_t(e) * 24 + size_t(a) * 3 + size_t(i)] = 0.01 * (unit[a][i] + jitter(rng));
          d.v[size_t(e) * 24 + size_t(a) * 3 + size_t(i)] = vel(rng);
        }
  }
  return d;
}

constexpr Real kRho = 7850, kC = 5856, kKappa = 0.05;

/// The library functions, one element at a time.
void scalarLibrary(Data &d, int e)
{
  const auto *x = reinterpret_cast<const Real(*)[3]>(&d.x[size_t(e) * 24]);
  const auto *v = reinterpret_cast<const Real(*)[3]>(&d.v[size_t(e) * 24]);
  Real B[8][3], amax2, Q[12] = {}, f[8][3] = {};
  const Real V = scpdyn::hex8Gradients(x, B, amax2);
  const Real p = scpdyn::hex8HourglassForces(x, v, B, V, kRho, kC, scpdyn::HourglassType::Viscous,
                                             kKappa, 1e-7, Q, f);
  Real *o = &d.out[size_t(e) * 28];
  o[0] = V;
  o[1] = amax2;
  o[2] = p;
  std::memcpy(o + 3, f, sizeof f);
}

/// W elements at once; element-major data transposed into lanes and back (as a kernel's
/// gather from the nodes would).
template <int W>
void lanes(Data &d, int e0)
{
  using P = Pack<W>;
  P x[8][3], v[8][3], B[8][3], amax2, Q[12], f[8][3];
  for (int a = 0; a < 8; ++a)
    for (int i = 0; i < 3; ++i)
      for (int l = 0; l < W; ++l)
      {
        x[a][i][l] = d.x[size_t(e0 + l) * 24 + size_t(a) * 3 + size_t(i)];
        v[a][i][l] = d.v[size_t(e0 + l) * 24 + size_t(a) * 3 + size_t(i)];
      }
  const P zero = lit(0.0, x[0][0]);
  for (auto &q : Q)
    q = zero;
  for (auto &fa : f)
    for (auto &fi : fa)
      fi = zero;
  const P V = hex8GradientsT(x, B, amax2);
  const P p = hex8ViscousHourglassT(x, v, B, V, lit(kRho, V), lit(kC, V), kKappa, Q, f);
  for (int l = 0; l < W; ++l)
  {
    Real *o = &d.out[size_t(e0 + l) * 28];
    o[0] = V[l];
    o[1] = amax2[l];
    o[2] = p[l];
    for (int a = 0; a < 8; ++a)
      for (int i = 0; i < 3; ++i)
        o[3 + a * 3 + i] = f[a][i][l];
  }
}

/// Lanes and library agree bit for bit on every element (else the timing is void).
template <int W>
bool sameBits(Data &d)
{
  std::vector<Real> ref(d.out.size());
  for (int e = 0; e < d.n; ++e)
    scalarLibrary(d, e);
  ref = d.out;
  for (int e = 0; e + W <= d.n; e += W)
    lanes<W>(d, e);
  return std::memcmp(ref.data(), d.out.data(), sizeof(Real) * size_t(d.n / W * W) * 28) == 0;
}

void BM_ScalarLibrary(benchmark::State &state)
{
  Data &d = data();
  for (auto _ : state)
  {
    for (int e = 0; e < d.n; ++e)
      scalarLibrary(d, e);
    benchmark::ClobberMemory();
  }
  state.counters["ns_per_element"] =
      benchmark::Counter(double(d.n) * double(state.iterations()),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

template <int W>
void BM_Lanes(benchmark::State &state)
{
  Data &d = data();
  if (!sameBits<W>(d))
  {
    state.SkipWithError("lanes differ from the library");
    return;
  }
  for (auto _ : state)
  {
    for (int e = 0; e + W <= d.n; e += W)
      lanes<W>(d, e);
    benchmark::ClobberMemory();
  }
  state.counters["ns_per_element"] =
      benchmark::Counter(double(d.n / W * W) * double(state.iterations()),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// One thread, no Kokkos: CPU time (the default) is the measure least disturbed by a loaded
// machine; "min" over repetitions as in the other drivers.
double minimum(const std::vector<double> &v) { return *std::min_element(v.begin(), v.end()); }
BENCHMARK(BM_ScalarLibrary)->Unit(benchmark::kMillisecond)->ComputeStatistics("min", minimum);
BENCHMARK_TEMPLATE(BM_Lanes, 2)->Unit(benchmark::kMillisecond)->ComputeStatistics("min", minimum);
BENCHMARK_TEMPLATE(BM_Lanes, 4)->Unit(benchmark::kMillisecond)->ComputeStatistics("min", minimum);
BENCHMARK_TEMPLATE(BM_Lanes, 8)->Unit(benchmark::kMillisecond)->ComputeStatistics("min", minimum);

} // namespace

BENCHMARK_MAIN();
