// appendMesh shifts node, element and part ids of the appended mesh's parts and sets.
#include "mesh/MeshGenerators.hpp"
#include "mesh/MeshOps.hpp"

#include <gtest/gtest.h>

using namespace scpdyn;

TEST(AppendMesh, ShiftsNodeElementAndPartIds)
{
  HostMesh a;
  appendBlock(a, "first", ElementType::Quad4, {2, 2, 1}, {0, 0, 0}, {1, 1, 0});
  HostMesh b;
  appendBlock(b, "second", ElementType::Quad4, {3, 1, 1}, {2, 0, 0}, {3, 1, 0});
  const auto faces_b = extractExternalFaces(b);
  b.face_sets["all_b"] = faces_b;
  b.node_sets["corner"] = {0};
  const Index nodes_a = a.numNodes(), elems_a = a.numElements();
  appendMesh(a, b, "g.");
  ASSERT_EQ(a.parts.size(), 2u);
  EXPECT_EQ(a.parts[1].name, "g.second");
  EXPECT_EQ(a.numNodes(), nodes_a + b.numNodes());
  EXPECT_EQ(a.node_sets["corner"][0], nodes_a);
  // the shifted face set equals the external faces of the appended part in the whole mesh
  const auto all = facesOfParts(extractExternalFaces(a), {1});
  const auto &set = a.face_sets["all_b"];
  ASSERT_EQ(set.size(), all.size());
  for (size_t k = 0; k < set.size(); ++k)
  {
    EXPECT_EQ(set[k].element, faces_b[k].element + elems_a);
    EXPECT_EQ(set[k].part, 1);
    for (int i = 0; i < set[k].num_nodes; ++i)
      EXPECT_EQ(set[k].nodes[size_t(i)], faces_b[k].nodes[size_t(i)] + nodes_a);
  }
}
