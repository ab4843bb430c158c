// Gmsh 4.1 reader, on meshes the real gmsh writes inside the test.
#include "mesh/GmshReader.hpp"
#include "mesh/MeshOps.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>

using namespace scpdyn;

namespace
{
bool haveGmsh() { return std::system("gmsh --version > /dev/null 2>&1") == 0; }

// Writes <name>.geo into the work directory, meshes it, returns the .msh path.
std::string mesh(const std::string &name, const std::string &geo, int dim,
                 const std::string &format = "msh41", const std::string &extra = "")
{
  const std::string base = std::string(SCPDYN_TEST_WORKDIR) + "/" + name;
  std::ofstream(base + ".geo") << geo;
  const std::string cmd = "gmsh -" + std::to_string(dim) + " " + base + ".geo -format " + format +
                          " " + extra + " -o " + base + ".msh > " + base + ".log 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  return base + ".msh";
}

int partIndex(const HostMesh &m, const std::string &name)
{
  for (int p = 0; p < int(m.parts.size()); ++p)
    if (m.parts[p].name == name)
      return p;
  return -1;
}

std::string errorOf(const std::string &path)
{
  try
  {
    readGmsh41(path);
  }
  catch (const std::runtime_error &e)
  {
    return e.what();
  }
  return "no error";
}

// Two transfinite rectangles [0,2]x[0,1] (4 x 2 cells) and [2,3]x[0,1] (2 x 2) sharing x = 2.
const std::string kTwoRects = R"(
Point(1) = {0, 0, 0}; Point(2) = {2, 0, 0}; Point(3) = {2, 1, 0}; Point(4) = {0, 1, 0};
Point(5) = {3, 0, 0}; Point(6) = {3, 1, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {2, 5}; Line(6) = {5, 6}; Line(7) = {6, 3};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Curve Loop(2) = {-2, 5, 6, 7}; Plane Surface(2) = {2};
Transfinite Curve{1, 3} = 5; Transfinite Curve{2, 4, 5, 6, 7} = 3;
Transfinite Surface{1, 2};
)";
const std::string kQuads = "Recombine Surface{1, 2};\n";

// Surface area vector (2D: outward normal times length) of a face.
std::array<Real, 3> areaVector(const HostMesh &m, const HostFace &f)
{
  auto x = [&](int i) { return m.coords[f.nodes[i]]; };
  if (f.num_nodes == 2)
    return {x(1)[1] - x(0)[1], -(x(1)[0] - x(0)[0]), 0};
  std::array<Real, 3> n{0, 0, 0};
  for (int i = 1; i + 1 < f.num_nodes; ++i)
  {
    Real a[3], b[3];
    for (int k = 0; k < 3; ++k)
      a[k] = x(i)[k] - x(0)[k], b[k] = x(i + 1)[k] - x(0)[k];
    n[0] += 0.5 * (a[1] * b[2] - a[2] * b[1]);
    n[1] += 0.5 * (a[2] * b[0] - a[0] * b[2]);
    n[2] += 0.5 * (a[0] * b[1] - a[1] * b[0]);
  }
  return n;
}
} // namespace

// gmsh writes coordinates with ~1e-12 relative error on transfinite lines; areas and
// volumes therefore match the geometry to 1e-10 relative.
constexpr Real kGeomTol = 1e-10;

