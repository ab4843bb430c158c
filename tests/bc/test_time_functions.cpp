// The deck's time functions (bc/TimeFunctions): linear between points, constant beyond the
// ends, 1 without points; a BC names its function, an unknown name is an input error.
#include "bc/TimeFunctions.hpp"

#include <gtest/gtest.h>

namespace scpdyn
{
namespace
{

TimeFunction ramp()
{
  TimeFunction f;
  f.name = "ramp";
  f.t = {0.0, 1.0, 3.0};
  f.value = {0.0, 2.0, 1.0};
  return f;
}

TEST(TimeFunctions, LinearBetweenPointsConstantBeyondTheEnds)
{
  const TimeFunction f = ramp();
  EXPECT_EQ(evaluate(f, -1.0), 0.0);
  EXPECT_EQ(evaluate(f, 0.0), 0.0);
  EXPECT_EQ(evaluate(f, 0.25), 0.5);
  EXPECT_EQ(evaluate(f, 1.0), 2.0);
  EXPECT_EQ(evaluate(f, 2.0), 1.5);
  EXPECT_EQ(evaluate(f, 3.0), 1.0);
  EXPECT_EQ(evaluate(f, 10.0), 1.0);
}

TEST(TimeFunctions, WithoutPointsTheValueIsOne) { EXPECT_EQ(evaluate(TimeFunction{}, 5.0), 1.0); }

TEST(TimeFunctions, FindByNameNoneOrAnInputErrorNamingTheKey)
{
  TimeFunction other = ramp();
  other.name = "other";
  const std::vector<TimeFunction> functions = {ramp(), other};
  EXPECT_EQ(findFunction(functions, "", "bc.function"), -1);
  EXPECT_EQ(findFunction(functions, "ramp", "bc.function"), 0);
  EXPECT_EQ(findFunction(functions, "other", "bc.function"), 1);
  try
  {
    findFunction(functions, "rampp", "deck.yaml: boundary_conditions[2].function");
    FAIL() << "no InputError for an unknown function";
  }
  catch (const InputError &e)
  {
    EXPECT_STREQ(e.what(), "deck.yaml: boundary_conditions[2].function: unknown function 'rampp'");
  }
}

} // namespace
} // namespace scpdyn
