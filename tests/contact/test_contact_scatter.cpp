// The rule of the contact scatter's fast path (contact_kernels::NodeAdder, ContactKernels.hpp):
// plain adds on one thread, atomic adds otherwise, and in one order both form the same sums,
// bit for bit. The other half of the rule, that one thread and two threads give the same run to
// round-off (plain adds against atomics in another order), is parallel_hybrid's: its decks run
// at 1 x 1 and 1 x 2 (tests/parallel/hybrid.sh).
#include "contact/ContactKernels.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <vector>

using namespace scpdyn;
using contact_kernels::NodeAdder;

namespace
{

// shares of every sign and magnitude into a few targets, as the CPs of a node add them
std::vector<Real> shares()
{
  std::vector<Real> s;
  Real x = 0.123456789;
  for (int i = 0; i < 997; ++i)
  {
    x = x * 3.9 * (1.0 - x); // a logistic map: no two shares alike
    s.push_back((i % 3 == 0 ? -1.0 : 1.0) * x * (i % 7 == 0 ? 1e-9 : 1.0) * (1 + i % 5));
  }
  return s;
}

} // namespace

TEST(ContactScatter, PlainAndAtomicAddsInOneOrderGiveTheSameBits)
{
  const std::vector<Real> s = shares();
  Real plain[5] = {0, 0, 0, 0, 0}, atomic[5] = {0, 0, 0, 0, 0};
  const NodeAdder add_plain{true}, add_atomic{false};
  for (size_t i = 0; i < s.size(); ++i)
  {
    add_plain(&plain[i % 5], s[i]);
    add_atomic(&atomic[i % 5], s[i]);
  }
  EXPECT_EQ(std::memcmp(plain, atomic, sizeof(plain)), 0);
  for (int k = 0; k < 5; ++k)
    EXPECT_NE(plain[k], 0.0);
}

TEST(ContactScatter, PlainAddsOnlyOnOneThread)
{
  EXPECT_EQ(contact_kernels::nodeAdder().plain, ExecSpace().concurrency() == 1);
}
