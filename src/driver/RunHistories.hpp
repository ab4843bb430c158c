#pragma once
/// \file RunHistories.hpp
/// \brief The histories beside history.csv, at its rows (driver/Outputs.hpp): rcforc.csv (the
/// contact force per pair of contact surfaces), spcforc.csv (the reaction of every velocity
/// boundary condition) and matsum.csv (energies and momentum per deck part). Column meanings:
/// docs/input.md, `output`. Decomposed runs: each rank sums what it owns (a CP on the rank of
/// its face 1, a node on its owner) in its local order, and the ranks' sums are added in rank
/// order, so the values agree with the serial run's to round-off.
#include <string>
#include <vector>

namespace scpdyn
{

class Solver;
struct Deck;

/// \brief The columns of the three files (after `time`), from the deck alone; an empty list:
/// the file is not written (no contact surfaces, no velocity boundary conditions).
struct RunHistoryColumns
{
  std::vector<std::string> contact;   ///< rcforc.csv: "a-b:fx1" .. "a-b:fz2" per surface pair
  std::vector<std::string> reactions; ///< spcforc.csv: "<node set>:<x|y|z>" per velocity BC
  std::vector<std::string> parts;     ///< matsum.csv: "<part>:kinetic" .. per deck part
};

RunHistoryColumns runHistoryColumns(const Deck &deck);

class RunHistories
{
public:
  /// \brief Assigns every node to a deck part (collective in a decomposed run).
  explicit RunHistories(const Solver &solver);

  /// \brief The rows of the three files now, in the order of runHistoryColumns(), on every
  /// rank (collective).
  struct Rows
  {
    std::vector<double> contact, reactions, parts;
  };
  Rows rows() const;

private:
  void contactForces(std::vector<double> &out) const;
  void reactions(std::vector<double> &out) const;
  void partSums(std::vector<double> &out) const;

  const Solver &_solver;
  RunHistoryColumns _columns;
  std::vector<int> _node_part; ///< per local node: its deck part, -1 when another rank owns it
};

} // namespace scpdyn
