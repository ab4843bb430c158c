#include "bc/TimeFunctions.hpp"

#include <algorithm>

namespace scpdyn
{

Real evaluate(const TimeFunction &f, Real t)
{
  if (f.t.empty())
    return 1;
  if (t <= f.t.front())
    return f.value.front();
  if (t >= f.t.back())
    return f.value.back();
  const auto it = std::upper_bound(f.t.begin(), f.t.end(), t);
  const size_t k = size_t(it - f.t.begin());
  const Real w = (t - f.t[k - 1]) / (f.t[k] - f.t[k - 1]);
  return (1 - w) * f.value[k - 1] + w * f.value[k];
}

int findFunction(const std::vector<TimeFunction> &functions, const std::string &name,
                 const std::string &key)
{
  if (name.empty())
    return -1;
  for (size_t i = 0; i < functions.size(); ++i)
    if (functions[i].name == name)
      return int(i);
  throw InputError(key + ": unknown function '" + name + "'");
}

} // namespace scpdyn
