// The next time step (integrate/TimeStep.hpp): the smallest of the elements' Courant step, the
// explicit contacts' limit (19) and the deck's cap; the contacts' horizon is the elements' own
// step, capped, before the Courant factor.
#include "integrate/TimeStep.hpp"

#include <gtest/gtest.h>

namespace scpdyn
{
namespace
{

TEST(TimeStep, TheSmallestLimitSetsTheStep)
{
  TimeStepControls ctl;
  ctl.courant = 0.5;
  ctl.dt_max = 1.0;
  TimeStepLimits limits;
  limits.element = 4e-6; // h / c
  NodeSums sums;
  EXPECT_EQ(nextTimeStep(limits, ctl, sums, MPI_COMM_NULL), 2e-6); // the elements, with courant
  limits.contact = 1e-6;
  EXPECT_EQ(nextTimeStep(limits, ctl, sums, MPI_COMM_NULL), 1e-6); // the contacts, as given
  ctl.dt_max = 5e-7;
  EXPECT_EQ(nextTimeStep(limits, ctl, sums, MPI_COMM_NULL), 5e-7); // the cap
}

TEST(TimeStep, TheContactHorizonIsTheCappedElementStepWithoutTheCourantFactor)
{
  TimeStepControls ctl;
  ctl.courant = 0.5;
  TimeStepLimits limits;
  limits.element = 4e-6;
  EXPECT_EQ(elementStep(limits, ctl, MPI_COMM_NULL), 4e-6);
  ctl.dt_max = 1e-6; // the cap binds: the horizon is the step the elements are held to
  EXPECT_EQ(elementStep(limits, ctl, MPI_COMM_NULL), 2e-6);
}

TEST(TimeStep, OneRankLeavesTheSumsAlone)
{
  TimeStepControls ctl;
  TimeStepLimits limits;
  limits.element = 1.0;
  NodeSums sums;
  sums.kinetic = 3;
  sums.momentum[2] = -2;
  nextTimeStep(limits, ctl, sums, MPI_COMM_NULL);
  EXPECT_EQ(sums.kinetic, 3);
  EXPECT_EQ(sums.momentum[2], -2);
}

} // namespace
} // namespace scpdyn
