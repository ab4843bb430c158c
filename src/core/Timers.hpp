#pragma once
/// \file Timers.hpp
/// \brief Wall-clock timers for the named steps of the cycle, and a Kokkos profiling region
/// per step (Kokkos 3.4 has no ScopedRegion, hence the small RAII helper).
#include <Kokkos_Core.hpp>

#include <chrono>
#include <map>
#include <string>

namespace scpdyn
{

class StepTimers
{
public:
  void add(const std::string &name, double seconds) { _seconds[name] += seconds; }
  const std::map<std::string, double> &seconds() const { return _seconds; }

private:
  std::map<std::string, double> _seconds;
};

/// \brief Times one step: pushes a Kokkos profiling region, fences at the end so the
/// time belongs to this step.
class ScopedStep
{
public:
  ScopedStep(StepTimers &timers, const char *name)
      : _timers(timers), _name(name), _start(std::chrono::steady_clock::now())
  {
    Kokkos::Profiling::pushRegion(name);
  }
  ~ScopedStep()
  {
    Kokkos::fence();
    Kokkos::Profiling::popRegion();
    _timers.add(_name, std::chrono::duration<double>(std::chrono::steady_clock::now() - _start).count());
  }
  ScopedStep(const ScopedStep &) = delete;
  ScopedStep &operator=(const ScopedStep &) = delete;

private:
  StepTimers &_timers;
  const char *_name;
  std::chrono::steady_clock::time_point _start;
};

} // namespace scpdyn
