#pragma once
/// \file Preflight.hpp
/// \brief What a run is about to do, told before its first cycle (a block on stdout, and
/// summary.json's `preflight`): every deck part's elements and mass, with the sub-parts its
/// mesh made (a brick wall's bricks, a gmsh file's physical groups), the first time step and
/// what set it, the run's estimate (Outputs.hpp) and the resident memory after set-up.
#include "driver/Outputs.hpp"
#include "driver/Solver.hpp"
#include "io/TextOutput.hpp"

#include <string>
#include <vector>

namespace scpdyn
{

/// \brief Elements and mass of a part, over all ranks.
struct PartTally
{
  std::string name;
  long elements = 0;
  double mass = 0; ///< [kg] in Preflight::mass_unit
};

/// \brief A deck part (parts[] entry) and the mesh parts it made.
struct DeckPartTally : PartTally
{
  std::string material;
  /// The mesh parts, in mesh order; empty when the mesh made one part of the deck part's own
  /// name (a block).
  std::vector<PartTally> sub_parts;
};

struct Preflight
{
  std::vector<DeckPartTally> parts;
  long elements = 0;               ///< of all parts
  double mass = 0;                 ///< of all parts [kg] in mass_unit
  std::string mass_unit;           ///< "kg", "kg per metre (plane strain)", ...
  Solver::SmallestStep first_step; ///< the first time step and what set it
  RunEstimate estimate;
  int ranks = 1;
  double resident_bytes = 0;         ///< summed over the ranks; 0 where unknown
  double resident_bytes_largest = 0; ///< of the rank that holds the most
};

/// \brief The pre-flight of `solver`'s run with its `estimate` (collective: every rank takes
/// part in the sums and gets the same result).
Preflight preflight(const Solver &solver, const RunEstimate &estimate);

/// \brief The block printed before the first cycle: one line per deck part, its sub-parts on
/// lines of their own when there are a few and grouped on the part's line when there are
/// more, then the totals, the first step, the estimate and the memory.
std::string preflightText(const Preflight &p);

/// \brief summary.json's `preflight`, with every sub-part.
JsonObject preflightJson(const Preflight &p);

/// \brief This process's resident memory (VmRSS of /proc/self/status) [bytes], 0 where the
/// file does not say.
double residentBytes();

/// \brief The unit of the model's masses: kg in 3D, per metre in plane strain, per radian
/// axisymmetric, per square metre of cross-section in 1D.
std::string massUnit(const Deck &deck);

} // namespace scpdyn
