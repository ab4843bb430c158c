// The fused step 12 (integrate/NodeSweep.hpp) integrates a node inside step 6 unless a room
// that acts on nodes after step 6 declared it (integrate/LateNodes.hpp). The check mode must
// catch a writer that did not declare its nodes: here the nodal forces of step 11, run with a
// sweep built from every declaration but theirs.
#include "driver/Solver.hpp"
#include "input/Deck.hpp"
#include "integrate/LateNodes.hpp"
#include "integrate/NodeSweep.hpp"
#include "integrate/NodeUpdate.hpp"

#include <gtest/gtest.h>

namespace scpdyn
{
namespace
{

const char *kDeck = R"(title: late writer
dimension: 3
time: {end: 1.0, courant: 0.5}
gravity: [0.0, 0.0, -9.81]
materials:
  - {name: steel, model: elastic, density: 7850, youngs_modulus: 200.0e9, poisson_ratio: 0.3}
parts:
  - name: a
    material: steel
    mesh: {type: block, element: hex8, elements: [6, 5, 4], size: [0.6, 0.5, 0.4]}
    initial_velocity: [1.0, 2.0, 0.0]
node_sets:
  - {name: corner, box: {min: [0.6, 0.5, 0.4], max: [0.6, 0.5, 0.4]}}
boundary_conditions:
  - {type: force, node_set: corner, value: [0.0, 0.0, -100.0]}
)";

/// Step 6 with a sweep built from `late`, then step 11 (the nodal forces) and the check.
Index writtenLate(Solver &s, const LateNodes &late, std::string *what)
{
  const NodeFields &n = s.nodes();
  BoundaryConditions bc = s.boundaryConditions(); // its Views are the solver's
  updateLoadValues(bc, s.time() + 0.5 * s.dt());  // step 10's values of the nodal forces
  NodeSweep sweep = makeNodeSweep(s.elements(), s.groups(), n, 1, late.mask());
  const Real *g = s.deck().gravity.data();
  sweep.node = nodeIntegrator(n, bc.velocity_current, s.dt(), IndexView(), g);
  sweep.loads = true;
  ElementControls ctl = s.elementControls();
  ctl.gather = false;
  zeroForces(n, g, true);
  const NodeCorners no_corners;
  computeElementForces(s.groups(), ctl, n, s.elements(), s.materials(), no_corners, sweep);
  EarlyNodeSnapshot snap;
  snapshotEarlyNodes(n, snap);
  applyNodeForces(bc, n); // step 11 writes f_ext of the corner node
  return earlyNodeWrittenLate(sweep, n, snap, true, g, what);
}

TEST(LateNodes, CheckModeCatchesAWriterThatDidNotDeclareItsNodes)
{
  Solver s(parseDeckString(kDeck, "late.yaml"));
  ASSERT_EQ(s.boundaryConditions().force_node.extent(0), 1u);
  const Index corner =
      Kokkos::create_mirror_view_and_copy(HostSpace(), s.boundaryConditions().force_node)(0);

  LateNodes without(s.nodes().count); // every room's declaration but the node forces'
  std::string what;
  EXPECT_EQ(writtenLate(s, without, &what), corner) << "the undeclared force went unnoticed";
  EXPECT_NE(what.find("f_ext"), std::string::npos) << what;

  Solver t(parseDeckString(kDeck, "late.yaml"));
  LateNodes with(t.nodes().count);
  declareLateNodes(t.boundaryConditions(), with);
  EXPECT_EQ(writtenLate(t, with, nullptr), -1) << "a declared writer was reported";
}

TEST(LateNodes, TheSolverDeclaresEveryWriterItRuns)
{
  // the suite runs with the check mode on: a whole run of a deck with a nodal force, face
  // pressure, gravity and a velocity constraint must not stop
  ASSERT_TRUE(nodeSweepCheckEnabled());
  std::string deck = kDeck;
  deck += R"(  - {type: pressure, face_set: top, value: 1.0e5}
  - {type: velocity, node_set: left, component: x, value: 0.0}
face_sets:
  - {name: top, box: {min: [0, 0, 0.4], max: [0.6, 0.5, 0.4]}}
)";
  deck.replace(deck.find("node_sets:\n"), 11,
               "node_sets:\n  - {name: left, box: {min: [0, 0, 0], max: [0, 0.5, 0.4]}}\n");
  Solver s(parseDeckString(deck, "late_all.yaml"));
  ASSERT_TRUE(s.nodeSweep().active);
  ASSERT_GT(s.nodeSweep().early_nodes, 0);
  for (int c = 0; c < 20; ++c)
    EXPECT_NO_THROW(s.cycle());
}

TEST(LateNodes, DeclarationsAreUnitedAndIgnoreGhostIds)
{
  LateNodes late(5);
  late.declare("a", std::vector<Index>{0, 3, 7, -1});
  late.declareFlagged("b", {0, 1, 0, 0, 0, 1});
  const std::vector<char> expect = {1, 1, 0, 1, 0};
  EXPECT_EQ(late.mask(), expect);
  EXPECT_EQ(late.writers(), (std::vector<std::string>{"a", "b"}));
}

} // namespace
} // namespace scpdyn
