// What the set-up refuses, and how it says so: every message names the deck key, and the cases a
// new user meets (a negative radius, a typo in a gmsh set name, a mesh too large for the index or
// for the machine, a gauge far outside the mesh, a deck set named like a gmsh group) say what is
// wrong rather than a consequence of it.
#include "TestUtil.hpp"
#include "core/InputError.hpp"
#include "driver/Solver.hpp"

#include <gtest/gtest.h>

#include <fstream>

using namespace scpdyn;
using namespace scpdyn::test;

namespace
{

const std::string kRock = "materials:\n  - {name: rock, model: elastic, density: 2600, "
                          "youngs_modulus: 40.0e9, poisson_ratio: 0.25}\n";

/// The InputError message of setting up the deck, or "accepted".
std::string setupError(const std::string &yaml, const std::string &name)
{
  return inputErrorOf(
      [&] { Solver s(parseDeckString(yaml, writeWorkFile(name + ".yaml", yaml))); });
}

/// Two quads as gmsh physical surfaces 'left' and 'right' sharing the edge x = 1, and a
/// physical line 'bottom' along y = 0.
std::string twoSurfaceMesh()
{
  const std::string path = std::string(SCPDYN_TEST_WORKDIR) + "/two_surfaces.msh";
  std::ofstream(path) << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
                         "$PhysicalNames\n3\n1 10 \"bottom\"\n2 1 \"left\"\n2 2 \"right\"\n"
                         "$EndPhysicalNames\n"
                         "$Entities\n0 1 2 0\n1 0 0 0 2 0 0 1 10 0\n1 0 0 0 1 1 0 1 1 0\n"
                         "2 1 0 0 2 1 0 1 2 0\n$EndEntities\n"
                         "$Nodes\n1 6 1 6\n2 1 0 6\n1\n2\n3\n4\n5\n6\n"
                         "0 0 0\n1 0 0\n2 0 0\n0 1 0\n1 1 0\n2 1 0\n$EndNodes\n"
                         "$Elements\n3 4 1 4\n2 1 3 1\n1 1 2 5 4\n2 2 3 1\n2 2 3 6 5\n"
                         "1 1 1 2\n3 1 2\n4 2 3\n$EndElements\n";
  return path;
}

std::string gmshDeck(const std::string &extra)
{
  return "dimension: 2\ntime: {end: 1.0e-6}\n" + kRock +
         "parts:\n  - {name: m, material: rock, mesh: {type: gmsh, file: " + twoSurfaceMesh() +
         "}}\n" + extra;
}

} // namespace

TEST(SetupChecks, NegativeRadiusInAxisymmetryIsNamed)
{
  const std::string e = setupError(
      "dimension: 2\ngeometry: axisymmetric\ntime: {end: 1.0e-6}\n" + kRock +
          "parts:\n  - {name: ring, material: rock, mesh: {elements: [2, 2], origin: [-0.05, "
          "0], size: [0.1, 0.1]}}\n",
      "negative_radius");
  EXPECT_NE(e.find("parts[0] ('ring'): node 0 is at radius x = -0.05 < 0"), std::string::npos) << e;
  EXPECT_EQ(e.find("zero mass"), std::string::npos) << e;
}

// A gmsh set name is checked after meshing: the message has the deck line and a suggestion.
TEST(SetupChecks, GmshSetTypoHasLineAndSuggestion)
{
  const std::string e = setupError(
      gmshDeck("boundary_conditions:\n  - {type: velocity, node_set: botom, component: y, "
               "value: 0}\n"),
      "gmsh_set_typo");
  EXPECT_NE(e.find("boundary_conditions[0].node_set (line 8): unknown node set 'botom'; did "
                   "you mean 'bottom'?"),
            std::string::npos)
      << e;
}

TEST(SetupChecks, DeckSetNamedLikeAGmshGroupIsRefused)
{
  const std::string e =
      setupError(gmshDeck("node_sets:\n  - {name: bottom, box: {min: [0, 0], max: [2, 0]}}\n"),
                 "gmsh_set_clash");
  EXPECT_NE(e.find("node_sets[0].name: 'bottom' is also a physical group of a gmsh mesh"),
            std::string::npos)
      << e;
}

// Sub-parts the meshing makes are valid references in node sets and contact surfaces.
TEST(SetupChecks, SubPartNamesAreAccepted)
{
  const std::string deck = gmshDeck("node_sets:\n  - {name: l, part: m.left}\n"
                                    "contact:\n  surfaces:\n    - {name: j, part: m.right, "
                                    "option: sticky}\n");
  Solver s(parseDeckString(deck, "sub_parts.yaml"));
  EXPECT_EQ(s.model().node_sets.at("l").size(), 4u);
  const std::string wall =
      "dimension: 2\ntime: {end: 1.0e-6}\n" + kRock +
      "parts:\n  - {name: wall, material: rock, mesh: {type: brick_wall, elements: [1, 1], "
      "brick_size: [0.2, 0.1], count: [2, 2], stagger: 0.5}}\n"
      "node_sets:\n  - {name: one, part: wall.0.0}\n";
  Solver w(parseDeckString(wall, "sub_parts_wall.yaml"));
  EXPECT_EQ(w.model().node_sets.at("one").size(), 4u);
}

TEST(SetupChecks, MeshBeyondTheIndexOrTheMemoryIsRefusedFirst)
{
  const std::string base = "dimension: 3\ntime: {end: 1.0e-6}\n" + kRock +
                           "parts:\n  - {name: b, material: rock, mesh: {element: hex8, "
                           "elements: ELEMENTS, size: [1, 1, 1]}}\n";
  std::string deck = base;
  deck.replace(deck.find("ELEMENTS"), 8, "[2147483647, 1, 1]");
  std::string e = setupError(deck, "index_overflow");
  EXPECT_NE(e.find("beyond the index limit"), std::string::npos) << e;
  deck = base;
  deck.replace(deck.find("ELEMENTS"), 8, "[2000, 2000, 2000]"); // 8e9 hexes: ~8 TB
  e = setupError(deck, "too_big");
  EXPECT_NE(e.find("beyond the index limit"), std::string::npos) << e;
  deck = base;
  deck.replace(deck.find("ELEMENTS"), 8, "[1200, 1200, 1000]"); // 1.44e9 hexes, ~1.4 TB
  e = setupError(deck, "too_big_memory");
  EXPECT_NE(e.find("GiB per rank to set up, more than 80 % of this machine's"), std::string::npos)
      << e;
}

TEST(SetupChecks, GaugeFarOutsideTheMeshIsRefused)
{
  const std::string e = setupError(
      "dimension: 2\ntime: {end: 1.0e-6}\n" + kRock +
          "parts:\n  - {name: b, material: rock, mesh: {elements: [2, 2], size: [0.1, 0.1]}}\n"
          "gauges:\n  - {name: far, point: [1.0e6, 0.05], kind: node, quantities: [vx]}\n",
      "gauge_far");
  EXPECT_NE(e.find("gauges[0].point: coordinate 0 = 1e+06 m lies outside the meshes"),
            std::string::npos)
      << e;
}
