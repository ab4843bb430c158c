#pragma once
#include "core/RealText.hpp"
/// \file YamlReader.hpp
/// \brief Checked access to a yaml-cpp tree for the deck parser: every value knows its key path
/// (`parts[1].mesh.elements`) and 1-based YAML line, and every wrong type, missing key or
/// unknown key becomes an InputError "<key path> (line N): <what>" (the parser prepends the
/// deck path). Host-only.
#include "input/Deck.hpp"

#include <yaml-cpp/yaml.h>

#include <array>
#include <string>
#include <vector>

namespace scpdyn
{
namespace input_impl
{

class YamlMap;

/// \brief One value of the deck with its key path and line.
class YamlValue
{
public:
  YamlValue(YAML::Node node, std::string path, int line);

  const YAML::Node &node() const { return _node; }
  const std::string &path() const { return _path; }
  int line() const { return _line; }
  bool isNull() const { return !_node.IsDefined() || _node.IsNull(); }
  /// \brief The scalar as written (for messages).
  std::string text() const;

  /// \brief Throw InputError "<path> (line N): <what>".
  [[noreturn]] void fail(const std::string &what) const;

  Real real() const;          ///< finite number (plain scalar)
  long integer() const;       ///< integer (plain scalar, no fraction or exponent)
  bool boolean() const;       ///< true | false
  std::string string() const; ///< any non-empty scalar
  /// \brief A string that must be one of `allowed` (suggests the closest otherwise).
  std::string choice(const std::vector<std::string> &allowed) const;

  /// \brief The items of a list; a null value is an empty list unless `min_size` > 0.
  std::vector<YamlValue> list(std::size_t min_size = 0) const;
  /// \brief A list of exactly `n` reals (n <= 3), unused components 0.
  std::array<Real, 3> realVector(int n) const;
  /// \brief A list of exactly `n` integers >= `min_value` (n <= 3), unused components `fill`.
  std::array<int, 3> intVector(int n, int min_value, int fill) const;
  /// \brief A mapping whose keys must all be in `known` (a null value is an empty mapping).
  YamlMap map(const std::vector<std::string> &known) const;
  /// \brief A mapping with any keys (the caller checks them).
  YamlMap openMap() const;

private:
  YAML::Node _node;
  std::string _path;
  int _line;
};

/// \brief A checked mapping: keys unique, in order, each with its line.
class YamlMap
{
public:
  struct Entry
  {
    std::string key;
    YAML::Node value;
    int line;
  };

  YamlMap(const YamlValue &owner, const std::vector<std::string> *known);

  bool has(const std::string &key) const;
  /// \brief The value of a required key (missing -> InputError at the map's line).
  YamlValue operator[](const std::string &key) const;
  /// \brief Throw for the key missing from this map.
  [[noreturn]] void missing(const std::string &key) const;
  /// \brief Throw unless exactly one of the keys is present; returns its name.
  std::string exactlyOne(const std::vector<std::string> &keys) const;
  const std::vector<Entry> &entries() const { return _entries; }
  const YamlValue &owner() const { return _owner; }

  Real real(const std::string &key, Real fallback) const;
  long integer(const std::string &key, long fallback) const;
  bool boolean(const std::string &key, bool fallback) const;
  std::string string(const std::string &key, const std::string &fallback) const;
  std::string choice(const std::string &key, const std::vector<std::string> &allowed,
                     const std::string &fallback) const;

private:
  YamlValue _owner;
  std::vector<Entry> _entries;
};

/// \brief Optimal-string-alignment edit distance (insertions, deletions, substitutions,
/// adjacent transpositions).
int editDistance(const std::string &a, const std::string &b);
/// \brief "; did you mean 'x'?" for the closest candidate within distance 2, else
/// " (expected one of: a, b, c)".
std::string suggestion(const std::string &word, const std::vector<std::string> &candidates);
/// \brief "a, b, c".
std::string joined(const std::vector<std::string> &words);

} // namespace input_impl
} // namespace scpdyn
