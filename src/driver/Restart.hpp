#pragma once
/// \file Restart.hpp
/// \brief What ties a restart file to its deck: the hash of the resolved deck without what a
/// restart may change (the deck's path, the output keys, time.end and time.max_cycles).
#include "input/Deck.hpp"

#include <string>

namespace scpdyn
{

std::string restartDeckHash(const Deck &deck);

/// \brief `dir`/restart_<cycle>.h5
std::string restartFileName(const std::string &dir, long cycle);

} // namespace scpdyn
