#pragma once
/// \file InputError.hpp
/// \brief The error of a bad input deck. Every room that checks part of the deck throws it (the
/// parser, the material room for its models' keys, the set-up for what needs the mesh), so it
/// lives below all of them; `what()` names the key path (and line when known). main() prints it
/// and exits with status 2.
#include <stdexcept>

namespace scpdyn
{

struct InputError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

} // namespace scpdyn
