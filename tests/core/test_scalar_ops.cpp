// The shared branch helpers (core/ScalarOps.hpp) and the set-up copy to the device
// (core/HostCopy.hpp).
#include "core/HostCopy.hpp"
#include "core/ScalarOps.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace scpdyn
{
namespace
{

TEST(ScalarOps, AbsMinMaxClamp)
{
  EXPECT_EQ(scalar_ops::abs(-2.5), 2.5);
  EXPECT_EQ(scalar_ops::abs(2.5), 2.5);
  EXPECT_EQ(scalar_ops::min(1.0, -3.0), -3.0);
  EXPECT_EQ(scalar_ops::max(1.0, -3.0), 1.0);
  EXPECT_EQ(scalar_ops::clamp(-1.0, 0.0, 1.0), 0.0);
  EXPECT_EQ(scalar_ops::clamp(0.5, 0.0, 1.0), 0.5);
  EXPECT_EQ(scalar_ops::clamp(2.0, 0.0, 1.0), 1.0);
}

TEST(ScalarOps, WithANanOperandMinAndMaxReturnTheSecond)
{
  const Real nan = std::numeric_limits<Real>::quiet_NaN();
  EXPECT_EQ(scalar_ops::min(nan, 1.0), 1.0);
  EXPECT_EQ(scalar_ops::max(nan, 1.0), 1.0);
  EXPECT_TRUE(std::isnan(scalar_ops::min(1.0, nan)));
  EXPECT_TRUE(std::isnan(scalar_ops::max(1.0, nan)));
}

TEST(HostCopy, ToDeviceKeepsValuesAndLabel)
{
  const std::vector<Index> host = {3, 1, 4, 1, 5};
  const IndexView v = toDevice(host, "scpdyn::test::digits");
  EXPECT_EQ(v.label(), "scpdyn::test::digits");
  ASSERT_EQ(v.extent(0), host.size());
  auto h = Kokkos::create_mirror_view_and_copy(HostSpace(), v);
  for (size_t i = 0; i < host.size(); ++i)
    EXPECT_EQ(h(i), host[i]);
}

} // namespace
} // namespace scpdyn
