#pragma once
/// \file DeckSections.hpp
/// \brief Internal to the deck parser: the section readers split across DeckParser.cpp and
/// DeckSections.cpp, and the small checks they share. Not for use outside src/input/.
#include "input/Deck.hpp"
#include "input/YamlReader.hpp"

#include <filesystem>
#include <initializer_list>
#include <map>
#include <string>
#include <vector>

namespace scpdyn
{
namespace input_impl
{

/// \brief Names defined so far, each with its YAML line (for references and duplicates).
struct DeckNames
{
  std::map<std::string, int> functions, materials, parts, node_sets, face_sets;
};

bool isPositive(Real x);
bool isNonNegative(Real x);

/// \brief Optional real with a range check (`ok` may be null); `expected` reads "> 0" etc.
Real readReal(const YamlMap &m, const std::string &key, Real fallback, bool (*ok)(Real),
              const char *expected);
/// \brief Required real with a range check.
Real requireReal(const YamlMap &m, const std::string &key, bool (*ok)(Real), const char *expected);
/// \brief Record a name; throws when it was already used in the same list.
void claimName(std::map<std::string, int> &seen, const YamlValue &v, const std::string &name);
/// \brief Throw unless `name` is in `defined` (suggesting the closest defined name).
void checkReference(const YamlValue &v, const std::string &name, const std::string &what,
                    const std::map<std::string, int> &defined);
/// \brief Throw unless `part` names a defined part or, ending in '*', is the prefix of one.
void checkPartReference(const YamlValue &v, const std::string &part, const DeckNames &names);
/// \brief Throw for a key of `m` that is not in `allowed` (for keys that depend on a type).
void restrictKeys(const YamlMap &m, const std::vector<std::string> &allowed,
                  const std::string &context);

/// \brief The deck words of `values`, in their order (the order messages list them in).
template <class E>
std::vector<std::string> deckNames(std::initializer_list<E> values)
{
  std::vector<std::string> words;
  for (E e : values)
    words.push_back(deckName(e));
  return words;
}
/// \brief The value of `values` whose deck word is `word` (a word choice() has accepted).
template <class E>
E valueNamed(const std::string &word, std::initializer_list<E> values)
{
  for (E e : values)
    if (word == deckName(e))
      return e;
  return *values.begin();
}
/// \brief A required choice: the value `v` names, one of `values`.
template <class E>
E choiceOf(const YamlValue &v, std::initializer_list<E> values)
{
  return valueNamed(v.choice(deckNames(values)), values);
}
/// \brief An optional choice: the value key `key` names, or `fallback` without the key.
template <class E>
E readChoice(const YamlMap &m, const std::string &key, std::initializer_list<E> values, E fallback)
{
  return m.has(key) ? choiceOf(m[key], values) : fallback;
}

/// \brief parts[] (with meshes); gmsh files are resolved against `deck_dir`.
void parseParts(const YamlMap &root, Deck &deck, DeckNames &names,
                const std::filesystem::path &deck_dir);
/// \brief gravity: a vector, or {value: vector, function: name}; after the functions.
void parseGravity(const YamlMap &root, Deck &deck, const DeckNames &names);
/// \brief settling: {end, damping}; after time and gravity.
void parseSettling(const YamlMap &root, Deck &deck);
/// \brief node_sets[], face_sets[], initial_conditions[], boundary_conditions[].
void parseSetsAndConditions(const YamlMap &root, Deck &deck, DeckNames &names);
/// \brief gauges[].
void parseGauges(const YamlMap &root, Deck &deck);
/// \brief contact (DeckContact.cpp); after the parts and sets it refers to.
void parseContact(const YamlMap &root, Deck &deck, const DeckNames &names);

} // namespace input_impl
} // namespace scpdyn
