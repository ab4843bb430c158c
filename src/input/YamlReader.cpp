#include "input/YamlReader.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>

namespace scpdyn
{
namespace input_impl
{
namespace
{

int lineOf(const YAML::Node &node, int fallback)
{
  const YAML::Mark mark = node.Mark();
  return mark.is_null() ? fallback : mark.line + 1;
}

// yaml-cpp tags plain scalars "?" and quoted ones "!": a quoted "1.0" is a string, not a number.
bool isQuoted(const YAML::Node &node) { return node.Tag() == "!"; }

std::string describe(const YAML::Node &node)
{
  if (!node.IsDefined() || node.IsNull())
    return "an empty value";
  if (node.IsSequence())
    return "a list";
  if (node.IsMap())
    return "a mapping";
  return isQuoted(node) ? "the quoted string \"" + node.Scalar() + "\"" : "'" + node.Scalar() + "'";
}

std::string childPath(const std::string &parent, const std::string &key)
{
  return parent.empty() ? key : parent + "." + key;
}

} // namespace

std::string joined(const std::vector<std::string> &words)
{
  std::string out;
  for (const auto &w : words)
    out += (out.empty() ? "" : ", ") + w;
  return out;
}

YamlValue::YamlValue(YAML::Node node, std::string path, int line)
    : _node(std::move(node)), _path(std::move(path)), _line(line)
{
}

std::string YamlValue::text() const { return _node.IsScalar() ? _node.Scalar() : describe(_node); }

void YamlValue::fail(const std::string &what) const
{
  std::string where = _path.empty() ? "<document>" : _path;
  if (_line > 0)
    where += " (line " + std::to_string(_line) + ")";
  throw InputError(where + ": " + what);
}

Real YamlValue::real() const
{
  if (!_node.IsScalar() || isQuoted(_node))
    fail("expected a number, got " + describe(_node));
  const std::string &s = _node.Scalar();
  char *end = nullptr;
  errno = 0;
  const double x = std::strtod(s.c_str(), &end);
  if (s.empty() || end != s.c_str() + s.size())
    fail("expected a number, got " + describe(_node));
  if (!std::isfinite(x) || (errno == ERANGE && std::fabs(x) > 1))
    fail("expected a finite number, got '" + s + "' (beyond +-1.8e308)");
  if (errno == ERANGE && x == 0) // a subnormal (1e-320) is a number; only a total underflow is not
    fail("'" + s + "' is too small for a double (below 4.9e-324): write 0 if zero is meant");
  return x;
}

long YamlValue::integer() const
{
  if (!_node.IsScalar() || isQuoted(_node))
    fail("expected an integer, got " + describe(_node));
  const std::string &s = _node.Scalar();
  char *end = nullptr;
  errno = 0;
  const long n = std::strtol(s.c_str(), &end, 10);
  if (s.empty() || end != s.c_str() + s.size())
    fail("expected an integer, got " + describe(_node));
  if (errno == ERANGE || n > std::numeric_limits<int>::max() || n < std::numeric_limits<int>::min())
    fail("integer '" + s + "' is out of range");
  return n;
}

bool YamlValue::boolean() const
{
  bool b = false;
  if (!_node.IsScalar() || isQuoted(_node) || !YAML::convert<bool>::decode(_node, b))
    fail("expected true or false, got " + describe(_node));
  return b;
}

std::string YamlValue::string() const
{
  if (!_node.IsScalar())
    fail("expected a string, got " + describe(_node));
  if (_node.Scalar().empty())
    fail("must not be an empty string");
  return _node.Scalar();
}

std::string YamlValue::choice(const std::vector<std::string> &allowed) const
{
  const std::string s = string();
  if (std::find(allowed.begin(), allowed.end(), s) == allowed.end())
    fail("unknown value '" + s + "'" + suggestion(s, allowed));
  return s;
}

std::vector<YamlValue> YamlValue::list(std::size_t min_size) const
{
  std::vector<YamlValue> items;
  if (isNull() && min_size == 0)
    return items;
  if (!_node.IsSequence())
    fail("expected a list, got " + describe(_node));
  for (std::size_t i = 0; i < _node.size(); ++i)
    items.emplace_back(_node[i], _path + "[" + std::to_string(i) + "]", lineOf(_node[i], _line));
  if (items.size() < min_size)
    fail(min_size == 1 ? std::string("must be a non-empty list")
                       : "expected at least " + std::to_string(min_size) + " entries, got " +
                             std::to_string(items.size()));
  return items;
}

std::array<Real, 3> YamlValue::realVector(int n) const
{
  if (!_node.IsSequence() || static_cast<int>(_node.size()) != n)
    fail("expected a list of " + std::to_string(n) + " number" + (n > 1 ? "s" : "") +
         " (one per dimension), got " +
         (_node.IsSequence() ? std::to_string(_node.size()) + " entries" : describe(_node)));
  std::array<Real, 3> v{{0, 0, 0}};
  const auto items = list();
  for (int i = 0; i < n; ++i)
    v[i] = items[i].real();
  return v;
}

std::array<int, 3> YamlValue::intVector(int n, int min_value, int fill) const
{
  if (!_node.IsSequence() || static_cast<int>(_node.size()) != n)
    fail("expected a list of " + std::to_string(n) + " integer" + (n > 1 ? "s" : "") +
         " (one per dimension), got " +
         (_node.IsSequence() ? std::to_string(_node.size()) + " entries" : describe(_node)));
  std::array<int, 3> v{{fill, fill, fill}};
  const auto items = list();
  for (int i = 0; i < n; ++i)
  {
    const long k = items[i].integer();
    if (k < min_value)
      items[i].fail("must be >= " + std::to_string(min_value) + ", got " + items[i].text());
    v[i] = static_cast<int>(k);
  }
  return v;
}

YamlMap YamlValue::map(const std::vector<std::string> &known) const
{
  return YamlMap(*this, &known);
}

YamlMap YamlValue::openMap() const { return YamlMap(*this, nullptr); }

YamlMap::YamlMap(const YamlValue &owner, const std::vector<std::string> *known) : _owner(owner)
{
  const YAML::Node &node = owner.node();
  if (owner.isNull())
    return;
  if (!node.IsMap())
    owner.fail("expected a mapping of keys" + (known ? " (" + joined(*known) + ")" : "") +
               ", got " + describe(node));
  for (auto it = node.begin(); it != node.end(); ++it)
  {
    const int line = lineOf(it->first, owner.line());
    if (!it->first.IsScalar())
      YamlValue(it->first, owner.path(), line).fail("keys must be plain names");
    const std::string key = it->first.Scalar();
    const YamlValue here(it->second, childPath(owner.path(), key), line);
    for (const auto &e : _entries)
      if (e.key == key)
        here.fail("duplicate key '" + key + "' (first given on line " + std::to_string(e.line) +
                  ")");
    if (known && std::find(known->begin(), known->end(), key) == known->end())
      here.fail("unknown key '" + key + "'" + suggestion(key, *known));
    _entries.push_back({key, it->second, line});
  }
}

bool YamlMap::has(const std::string &key) const
{
  return std::any_of(_entries.begin(), _entries.end(),
                     [&](const Entry &e) { return e.key == key; });
}

YamlValue YamlMap::operator[](const std::string &key) const
{
  for (const auto &e : _entries)
    if (e.key == key)
      return YamlValue(e.value, childPath(_owner.path(), key), e.line);
  missing(key);
}

void YamlMap::missing(const std::string &key) const
{
  YamlValue(YAML::Node(), childPath(_owner.path(), key), _owner.line())
      .fail("required key is missing");
}

std::string YamlMap::exactlyOne(const std::vector<std::string> &keys) const
{
  std::vector<std::string> present;
  for (const auto &k : keys)
    if (has(k))
      present.push_back(k);
  if (present.size() != 1)
    _owner.fail("give exactly one of " + joined(keys) +
                (present.empty() ? " (none given)" : " (got " + joined(present) + ")"));
  return present[0];
}

Real YamlMap::real(const std::string &key, Real fallback) const
{
  return has(key) ? (*this)[key].real() : fallback;
}

long YamlMap::integer(const std::string &key, long fallback) const
{
  return has(key) ? (*this)[key].integer() : fallback;
}

bool YamlMap::boolean(const std::string &key, bool fallback) const
{
  return has(key) ? (*this)[key].boolean() : fallback;
}

std::string YamlMap::string(const std::string &key, const std::string &fallback) const
{
  return has(key) ? (*this)[key].string() : fallback;
}

std::string YamlMap::choice(const std::string &key, const std::vector<std::string> &allowed,
                            const std::string &fallback) const
{
  return has(key) ? (*this)[key].choice(allowed) : fallback;
}

int editDistance(const std::string &a, const std::string &b)
{
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::vector<int>> d(n + 1, std::vector<int>(m + 1, 0));
  for (std::size_t i = 0; i <= n; ++i)
    d[i][0] = static_cast<int>(i);
  for (std::size_t j = 0; j <= m; ++j)
    d[0][j] = static_cast<int>(j);
  for (std::size_t i = 1; i <= n; ++i)
    for (std::size_t j = 1; j <= m; ++j)
    {
      const int cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[n][m];
}

std::string suggestion(const std::string &word, const std::vector<std::string> &candidates)
{
  int best = 3;
  std::string closest;
  for (const auto &c : candidates)
  {
    const int d = editDistance(word, c);
    if (d < best)
    {
      best = d;
      closest = c;
    }
  }
  if (!closest.empty())
    return "; did you mean '" + closest + "'?";
  return " (expected one of: " + joined(candidates) + ")";
}

} // namespace input_impl
} // namespace scpdyn