TEST(GmshReader, QuadPartsFaceSetsAndNodeSets)
{
  if (!haveGmsh())
    GTEST_SKIP() << "gmsh not on PATH";
  const auto path = mesh("two_rects", kTwoRects + kQuads + R"(
Physical Surface("left") = {1};
Physical Surface(7) = {2};
Physical Curve("bottom") = {1, 5};
Physical Curve("interface") = {2};
Physical Point("corner") = {1};
)",
                         2);
  const HostMesh m = readGmsh41(path);
  EXPECT_EQ(m.dim, 2);
  ASSERT_EQ(m.parts.size(), 2u);
  const int l = partIndex(m, "left"), r = partIndex(m, "physical_7");
  ASSERT_EQ(l, 0);
  ASSERT_EQ(r, 1);
  EXPECT_EQ(m.parts[l].type, ElementType::Quad4);
  EXPECT_EQ(m.parts[l].numElements(), 8);
  EXPECT_EQ(m.parts[r].numElements(), 4);
  EXPECT_EQ(m.numNodes(), 15 + 9); // the 3 nodes on x = 2 are duplicated
  EXPECT_NEAR(meshMeasure(m, l), 2.0, kGeomTol * 2);
  EXPECT_NEAR(meshMeasure(m, r), 1.0, kGeomTol);
  EXPECT_NO_THROW(checkElements(m));

  ASSERT_TRUE(m.face_sets.count("bottom"));
  EXPECT_EQ(m.face_sets.at("bottom").size(), 6u);
  Real length = 0;
  for (const auto &f : m.face_sets.at("bottom"))
  {
    const auto n = areaVector(m, f);
    EXPECT_NEAR(n[0], 0, kGeomTol);
    EXPECT_LT(n[1], 0); // outward is -y
    length -= n[1];
  }
  EXPECT_NEAR(length, 3.0, kGeomTol * 3);
  EXPECT_EQ(m.node_sets.at("bottom").size(), 5u + 3u); // 7 gmsh nodes, (2,0) in both parts
  // the interface is external to both parts: one face from each side, opposite normals
  ASSERT_EQ(m.face_sets.at("interface").size(), 4u);
  Real sx = 0;
  for (const auto &f : m.face_sets.at("interface"))
    sx += areaVector(m, f)[0];
  EXPECT_NEAR(sx, 0, kGeomTol);
  EXPECT_EQ(m.node_sets.at("interface").size(), 6u);
  ASSERT_EQ(m.node_sets.at("corner").size(), 1u);
  const auto &c = m.coords[m.node_sets.at("corner")[0]];
  EXPECT_EQ(c[0] * c[0] + c[1] * c[1], 0.0);
}

TEST(GmshReader, ClockwiseSurfaceAndUnnamedElements)
{
  if (!haveGmsh())
    GTEST_SKIP() << "gmsh not on PATH";
  // Surface 2 is in no physical group; SaveAll writes it (and every curve) anyway. Surface 1
  // is defined clockwise so gmsh's quads come out clockwise and must be flipped.
  std::string geo = kTwoRects;
  geo.replace(geo.find("Curve Loop(1) = {1, 2, 3, 4}"), 28, "Curve Loop(1) = {-4, -3, -2, -1}");
  const auto path = mesh("unnamed", geo + kQuads + R"(
Physical Surface("named") = {1};
Mesh.SaveAll = 1;
)",
                         2);
  const HostMesh m = readGmsh41(path);
  ASSERT_EQ(m.parts.size(), 2u);
  EXPECT_EQ(m.parts[0].name, "named");
  EXPECT_EQ(m.parts[1].name, "unnamed");
  EXPECT_EQ(m.parts[1].numElements(), 4);
  EXPECT_NEAR(meshMeasure(m, 0), 2.0, kGeomTol * 2); // positive after re-orientation
  EXPECT_NO_THROW(checkElements(m));
  EXPECT_TRUE(m.face_sets.empty());
}

