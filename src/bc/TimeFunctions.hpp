#pragma once
/// \file TimeFunctions.hpp
/// \brief Piecewise-linear time functions of the deck, evaluated on the host once per cycle.
#include "input/Deck.hpp"

namespace scpdyn
{

/// \brief Value of f at time t: linear between points, constant beyond the ends.
Real evaluate(const TimeFunction &f, Real t);

/// \brief Index of the function called `name` in `functions`, or -1 when name is empty.
/// Throws InputError naming `key` when the name is unknown.
int findFunction(const std::vector<TimeFunction> &functions, const std::string &name,
                 const std::string &key);

} // namespace scpdyn
