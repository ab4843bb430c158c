#pragma once
// Values of a summary.json read by key path, for the tests of what a run writes: enough JSON
// for scpdyn's own pretty-printed output (JsonObject::dump), not a general parser.
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace scpdyn::test
{

/// The keys of the object that starts at `object` (its own, not those of objects inside it),
/// each with the position of its value.
inline std::vector<std::pair<std::string, size_t>> members(const std::string &json, size_t object)
{
  std::vector<std::pair<std::string, size_t>> out;
  if (object >= json.size() || json[object] != '{')
    return out;
  int depth = 0;
  for (size_t k = object; k < json.size(); ++k)
  {
    const char c = json[k];
    if (c == '{' || c == '[')
      ++depth;
    else if ((c == '}' || c == ']') && --depth == 0)
      break;
    else if (c == '"') // a key or a string value: a key is followed by a colon
    {
      const size_t end = json.find('"', k + 1);
      if (depth == 1 && json.compare(end + 1, 2, ": ") == 0)
        out.emplace_back(json.substr(k + 1, end - k - 1), end + 3);
      k = end;
    }
  }
  return out;
}

/// Position of the value at the path of keys from the top of summary.json, or npos.
inline size_t jsonPos(const std::string &json, const std::vector<std::string> &path)
{
  size_t at = json.find('{');
  for (const std::string &key : path)
  {
    size_t found = std::string::npos;
    for (const auto &[k, value] : members(json, at))
      if (k == key)
        found = value;
    if ((at = found) == std::string::npos)
      break;
  }
  return at;
}

/// The scalar at `path` (a number, or a string without its quotes; "" if missing).
inline std::string jsonText(const std::string &json, const std::vector<std::string> &path)
{
  size_t at = jsonPos(json, path);
  if (at == std::string::npos)
    return "";
  std::string v = json.substr(at, json.find_first_of(",\n", at) - at);
  if (v.size() >= 2 && v.front() == '"')
    v = v.substr(1, v.size() - 2);
  return v;
}

inline double jsonNumber(const std::string &json, const std::vector<std::string> &path)
{
  const std::string v = jsonText(json, path);
  return v.empty() ? NAN : std::stod(v);
}

/// The keys of the object at `path`, in order.
inline std::vector<std::string> jsonKeys(const std::string &json,
                                         const std::vector<std::string> &path)
{
  const size_t at = jsonPos(json, path);
  std::vector<std::string> keys;
  if (at != std::string::npos)
    for (const auto &m : members(json, at))
      keys.push_back(m.first);
  return keys;
}

} // namespace scpdyn::test
