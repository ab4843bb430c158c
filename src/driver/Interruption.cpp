#include "driver/Interruption.hpp"

namespace scpdyn
{
namespace
{
volatile std::sig_atomic_t g_received_signal = 0;

extern "C" void recordSignal(int signal) { g_received_signal = signal; }

void install(int signal, struct sigaction &previous, int flags)
{
  struct sigaction action = {};
  action.sa_handler = recordSignal;
  sigemptyset(&action.sa_mask);
  // restarted system calls: a signal in the middle of a write does not fail the write
  action.sa_flags = SA_RESTART | flags;
  sigaction(signal, nullptr, &previous);
  if (previous.sa_handler != SIG_IGN)
    sigaction(signal, &action, nullptr);
}
} // namespace

InterruptionHandlers::InterruptionHandlers()
{
  // a second Ctrl-C ends the run at once; SIGTERM may come more than once from one request
  // (a batch system signals every process of the job, mpirun signals its ranks again), and
  // SIGKILL is there to force an end
  install(SIGINT, _previous_int, SA_RESETHAND);
  install(SIGTERM, _previous_term, 0);
}

InterruptionHandlers::~InterruptionHandlers()
{
  sigaction(SIGINT, &_previous_int, nullptr);
  sigaction(SIGTERM, &_previous_term, nullptr);
}

int receivedSignal() { return int(g_received_signal); }

std::string signalName(int signal)
{
  if (signal == SIGINT)
    return "SIGINT";
  if (signal == SIGTERM)
    return "SIGTERM";
  return "signal " + std::to_string(signal);
}

} // namespace scpdyn
