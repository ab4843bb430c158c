#pragma once
/// \file MaterialSpec.hpp
/// \brief A material as the deck gives it, and its check. The material room owns what a
/// `materials[]` entry may hold: the parser (input/DeckParser.cpp) reads an entry's keys into a
/// MaterialSpec and calls validateMaterialSpec(); which keys each model and eos take, their
/// checks and the conversion to MaterialParams are in MaterialLibrary.cpp.
#include "core/InputError.hpp"
#include "core/Types.hpp"

#include <map>
#include <string>

namespace scpdyn
{

/// \brief Model and eos names plus numeric parameters, as written in the deck.
struct MaterialSpec
{
  std::string name;
  std::string model = "elastic";      ///< elastic | elastic_plastic | ... (docs/input.md)
  std::string eos = "linear";         ///< linear | mie_gruneisen | ...
  std::map<std::string, Real> values; ///< every numeric key of the material (and of its eos:
                                      ///< eos keys are stored as "eos.<key>")
  std::map<std::string, int> lines;   ///< YAML line of each key, for error messages
  int index = 0;                      ///< position in the deck's materials list
  int line = 0;
};

/// \brief Check a material's model, eos and keys (unknown, missing, non-physical values);
/// throws InputError naming `materials[i].<key>` and the YAML line.
void validateMaterialSpec(const MaterialSpec &spec);

} // namespace scpdyn
