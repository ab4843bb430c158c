#pragma once
/// \file HostCopy.hpp
/// \brief Set-up helper: a host std::vector copied into a new device View (not for the cycle:
/// it allocates).
#include "core/Types.hpp"

#include <string>
#include <vector>

namespace scpdyn
{

/// \brief A device View labelled `label` holding the values of `host`.
template <class T>
DeviceView<T *> toDevice(const std::vector<T> &host, const std::string &label)
{
  DeviceView<T *> v(label, host.size());
  auto h = Kokkos::create_mirror_view(v);
  for (size_t i = 0; i < host.size(); ++i)
    h(i) = host[i];
  Kokkos::deep_copy(v, h);
  return v;
}

} // namespace scpdyn
