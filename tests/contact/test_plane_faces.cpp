// The fast paths of the per-CP geometry (step 9, sub-steps A-D) against the slow ones they
// replace, bit for bit:
// - the face geometry computed once per face and cycle (listPlaneFaces,
//   computePlaneFaceGeometry, pairGeometryOf in ContactSearch.hpp) gives every field of the
//   CpGeometry and the half-step nodes that pairGeometry gives, in 1D, 2D (plane and
//   axisymmetric) and 3D (quads, triangles, warped and non-convex projections);
// - the Sutherland-Hodgman clip without the copy before each edge (PolygonClip.hpp) gives the
//   vertices of the clip that copies the polygon and computes each side twice.
// Whole runs keep their gauges bit for bit only if these hold (scripts/same_bits.sh).
#include "contact/ContactSearch.hpp"
#include "core/HostCopy.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

using namespace scpdyn;

namespace
{

KOKKOS_INLINE_FUNCTION bool sameBits(Real a, Real b)
{
  std::uint64_t ia, ib;
  std::memcpy(&ia, &a, sizeof(a));
  std::memcpy(&ib, &b, sizeof(b));
  return ia == ib;
}

KOKKOS_INLINE_FUNCTION int differences(const CpGeometry &a, const CpGeometry &b)
{
  int n = a.valid != b.valid ? 1 : 0;
  const Real *va[] = {a.n, a.x_cp, a.x_poc, a.e1, a.e2, a.c1, a.c2, a.n1, a.n2};
  const Real *vb[] = {b.n, b.x_cp, b.x_poc, b.e1, b.e2, b.c1, b.c2, b.n1, b.n2};
  for (int k = 0; k < 9; ++k)
    for (int d = 0; d < 3; ++d)
      n += sameBits(va[k][d], vb[k][d]) ? 0 : 1;
  const Real sa[] = {a.Ac, a.A1, a.A2, a.A1p, a.A2p, a.f1, a.f2, a.u0, a.h1, a.h2};
  const Real sb[] = {b.Ac, b.A1, b.A2, b.A1p, b.A2p, b.f1, b.f2, b.u0, b.h1, b.h2};
  for (int k = 0; k < 10; ++k)
    n += sameBits(sa[k], sb[k]) ? 0 : 1;
  return n;
}

/// Faces of `nn` nodes (1: point faces with a back node) on random nodes near a plane, and
/// CPs between every pair of faces: facing, overlapping, disjoint, degenerate alike.
struct Scene
{
  ContactFaceData F;
  NodeFields nodes;
  IndexView face1, face2;
  Index count = 0;
};

Scene scene(int dim, int nfaces, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<Real> u(-1.0, 1.0);
  Scene s;
  const int per_face = dim == 1 ? 2 : dim == 2 ? 2 : 4;
  const size_t nnodes = size_t(nfaces * per_face);
  s.nodes.x = VectorView("x", nnodes);
  s.nodes.v = VectorView("v", nnodes);
  auto x = Kokkos::create_mirror_view(s.nodes.x);
  auto v = Kokkos::create_mirror_view(s.nodes.v);
  allocateFaces(s.F, size_t(nfaces));
  ContactFaceHost h(s.F);
  for (int f = 0; f < nfaces; ++f)
  {
    // every third 3D face a triangle; faces alternate their orientation (up, down)
    const int nn = dim == 1 ? 1 : dim == 2 ? 2 : (f % 3 == 2 ? 3 : 4);
    const Real flip = f % 2 == 0 ? 1.0 : -1.0;
    const Real cx = 0.3 * u(rng), cy = 0.3 * u(rng);
    for (int a = 0; a < per_face; ++a)
    {
      const size_t k = size_t(f * per_face + a);
      const Real ang = flip * 2 * M_PI * a / (dim == 3 ? nn : 2) + 0.2 * u(rng);
      x(k, 0) = 2 + cx + (dim == 1 ? (a == 0 ? 0.01 * u(rng) : -flip) : std::cos(ang));
      x(k, 1) = dim == 1 ? 0 : 1 + cy + (dim == 2 ? std::sin(ang) * 0.1 : std::sin(ang));
      x(k, 2) = dim == 3 ? 0.05 * u(rng) : 0;
      for (int d = 0; d < 3; ++d)
        v(k, d) = d < dim ? 10 * u(rng) : 0;
      if (a < nn)
        h.nodes(f, a) = Index(k);
    }
    for (int a = nn; a < kMaxFaceNodes; ++a)
      h.nodes(f, a) = -1;
    h.num_nodes(f) = nn;
    h.back(f) = dim == 1 ? Index(f * per_face + 1) : -1;
  }
  h.copyTo(s.F);
  Kokkos::deep_copy(s.nodes.x, x);
  Kokkos::deep_copy(s.nodes.v, v);
  std::vector<Index> a, b;
  for (int i = 0; i < nfaces; ++i)
    for (int j = i + 1; j < nfaces; ++j)
      if ((i + j) % 5 != 0) // some faces in fewer CPs than others; the last face in none
        if (j < nfaces - 1)
          a.push_back(i), b.push_back(j);
  s.count = Index(a.size());
  s.face1 = toDevice(a, "face1");
  s.face2 = toDevice(b, "face2");
  return s;
}

/// Fields of the two paths that differ, over every CP of the scene.
int pathDifferences(const Scene &s, int dim, bool axisym, Real dt, PlaneFaceGeometry &G)
{
  listPlaneFaces(s.F, s.face1, s.face2, s.count, G);
  computePlaneFaceGeometry(s.F, s.nodes, dt, dim, axisym, G);
  const ContactFaceData F = s.F;
  const PlaneFaceGeometry Gd = G;
  auto x = s.nodes.x, v = s.nodes.v;
  auto face1 = s.face1, face2 = s.face2;
  int bad = 0;
  Kokkos::parallel_reduce(
      "test::planeFaces", Kokkos::RangePolicy<ExecSpace>(0, s.count),
      KOKKOS_LAMBDA(const Index p, int &n) {
        Real xa1[kMaxFaceNodes][3], xa2[kMaxFaceNodes][3], xb1[kMaxFaceNodes][3],
            xb2[kMaxFaceNodes][3];
        const Index f1 = face1(p), f2 = face2(p);
        const CpGeometry a = pairGeometry(F, f1, f2, x, v, 0.5 * dt, dim, axisym, xa1, xa2);
        const CpGeometry b = pairGeometryOf(F, Gd, f1, f2, dim, axisym, xb1, xb2);
        n += differences(a, b);
        const int slots1 = dim == 1 ? 2 : F.num_nodes(f1), slots2 = dim == 1 ? 2 : F.num_nodes(f2);
        for (int d = 0; d < 3; ++d)
        {
          for (int i = 0; i < slots1; ++i)
            n += sameBits(xa1[i][d], xb1[i][d]) ? 0 : 1;
          for (int i = 0; i < slots2; ++i)
            n += sameBits(xa2[i][d], xb2[i][d]) ? 0 : 1;
        }
      },
      bad);
  return bad;
}

} // namespace

