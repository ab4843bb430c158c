#pragma once
/// \file Timers.hpp
/// \brief Wall-clock timers for the named steps of the cycle, and a Kokkos profiling region
/// per step (Kokkos 3.4 has no ScopedRegion, hence the small RAII helper).
///
/// Nothing here builds a std::string inside the cycle: the timers are keyed by the step's
/// name as a `const char *` (a string literal), and the profiling region (whose API takes a
/// std::string, a heap allocation for names over 15 characters) is pushed only when a
/// Kokkos tool is loaded. The cycle is then free of heap allocations (perf/bench_cycle).
#include <Kokkos_Core.hpp>

#include <chrono>
#include <cstring>
#include <map>
#include <string>

namespace scpdyn
{

class StepTimers
{
public:
  /// \brief Adds seconds to the step `name` (a string literal: the pointer is kept).
  void add(const char *name, double seconds)
  {
    for (int k = 0; k < _count; ++k)
      if (_names[k] == name || std::strcmp(_names[k], name) == 0)
      {
        _seconds[k] += seconds;
        return;
      }
    if (_count < kMaxSteps)
    {
      _names[_count] = name;
      _seconds[_count++] = seconds;
    }
    else
      _overflow[name] += seconds; // only past kMaxSteps distinct steps
  }
  /// \brief Seconds per step name, sorted by name [s].
  std::map<std::string, double> seconds() const
  {
    std::map<std::string, double> out = _overflow;
    for (int k = 0; k < _count; ++k)
      out[_names[k]] += _seconds[k];
    return out;
  }

private:
  static constexpr int kMaxSteps = 32;
  const char *_names[kMaxSteps] = {};
  double _seconds[kMaxSteps] = {};
  int _count = 0;
  std::map<std::string, double> _overflow;
};

/// \brief Times one step: pushes a Kokkos profiling region (if a tool is loaded), fences at
/// the end so the time belongs to this step.
class ScopedStep
{
public:
  ScopedStep(StepTimers &timers, const char *name)
      : _timers(timers), _name(name), _region(Kokkos::Tools::profileLibraryLoaded()),
        _start(std::chrono::steady_clock::now())
  {
    if (_region)
      Kokkos::Profiling::pushRegion(name);
  }
  ~ScopedStep()
  {
    Kokkos::fence();
    if (_region)
      Kokkos::Profiling::popRegion();
    _timers.add(_name,
                std::chrono::duration<double>(std::chrono::steady_clock::now() - _start).count());
  }
  ScopedStep(const ScopedStep &) = delete;
  ScopedStep &operator=(const ScopedStep &) = delete;

private:
  StepTimers &_timers;
  const char *_name;
  bool _region;
  std::chrono::steady_clock::time_point _start;
};

} // namespace scpdyn
