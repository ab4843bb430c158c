// The order-independent sums of the constraint solves (core/ExactSum.hpp): exact where a
// double sum loses everything, the same bits in any order and from a threaded reduction.
#include "core/ExactSum.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace scpdyn
{
namespace
{

Real exactSum(const std::vector<Real> &terms)
{
  ExactSums<1> s;
  s.clear();
  for (Real x : terms)
    s.add(0, x);
  return s.value(0);
}

Real bits(Real x) { return x; }

TEST(ExactSum, CancellationAndRangeEnds)
{
  EXPECT_EQ(exactSum({1e100, 1.0, -1e100}), 1.0);
  EXPECT_EQ(exactSum({std::numeric_limits<Real>::max(), -std::numeric_limits<Real>::max(), 0.5}),
            0.5);
  const Real tiny = std::numeric_limits<Real>::denorm_min();
  EXPECT_EQ(exactSum({tiny, tiny, tiny}), 3 * tiny);
  EXPECT_EQ(exactSum({1.0, tiny, -1.0}), tiny);
  EXPECT_EQ(exactSum({-2.5, -0.25}), -2.75);
  EXPECT_EQ(exactSum({}), 0.0);
  EXPECT_TRUE(std::isnan(exactSum({1.0, std::numeric_limits<Real>::infinity()})));
  EXPECT_TRUE(std::isnan(exactSum({std::nan("")})));
  // 2^1023 + 2^1023 is past the double range
  EXPECT_EQ(exactSum({std::ldexp(1.0, 1023), std::ldexp(1.0, 1023)}), HUGE_VAL);
}

// Pairs x, -x over 600 decades around a set whose sum is known exactly: a plain double sum
// keeps little of it, the exact one all, in every order.
TEST(ExactSum, KnownSumInAnyOrder)
{
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<Real> mant(-1.0, 1.0);
  std::uniform_int_distribution<int> expo(-300, 300);
  std::vector<Real> terms;
  for (int i = 0; i < 20000; ++i)
  {
    const Real x = std::ldexp(mant(rng), expo(rng));
    terms.push_back(x);
    terms.push_back(-x);
  }
  Real known = 0; // multiples of 2^-20 below 2^30: their double sum is exact
  for (int i = 0; i < 1000; ++i)
  {
    const Real y = std::ldexp(Real(std::int64_t(rng() % (1u << 30)) - (1 << 29)), -20);
    terms.push_back(y);
    known += y;
  }
  for (int round = 0; round < 5; ++round)
  {
    std::shuffle(terms.begin(), terms.end(), rng);
    EXPECT_EQ(bits(exactSum(terms)), bits(known)) << "order " << round;
  }
}

// A threaded reduction, split among threads in any way, gives the sequential limbs.
TEST(ExactSum, KokkosReductionMatchesSequential)
{
  const int n = 100000;
  Kokkos::View<Real *, MemSpace> t("terms", n);
  auto h = Kokkos::create_mirror_view(t);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<Real> u(-1.0, 1.0);
  std::vector<Real> terms(n);
  for (int i = 0; i < n; ++i)
    h(i) = terms[size_t(i)] = std::ldexp(u(rng), int(rng() % 80) - 40);
  Kokkos::deep_copy(t, h);
  ExactSums<2> s;
  Kokkos::parallel_reduce(
      "test::exactSum", Kokkos::RangePolicy<ExecSpace>(0, n),
      KOKKOS_LAMBDA(const int i, ExactSums<2> &acc) {
        acc.add(0, t(i));
        acc.add(1, t(i) * t(i));
      },
      ExactSumsReducer<2>(s));
  std::vector<Real> squares(terms.size());
  for (size_t i = 0; i < terms.size(); ++i)
    squares[i] = terms[i] * terms[i];
  EXPECT_EQ(bits(s.value(0)), bits(exactSum(terms)));
  EXPECT_EQ(bits(s.value(1)), bits(exactSum(squares)));
  Real plain = 0;
  for (Real x : squares)
    plain += x;
  EXPECT_NEAR(s.value(1), plain, 1e-12 * plain); // and it is the sum
}

} // namespace
} // namespace scpdyn