TEST(ContactPlaneFaces, FaceGeometryOncePerFaceGivesThePairGeometryBitForBit)
{
  struct Case
  {
    int dim;
    bool axisym;
  } cases[] = {{1, false}, {2, false}, {2, true}, {3, false}};
  for (const Case &c : cases)
    for (unsigned seed = 1; seed <= 4; ++seed)
    {
      const Scene s = scene(c.dim, 14, seed);
      PlaneFaceGeometry G;
      EXPECT_EQ(pathDifferences(s, c.dim, c.axisym, 1e-3 * seed, G), 0)
          << "dim " << c.dim << (c.axisym ? " axisymmetric" : "") << ", seed " << seed;
      // the active CPs are what the runs depend on: the scene must have some
      Index active = 0;
      const ContactFaceData F = s.F;
      auto x = s.nodes.x, v = s.nodes.v;
      auto face1 = s.face1, face2 = s.face2;
      const int dim = c.dim;
      const bool ax = c.axisym;
      Kokkos::parallel_reduce(
          "test::active", Kokkos::RangePolicy<ExecSpace>(0, s.count),
          KOKKOS_LAMBDA(const Index p, Index &n) {
            Real x1[kMaxFaceNodes][3], x2[kMaxFaceNodes][3];
            n +=
                cpIsActive(pairGeometry(F, face1(p), face2(p), x, v, 0.0, dim, ax, x1, x2)) ? 1 : 0;
          },
          active);
      EXPECT_GT(active, 0) << "dim " << c.dim << ", seed " << seed;
    }
}

