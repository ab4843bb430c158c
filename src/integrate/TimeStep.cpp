#include "integrate/TimeStep.hpp"

#include "parallel/Mpi.hpp"

namespace scpdyn
{

Real elementStep(const TimeStepLimits &limits, const TimeStepControls &ctl, MPI_Comm comm)
{
  Real step = cappedElementStep(limits, ctl);
  if (comm != MPI_COMM_NULL)
    step = allReduceMin(step, comm);
  return step / ctl.courant;
}

Real nextTimeStep(const TimeStepLimits &limits, const TimeStepControls &ctl, NodeSums &sums,
                  MPI_Comm comm, int *stop_signal)
{
  const Real element_dt = cappedElementStep(limits, ctl);
  Real dt = limits.contact < element_dt ? limits.contact : element_dt;
  if (comm == MPI_COMM_NULL)
    return dt;
  Real sum[7] = {sums.kinetic,     sums.kinetic_mid, sums.external_work, sums.momentum[0],
                 sums.momentum[1], sums.momentum[2], sums.damping_work};
  // the largest signal number as the least of their negatives, exact in a double
  Real mins[2] = {dt, stop_signal ? -Real(*stop_signal) : 0};
  allReduceSumMin(sum, 7, mins, 2, comm);
  dt = mins[0];
  if (stop_signal)
    *stop_signal = int(-mins[1]);
  sums.kinetic = sum[0];
  sums.kinetic_mid = sum[1];
  sums.external_work = sum[2];
  for (int i = 0; i < 3; ++i)
    sums.momentum[i] = sum[3 + i];
  sums.damping_work = sum[6];
  return dt;
}

} // namespace scpdyn
