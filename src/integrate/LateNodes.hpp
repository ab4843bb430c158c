#pragma once
/// \file LateNodes.hpp
/// \brief The nodes that something after step 6 touches (reads or writes their forces or
/// velocities before step 12 uses them). The node sweep (NodeSweep.hpp) integrates a node
/// inside step 6, right after its last element, unless it is late: so every room that acts on
/// nodes between step 6 and step 12 declares its nodes at set-up, and the sweep takes the
/// union of the declarations. The rooms that do so today: contact (its face nodes), face and
/// node loads (bc/), the shared-node exchange of a decomposed run (parallel/). A new writer of
/// nodal data (erosion, rigid grounds, settling, ...) adds its own declaration where set-up
/// builds the sweep (Solver::setupNodeSweep()).
///
/// The rule is guarded at run time by the check mode (SCPDYN_CHECK_NODE_SWEEP=1 in the
/// environment, which the test suite sets): step 12 then verifies that every early node comes
/// to it as step 6 left it (earlyNodeWrittenLate()), and stops the run naming the node when a
/// room wrote to it without declaring it.
#include "core/Fields.hpp"

#include <string>
#include <vector>

namespace scpdyn
{

struct NodeSweep;

class LateNodes
{
public:
  explicit LateNodes(Index num_nodes) : _mark(static_cast<size_t>(num_nodes), 0) {}

  /// \brief `writer` (a room's name, for messages) touches `nodes` after step 6; ids outside
  /// [0, num_nodes) (ghost nodes, padding) are ignored.
  void declare(const std::string &writer, const std::vector<Index> &nodes);
  /// \brief The same for a device list.
  void declare(const std::string &writer, const IndexView &nodes);
  /// \brief The same for the nodes of a per-node flag (nonzero: touched).
  void declareFlagged(const std::string &writer, const std::vector<char> &flag);

  /// \brief Per node, nonzero if any room declared it (makeNodeSweep()'s `late`).
  const std::vector<char> &mask() const { return _mark; }
  /// \brief The rooms that declared something, in order.
  const std::vector<std::string> &writers() const { return _writers; }

private:
  std::vector<char> _mark;
  std::vector<std::string> _writers;
};

/// \brief The state of the early nodes at the end of step 6, for the check mode.
struct EarlyNodeSnapshot
{
  VectorView x, v; ///< copies of x and v after step 6 (empty: no check)
};

/// \brief True when the check mode is on (SCPDYN_CHECK_NODE_SWEEP set and not "0").
bool nodeSweepCheckEnabled();

/// \brief Check mode, end of step 6: copies of x and v (allocated once).
void snapshotEarlyNodes(const NodeFields &nodes, EarlyNodeSnapshot &snap);

/// \brief Check mode, before step 12: the first early node of `sweep` that was written after
/// step 6 (-1 if none). Step 6 left an early node integrated and reset for the next cycle:
/// x and v as in `snap`, f_int = 0, f_ext = m g (with `loads`, g the next gravity) or 0, and
/// f_contact = 0. `what` says which field differs.
Index earlyNodeWrittenLate(const NodeSweep &sweep, const NodeFields &nodes,
                           const EarlyNodeSnapshot &snap, bool loads, const Real g[3],
                           std::string *what = nullptr);

} // namespace scpdyn