TEST(ContactPlaneFaces, ListHoldsTheFacesOfTheCpsOnceAscendingAndFollowsANewCpList)
{
  const Scene s = scene(3, 14, 7);
  PlaneFaceGeometry G;
  listPlaneFaces(s.F, s.face1, s.face2, s.count, G);
  auto faces = Kokkos::create_mirror_view_and_copy(HostSpace(), G.faces);
  auto slot = Kokkos::create_mirror_view_and_copy(HostSpace(), G.slot);
  auto f1 = Kokkos::create_mirror_view_and_copy(HostSpace(), s.face1);
  auto f2 = Kokkos::create_mirror_view_and_copy(HostSpace(), s.face2);
  std::vector<int> in(14, 0);
  for (Index p = 0; p < s.count; ++p)
    in[size_t(f1(p))] = in[size_t(f2(p))] = 1;
  Index expected = 0;
  for (Index f = 0; f < 14; ++f)
  {
    EXPECT_EQ(slot(f), in[size_t(f)] ? expected : -1) << "face " << f;
    if (in[size_t(f)])
    {
      ASSERT_LT(expected, G.count);
      EXPECT_EQ(faces(expected), f);
      ++expected;
    }
  }
  EXPECT_EQ(G.count, expected);
  EXPECT_EQ(slot(13), -1); // the last face is in no CP

  // a new CP list (another allocation, as after a search) is listed again; the same one is not
  const std::vector<Index> a = {13}, b = {5};
  const IndexView n1 = toDevice(a, "face1"), n2 = toDevice(b, "face2");
  listPlaneFaces(s.F, n1, n2, 1, G);
  EXPECT_EQ(G.count, 2);
  auto slot2 = Kokkos::create_mirror_view_and_copy(HostSpace(), G.slot);
  EXPECT_EQ(slot2(5), 0);
  EXPECT_EQ(slot2(13), 1);
  EXPECT_EQ(slot2(0), -1);
  EXPECT_EQ(pathDifferences(s, 3, false, 1e-3, G), 0); // back to the scene's list
}

namespace
{
// The clip as it was: copy the polygon before every edge, each side computed for S and for E.
int referenceClip(const Real subj[][2], int ns, const Real clip[][2], int nc, Real out[][2])
{
  Real buf[kMaxPolyVerts][2];
  int n = ns;
  for (int k = 0; k < ns; ++k)
    out[k][0] = subj[k][0], out[k][1] = subj[k][1];
  for (int e = 0; e < nc && n > 0; ++e)
  {
    const Real ax = clip[e][0], ay = clip[e][1];
    const int f = (e + 1) % nc;
    const Real ex = clip[f][0] - ax, ey = clip[f][1] - ay;
    for (int k = 0; k < n; ++k)
      buf[k][0] = out[k][0], buf[k][1] = out[k][1];
    const int nin = n;
    n = 0;
    for (int k = 0, j = nin - 1; k < nin; j = k++)
    {
      const Real dS = cp_geometry::cross2(ex, ey, buf[j][0] - ax, buf[j][1] - ay);
      const Real dE = cp_geometry::cross2(ex, ey, buf[k][0] - ax, buf[k][1] - ay);
      if ((dE >= 0) != (dS >= 0) && n < kMaxPolyVerts)
      {
        const Real t = dS / (dS - dE);
        out[n][0] = buf[j][0] + t * (buf[k][0] - buf[j][0]);
        out[n][1] = buf[j][1] + t * (buf[k][1] - buf[j][1]);
        ++n;
      }
      if (dE >= 0 && n < kMaxPolyVerts)
      {
        out[n][0] = buf[k][0], out[n][1] = buf[k][1];
        ++n;
      }
    }
  }
  return n < 3 ? 0 : n;
}
} // namespace

TEST(ContactPlaneFaces, ClipWithoutCopiesGivesTheVerticesOfTheCopyingClip)
{
  std::mt19937 rng(11);
  std::uniform_real_distribution<Real> u(-1.0, 1.0);
  int clipped = 0;
  for (int trial = 0; trial < 4000; ++trial)
  {
    // convex CCW polygons of 3 or 4 vertices (points on a circle, ascending angle), shifted
    Real P[2][4][2];
    int nv[2];
    for (int k = 0; k < 2; ++k)
    {
      nv[k] = 3 + (trial >> k) % 2;
      const Real cx = 0.8 * u(rng), cy = 0.8 * u(rng), r = 0.5 + 0.5 * (u(rng) + 1);
      for (int i = 0; i < nv[k]; ++i)
      {
        const Real ang = 2 * M_PI * (i + 0.4 * u(rng)) / nv[k];
        P[k][i][0] = cx + r * std::cos(ang), P[k][i][1] = cy + r * std::sin(ang);
      }
      if (trial % 7 == 0) // shared vertices and edges: the touching cases
        for (int i = 0; i < nv[k]; ++i)
          P[k][i][0] = std::round(4 * P[k][i][0]) / 4, P[k][i][1] = std::round(4 * P[k][i][1]) / 4;
    }
    Real a[kMaxPolyVerts][2], b[kMaxPolyVerts][2];
    const int na = cp_geometry::clipConvex(P[0], nv[0], P[1], nv[1], a);
    const int nb = referenceClip(P[0], nv[0], P[1], nv[1], b);
    ASSERT_EQ(na, nb) << "trial " << trial;
    for (int i = 0; i < na; ++i)
      for (int d = 0; d < 2; ++d)
        ASSERT_TRUE(sameBits(a[i][d], b[i][d])) << "trial " << trial << " vertex " << i;
    clipped += na > 0 ? 1 : 0;
  }
  EXPECT_GT(clipped, 1000);
  EXPECT_LT(clipped, 4000);
}