TEST(GmshReader, HexExtrusionTwoVolumes)
{
  if (!haveGmsh())
    GTEST_SKIP() << "gmsh not on PATH";
  const auto path = mesh("hex", kTwoRects + kQuads + R"(
out1[] = Extrude {0, 0, 0.5} { Surface{1}; Layers{3}; Recombine; };
out2[] = Extrude {0, 0, 0.5} { Surface{2}; Layers{3}; Recombine; };
Physical Volume("big") = {out1[1]};
Physical Volume("small") = {out2[1]};
Physical Surface("bottom") = {1, 2};
Physical Surface("top") = {out1[0], out2[0]};
)",
                         3);
  const HostMesh m = readGmsh41(path);
  EXPECT_EQ(m.dim, 3);
  ASSERT_EQ(m.parts.size(), 2u);
  EXPECT_EQ(m.parts[0].name, "big");
  EXPECT_EQ(m.parts[0].type, ElementType::Hex8);
  EXPECT_EQ(m.parts[0].numElements(), 4 * 2 * 3);
  EXPECT_EQ(m.parts[1].numElements(), 2 * 2 * 3);
  EXPECT_EQ(m.numNodes(), 15 * 4 + 9 * 4);
  EXPECT_NEAR(meshMeasure(m, 0), 1.0, kGeomTol);
  EXPECT_NEAR(meshMeasure(m, 1), 0.5, kGeomTol);
  const auto ext = extractExternalFaces(m);
  EXPECT_EQ(ext.size(), size_t(2 * (8 + 6 + 12) + 2 * (4 + 6 + 6)));
  for (const char *name : {"bottom", "top"})
  {
    ASSERT_TRUE(m.face_sets.count(name));
    const auto &fs = m.face_sets.at(name);
    EXPECT_EQ(fs.size(), 12u);
    Real az = 0;
    for (const auto &f : fs)
      az += areaVector(m, f)[2];
    EXPECT_NEAR(az, std::string(name) == "top" ? 3.0 : -3.0, kGeomTol * 3); // outward
    EXPECT_EQ(m.node_sets.at(name).size(), 15u + 9u) << name;               // every part copy
  }
}

TEST(GmshReader, TetBoxVolumeAndSkin)
{
  if (!haveGmsh())
    GTEST_SKIP() << "gmsh not on PATH";
  const auto path = mesh("tet", R"(
Point(1) = {0, 0, 0, 0.25}; Point(2) = {2, 0, 0, 0.25};
Point(3) = {2, 1, 0, 0.25}; Point(4) = {0, 1, 0, 0.25};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
out[] = Extrude {0, 0, 0.5} { Surface{1}; };
Physical Volume("box") = {out[1]};
Physical Surface("skin") = {1, out[0], out[2], out[3], out[4], out[5]};
)",
                         3);
  const HostMesh m = readGmsh41(path);
  ASSERT_EQ(m.parts.size(), 1u);
  EXPECT_EQ(m.parts[0].type, ElementType::Tet4);
  EXPECT_GT(m.parts[0].numElements(), 100);
  EXPECT_NEAR(meshMeasure(m, 0), 1.0, kGeomTol);
  EXPECT_NO_THROW(checkElements(m)); // every tet has positive volume after the reader
  const auto ext = extractExternalFaces(m);
  const auto &skin = m.face_sets.at("skin");
  EXPECT_EQ(skin.size(), ext.size());
  Real area = 0;
  std::array<Real, 3> sum{0, 0, 0};
  for (const auto &f : skin)
  {
    const auto n = areaVector(m, f);
    area += std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; ++k)
      sum[k] += n[k];
  }
  EXPECT_NEAR(area, 2 * (2 * 1 + 1 * 0.5 + 2 * 0.5), kGeomTol * 7);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(sum[k], 0, kGeomTol); // closed surface
  // outward: the flux of x through the skin is the volume (divergence theorem, per face exact)
  Real flux = 0;
  for (const auto &f : skin)
  {
    Real cx = 0;
    for (int i = 0; i < 3; ++i)
      cx += m.coords[f.nodes[i]][0] / 3;
    flux += cx * areaVector(m, f)[0];
  }
  EXPECT_NEAR(flux, 1.0, kGeomTol);
}

TEST(GmshReader, LineMeshWithEndPoints)
{
  if (!haveGmsh())
    GTEST_SKIP() << "gmsh not on PATH";
  const auto path = mesh("bar", R"(
Point(1) = {-0.5, 0, 0}; Point(2) = {1.5, 0, 0}; Line(1) = {1, 2};
Transfinite Curve{1} = 11;
Physical Curve("bar") = {1};
Physical Point("left") = {1};
Physical Point("right") = {2};
)",
                         1);
  const HostMesh m = readGmsh41(path);
  EXPECT_EQ(m.dim, 1);
  ASSERT_EQ(m.parts.size(), 1u);
  EXPECT_EQ(m.parts[0].type, ElementType::Line2);
  EXPECT_EQ(m.parts[0].numElements(), 10);
  EXPECT_NEAR(meshMeasure(m, 0), 2.0, kGeomTol * 2);
  ASSERT_EQ(m.face_sets.at("left").size(), 1u);
  EXPECT_EQ(m.face_sets.at("left")[0].local_face, 0); // the -x end of its element
  EXPECT_EQ(m.face_sets.at("right")[0].local_face, 1);
  EXPECT_EQ(m.coords[m.node_sets.at("right").at(0)][0], 1.5);
}

