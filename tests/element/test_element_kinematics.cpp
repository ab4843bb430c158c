// Element units: measures and mean gradients exact for affine elements of every type, the
// hex volume against Gauss quadrature on distorted hexes, the patch test (linear velocity ->
// exact uniform strain rate on distorted meshes), hourglass orthogonality.
#include "element/ElementKinematics.hpp"
#include "element/Hourglass.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace scpdyn;

namespace
{
// reference elements in our node orders
const Real kLine[2][3] = {{0, 0, 0}, {1, 0, 0}};
const Real kQuad[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
const Real kHex[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                         {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
const Real kTet[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

struct Affine
{
  Real F[3][3];
  Real t[3];
};

// a random well-conditioned affine map of dimension d with det F > 0
Affine randomAffine(std::mt19937 &rng, int d)
{
  std::uniform_real_distribution<Real> u(-0.3, 0.3);
  Affine a{};
  for (int i = 0; i < 3; ++i)
  {
    a.t[i] = i < d ? 10 * u(rng) : 0;
    for (int j = 0; j < 3; ++j)
      a.F[i][j] = (i < d && j < d) ? (i == j ? 1.5 : 0) + u(rng) : 0;
  }
  return a;
}

Real det(const Real F[3][3], int d)
{
  if (d == 1)
    return F[0][0];
  if (d == 2)
    return F[0][0] * F[1][1] - F[0][1] * F[1][0];
  return F[0][0] * (F[1][1] * F[2][2] - F[1][2] * F[2][1]) -
         F[0][1] * (F[1][0] * F[2][2] - F[1][2] * F[2][0]) +
         F[0][2] * (F[1][0] * F[2][1] - F[1][1] * F[2][0]);
}

template <ElementType T>
void checkAffine(const Real ref[][3], Real ref_measure)
{
  constexpr int N = ElementTraits<T>::nodes;
  constexpr int D = ElementTraits<T>::dim;
  std::mt19937 rng(42);
  for (int trial = 0; trial < 50; ++trial)
  {
    const Affine a = randomAffine(rng, D);
    Real x[N][3], Bref[N][3], B[N][3];
    for (int n = 0; n < N; ++n)
      for (int i = 0; i < 3; ++i)
      {
        x[n][i] = a.t[i];
        for (int j = 0; j < 3; ++j)
          x[n][i] += a.F[i][j] * ref[n][j];
      }
    const Real V = elementGradients<T>(x, B);
    elementGradients<T>(ref, Bref);
    // exact: V = det F * V_ref, and grad_x N = F^{-T} grad_X N, i.e. B F = B_ref
    EXPECT_NEAR(V, det(a.F, D) * ref_measure, 1e-13 * std::abs(V));
    for (int n = 0; n < N; ++n)
      for (int j = 0; j < D; ++j)
      {
        Real BF = 0;
        for (int i = 0; i < D; ++i)
          BF += B[n][i] * a.F[i][j];
        EXPECT_NEAR(BF, Bref[n][j], 1e-12);
      }
  }
}

// distorted (non-affine, warped) hex: nodes of the unit cube moved randomly by up to 20 %
void distortedHex(std::mt19937 &rng, Real x[8][3])
{
  std::uniform_real_distribution<Real> u(-0.2, 0.2);
  for (int n = 0; n < 8; ++n)
    for (int i = 0; i < 3; ++i)
      x[n][i] = kHex[n][i] + u(rng) + 3.0;
}

// trilinear volume by 2x2x2 Gauss quadrature, exact for det J (degree <= 2 per variable)
Real gaussHexVolume(const Real x[8][3])
{
  const Real sgn[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                          {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  const Real g = 1 / std::sqrt(3.0);
  Real V = 0;
  for (int p = 0; p < 8; ++p)
  {
    const Real xi[3] = {sgn[p][0] * g, sgn[p][1] * g, sgn[p][2] * g};
    Real J[3][3] = {};
    for (int n = 0; n < 8; ++n)
      for (int k = 0; k < 3; ++k)
      {
        Real dN = sgn[n][k] / 8;
        for (int m = 0; m < 3; ++m)
          if (m != k)
            dN *= 1 + sgn[n][m] * xi[m];
        for (int i = 0; i < 3; ++i)
          J[i][k] += x[n][i] * dN;
      }
    V += det(J, 3);
  }
  return V;
}
} // namespace

TEST(ElementKinematics, AffineLine2) { checkAffine<ElementType::Line2>(kLine, 1.0); }
TEST(ElementKinematics, AffineQuad4) { checkAffine<ElementType::Quad4>(kQuad, 1.0); }
TEST(ElementKinematics, AffineHex8) { checkAffine<ElementType::Hex8>(kHex, 1.0); }
TEST(ElementKinematics, AffineTet4) { checkAffine<ElementType::Tet4>(kTet, 1.0 / 6); }

TEST(ElementKinematics, DistortedHexVolumeAndGradientAreExact)
{
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial)
  {
    Real x[8][3], B[8][3];
    distortedHex(rng, x);
    const Real V = hex8Gradients(x, B);
    EXPECT_NEAR(V, gaussHexVolume(x), 1e-13);
    // B = (1/V) dV/dx: V is cubic in x, so the central difference is exact up to round-off
    const Real h = 1e-4;
    for (int n = 0; n < 8; ++n)
      for (int i = 0; i < 3; ++i)
      {
        Real xp[8][3], xm[8][3];
        std::copy(&x[0][0], &x[0][0] + 24, &xp[0][0]);
        std::copy(&x[0][0], &x[0][0] + 24, &xm[0][0]);
        xp[n][i] += h;
        xm[n][i] -= h;
        const Real dV = (gaussHexVolume(xp) - gaussHexVolume(xm)) / (2 * h);
        EXPECT_NEAR(B[n][i] * V, dV, 1e-8);
      }
  }
}

// Patch test at element level: v = G x + c gives sum_a v_a B_a = G exactly on distorted
// elements of every type (consistency sum_a x_a B_a = I holds for any shape).
template <ElementType T>
void checkPatch(std::mt19937 &rng, const Real ref[][3])
{
  constexpr int N = ElementTraits<T>::nodes;
  constexpr int D = ElementTraits<T>::dim;
  std::uniform_real_distribution<Real> u(-0.15, 0.15);
  for (int trial = 0; trial < 20; ++trial)
  {
    Real x[N][3], v[N][3], B[N][3], G[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        G[i][j] = (i < D && j < D) ? 100 * u(rng) : 0;
    for (int n = 0; n < N; ++n)
      for (int i = 0; i < 3; ++i)
        x[n][i] = ref[n][i] + (i < D ? u(rng) : 0);
    for (int n = 0; n < N; ++n)
      for (int i = 0; i < 3; ++i)
      {
        v[n][i] = i < D ? 3.0 : 0;
        for (int j = 0; j < 3; ++j)
          v[n][i] += G[i][j] * x[n][j];
      }
    elementGradients<T>(x, B);
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j)
      {
        Real L = 0;
        for (int n = 0; n < N; ++n)
          L += v[n][i] * B[n][j];
        EXPECT_NEAR(L, G[i][j], 1e-11);
      }
  }
}

TEST(ElementKinematics, PatchTestDistortedElements)
{
  std::mt19937 rng(3);
  checkPatch<ElementType::Line2>(rng, kLine);
  checkPatch<ElementType::Quad4>(rng, kQuad);
  checkPatch<ElementType::Hex8>(rng, kHex);
  checkPatch<ElementType::Tet4>(rng, kTet);
}

// Hourglass forces vanish for every linear velocity field on a distorted element, and
// resist the pure hourglass mode.
template <ElementType T>
void checkHourglass(const Real ref[][3])
{
  constexpr int N = ElementTraits<T>::nodes;
  constexpr int D = ElementTraits<T>::dim;
  std::mt19937 rng(11);
  std::uniform_real_distribution<Real> u(-0.15, 0.15);
  Real x[N][3], v[N][3], B[N][3], f[N][3] = {}, Q[kHourglassSize] = {};
  for (int n = 0; n < N; ++n)
    for (int i = 0; i < 3; ++i)
      x[n][i] = ref[n][i] + (i < D ? u(rng) : 0);
  const Real V = elementGradients<T>(x, B);
  for (int n = 0; n < N; ++n)
    for (int i = 0; i < 3; ++i)
      v[n][i] = i < D ? 1.0 + 2 * x[n][0] - 3 * x[n][1] + (D == 3 ? 0.5 * x[n][2] : 0) : 0;
  const Real p = hourglassForces<T>(x, v, B, V, hourglassAreaScale<T>(V), 1000, 5000,
                                    HourglassType::Viscous, 0.1, 1e-6, Q, f);
  EXPECT_NEAR(p, 0, 1e-6);
  for (int n = 0; n < N; ++n)
    for (int i = 0; i < D; ++i)
      EXPECT_NEAR(f[n][i], 0, 1e-6);
  for (int n = 0; n < N; ++n)
    for (int i = 0; i < 3; ++i)
      v[n][i] = i == 0 ? hourglassBase<T>(0, n) : 0;
  const Real p2 = hourglassForces<T>(x, v, B, V, hourglassAreaScale<T>(V), 1000, 5000,
                                     HourglassType::Viscous, 0.1, 1e-6, Q, f);
  EXPECT_GT(p2, 0); // the mode is damped: positive dissipation
}

// The butterflies of the hex8 hourglass (hex8ModeSums, hex8ModeSpread) against the sums with
// the base-vector table: every sign must be that of hourglassBase<Hex8>. Tolerance: a few ulp
// of the largest term (8 terms of size <= 1 in different order).
TEST(ElementKinematics, Hex8ModeButterfliesMatchTheBaseVectors)
{
  std::mt19937 rng(5);
  std::uniform_real_distribution<Real> u(-1, 1);
  for (int trial = 0; trial < 100; ++trial)
  {
    Real y[8], m[4], got[4], spread[8];
    for (int a = 0; a < 8; ++a)
      y[a] = u(rng);
    for (int k = 0; k < 4; ++k)
      m[k] = u(rng);
    hex8ModeSums(y[0], y[1], y[2], y[3], y[4], y[5], y[6], y[7], got);
    hex8ModeSpread(m, spread);
    for (int k = 0; k < 4; ++k)
    {
      Real ref = 0;
      for (int a = 0; a < 8; ++a)
        ref += hourglassBase<ElementType::Hex8>(k, a) * y[a];
      EXPECT_NEAR(got[k], ref, 1e-14) << "mode " << k;
    }
    for (int a = 0; a < 8; ++a)
    {
      Real ref = 0;
      for (int k = 0; k < 4; ++k)
        ref += hourglassBase<ElementType::Hex8>(k, a) * m[k];
      EXPECT_NEAR(spread[a], ref, 1e-14) << "node " << a;
    }
  }
}

TEST(ElementKinematics, HourglassOrthogonalToLinearFields)
{
  checkHourglass<ElementType::Quad4>(kQuad);
  checkHourglass<ElementType::Hex8>(kHex);
}

TEST(ElementKinematics, CharacteristicLengthOfCubesIsTheSide)
{
  Real B[8][3], x[8][3];
  for (int n = 0; n < 8; ++n)
    for (int i = 0; i < 3; ++i)
      x[n][i] = 0.002 * kHex[n][i];
  EXPECT_NEAR(characteristicLength<ElementType::Hex8>(x, hex8Gradients(x, B)), 0.002, 1e-15);
  Real q[4][3], Bq[4][3];
  for (int n = 0; n < 4; ++n)
    for (int i = 0; i < 3; ++i)
      q[n][i] = 0.002 * kQuad[n][i];
  EXPECT_NEAR(characteristicLength<ElementType::Quad4>(q, quad4Gradients(q, Bq)), 0.002, 1e-15);
}

TEST(ElementKinematics, AxisymmetricVolumePerRadian)
{
  // ring of rectangular section [r0, r1] x [0, h]: volume per radian = (r1^2 - r0^2)/2 * h
  const Real r0 = 0.3, r1 = 0.5, h = 0.2;
  const Real x[4][3] = {{r0, 0, 0}, {r1, 0, 0}, {r1, h, 0}, {r0, h, 0}};
  EXPECT_NEAR(quad4RadialVolume(x), 0.5 * (r1 * r1 - r0 * r0) * h, 1e-15);
}
