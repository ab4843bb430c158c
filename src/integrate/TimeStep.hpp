#pragma once
/// \file TimeStep.hpp
/// \brief The next cycle's time step from every limit (docs/theory.md 2.2, step 12): the
/// elements' Courant step, the explicit contacts' limit (19) and the deck's cap, in the one
/// reduction of the cycle that also sums step 12's energies and momentum over the ranks. The
/// explicit contacts' limit predicts the joint's closure over the elements' own step of this
/// cycle (elementStep()), which must be the same on every rank: with explicit contacts on more
/// than one rank that takes a reduction of its own, before the contact limit is computed.
#include "integrate/NodeIntegrator.hpp"

#include <mpi.h>

namespace scpdyn
{

/// \brief This rank's limits on the next time step, before the Courant factor where it applies.
struct TimeStepLimits
{
  Real element = 1e300; ///< smallest element h / c (step 6) [s]
  Real contact = 1e300; ///< smallest explicit-contact limit (19) (step 12), already safe [s]
};

/// \brief The deck's controls of the time step.
struct TimeStepControls
{
  Real courant = 0.5; ///< the elements' Courant number (the deck's default)
  Real dt_max = 1e30; ///< the user's cap (the deck's default: none) [s]
};

/// \brief The elements' step with the Courant factor and the cap, min(courant h / c, dt_max),
/// on this rank.
KOKKOS_INLINE_FUNCTION Real cappedElementStep(const TimeStepLimits &limits,
                                              const TimeStepControls &ctl)
{
  const Real courant_step = ctl.courant * limits.element;
  return courant_step < ctl.dt_max ? courant_step : ctl.dt_max;
}

/// \brief The horizon of the explicit contacts' limit (19): cappedElementStep() / courant, the
/// minimum over the ranks of `comm` (MPI_COMM_NULL: this rank's) [s].
Real elementStep(const TimeStepLimits &limits, const TimeStepControls &ctl, MPI_Comm comm);

/// \brief The next time step, min(cappedElementStep(), contact) over all ranks of `comm`, and
/// `sums` (this rank's step-12 sums of its owned nodes) summed over them in rank order, in one
/// collective (MPI_COMM_NULL: one rank, nothing to reduce) [s]. With `stop_signal`: in, the
/// signal this rank was asked to stop by (0: none), out, the largest of any rank's, in the same
/// collective, so that all ranks stop after the same cycle (driver/Interruption.hpp).
Real nextTimeStep(const TimeStepLimits &limits, const TimeStepControls &ctl, NodeSums &sums,
                  MPI_Comm comm, int *stop_signal = nullptr);

} // namespace scpdyn