TEST(GmshReader, ClearErrors)
{
  EXPECT_NE(errorOf("/nonexistent/x.msh").find("cannot open"), std::string::npos);
  if (!haveGmsh())
    GTEST_SKIP() << "gmsh not on PATH";
  const std::string named = "Physical Surface(\"s\") = {1, 2};\n";
  // triangles in the top dimension
  std::string e = errorOf(mesh("tris", kTwoRects + named, 2));
  EXPECT_NE(e.find("unsupported element type gmsh type 2 (tri3)"), std::string::npos) << e;
  EXPECT_NE(e.find("tris.msh:"), std::string::npos) << e; // names the file and line
  e = errorOf(mesh("v22", kTwoRects + kQuads + named, 2, "msh22"));
  EXPECT_NE(e.find("version 2.2"), std::string::npos) << e;
  EXPECT_NE(e.find("v22.msh:2:"), std::string::npos) << e;
  e = errorOf(mesh("bin", kTwoRects + kQuads + named, 2, "msh41", "-bin"));
  EXPECT_NE(e.find("binary"), std::string::npos) << e;
  // one part over both rectangles: the curve x = 2 is interior, not a face of any part
  e = errorOf(mesh("interior", kTwoRects + kQuads + named + "Physical Curve(\"mid\") = {2};\n", 2));
  EXPECT_NE(e.find("element of physical group 'mid' (dimension 1) is not an external face"),
            std::string::npos)
      << e;
}

TEST(GmshReader, HandWrittenErrors)
{
  const std::string dir = std::string(SCPDYN_TEST_WORKDIR) + "/";
  const std::string head = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
                           "$Entities\n0 0 0 2\n"
                           "1 0 0 0 1 1 1 1 5 0\n2 0 0 0 1 1 1 1 5 0\n$EndEntities\n"
                           "$Nodes\n1 9 1 9\n3 1 0 9\n1\n2\n3\n4\n5\n6\n7\n8\n9\n"
                           "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n1 1 2\n"
                           "$EndNodes\n";
  // one physical volume (5) holding a hex and a tet: one part cannot hold both
  std::ofstream(dir + "mixed.msh") << head
                                   << "$Elements\n2 2 1 2\n3 1 5 1\n1 1 2 3 4 5 6 7 8\n"
                                      "3 2 4 1\n2 5 6 7 9\n$EndElements\n";
  std::string e = errorOf(dir + "mixed.msh");
  EXPECT_NE(e.find("mixed.msh:35: physical group 'physical_5' mixes"), std::string::npos) << e;
  // unknown node tag
  std::ofstream(dir + "badnode.msh") << head
                                     << "$Elements\n1 1 1 1\n3 1 5 1\n1 1 2 3 4 5 6 7 42\n"
                                        "$EndElements\n";
  e = errorOf(dir + "badnode.msh");
  EXPECT_NE(e.find("badnode.msh:34: unknown node tag 42"), std::string::npos) << e;
  // a node tag given twice: refused, not the last copy silently winning
  std::string twice = head;
  twice.replace(twice.find("1\n2\n3\n4\n5\n6\n7\n8\n9\n"), 18, "1\n2\n3\n4\n5\n6\n7\n8\n3\n");
  std::ofstream(dir + "twice.msh") << twice
                                   << "$Elements\n1 1 1 1\n3 1 5 1\n1 1 2 3 4 5 6 7 8\n"
                                      "$EndElements\n";
  e = errorOf(dir + "twice.msh");
  EXPECT_NE(e.find("twice.msh:29: node tag 3 given twice (first at line 23)"), std::string::npos)
      << e;
}
