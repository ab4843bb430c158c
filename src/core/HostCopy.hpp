#pragma once
/// \file HostCopy.hpp
/// \brief Host <-> device copies outside the cycle (they allocate): a host std::vector into a
/// new device View, and a View of rank 1 or 2 to and from a flat vector of doubles (restart
/// files), entry (i, j) at i * extent(1) + j whatever the layout.
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

/// \brief The values per entry (row) of `v` in flatten(), whatever its number of rows.
template <class View>
int flatWidth(const View &v)
{
  return View::rank > 1 ? int(v.extent(1)) : 1;
}

/// \brief The entries of `v` (rank 1 or 2) as doubles, row by row.
template <class View>
std::vector<double> flatten(const View &v)
{
  auto h = Kokkos::create_mirror_view_and_copy(HostSpace(), v);
  const size_t n = h.extent(0), m = View::rank > 1 ? h.extent(1) : 1;
  std::vector<double> out(n * m);
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < m; ++j)
    {
      if constexpr (View::rank > 1)
        out[i * m + j] = double(h(i, j));
      else
        out[i] = double(h(i));
    }
  return out;
}

/// \brief The inverse of flatten(): `v` (already of the right size) takes the values of `flat`.
template <class View>
void unflatten(const View &v, const std::vector<double> &flat)
{
  auto h = Kokkos::create_mirror_view(v);
  const size_t n = h.extent(0), m = View::rank > 1 ? h.extent(1) : 1;
  using T = typename View::non_const_value_type;
  for (size_t i = 0; i < n && (i + 1) * m <= flat.size(); ++i)
    for (size_t j = 0; j < m; ++j)
    {
      if constexpr (View::rank > 1)
        h(i, j) = T(flat[i * m + j]);
      else
        h(i) = T(flat[i]);
    }
  Kokkos::deep_copy(v, h);
}

} // namespace scpdyn
