#pragma once
/// \file Interruption.hpp
/// \brief SIGINT and SIGTERM stop a run at the end of the cycle they arrive in, with complete
/// outputs (Solver::run): the handler only records the signal, and the cycle's time-step
/// reduction (integrate/TimeStep.hpp) tells every rank whether any rank has one, so that all
/// ranks stop after the same cycle and finalise MPI normally.
#include <csignal>
#include <string>

namespace scpdyn
{

/// \brief While it lives, SIGINT and SIGTERM are recorded for receivedSignal() instead of ending
/// the process. The first SIGINT restores its default action, so a second one ends the process
/// at once; every SIGTERM is recorded alike. A signal ignored when the object is made (SIGINT of
/// a background job of a script) stays ignored. The previous actions come back on destruction.
class InterruptionHandlers
{
public:
  InterruptionHandlers();
  ~InterruptionHandlers();
  InterruptionHandlers(const InterruptionHandlers &) = delete;
  InterruptionHandlers &operator=(const InterruptionHandlers &) = delete;

private:
  struct sigaction _previous_int, _previous_term;
};

/// \brief The last signal recorded in this process (0: none).
int receivedSignal();

/// \brief "SIGINT", "SIGTERM", else "signal N".
std::string signalName(int signal);

/// \brief The shell's exit status of a process ended by `signal`: 128 + its number.
inline int interruptedExitStatus(int signal) { return 128 + signal; }

} // namespace scpdyn
