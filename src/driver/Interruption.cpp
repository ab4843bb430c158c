#include "driver/Interruption.hpp"

namespace scpdyn
{
namespace
{
volatile std::sig_atomic_t g_received_signal = 0;

extern "C" void recordSignal(int signal) { g_received_signal = signal; }

void install(int signal, struct sigaction &previous)
{
  struct sigaction action = {};
  action.sa_handler = recordSignal;
  sigemptyset(&action.sa_mask);
  // restarted system calls: a signal in the middle of a write does not fail the write
  action.sa_flags = SA_RESTART | SA_RESETHAND;
  sigaction(signal, nullptr, &previous);
  if (previous.sa_handler != SIG_IGN)
    sigaction(signal, &action, nullptr);
}
} // namespace

InterruptionHandlers::InterruptionHandlers()
{
  install(SIGINT, _previous_int);
  install(SIGTERM, _previous_term);
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
