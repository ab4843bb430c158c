// The candidate search's fast path (docs/theory.md 3.2: bins by normal class, each face's
// stencil box, the bounds and boxes before the clipping) finds exactly the pairs that the rules
// of 3.2, applied to every pair of faces, accept: a pile of small blocks turned at random
// (normals near the axes and far from them, faces overlapping, touching and apart) against the
// search at cycle 0.
#include "TestUtil.hpp"

#include "contact/ContactChecks.hpp"
#include "contact/ContactSearch.hpp"
#include "contact/ContactSystem.hpp"
#include "driver/Solver.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

using namespace scpdyn;
using namespace scpdyn::test;

namespace
{

/// n^dim blocks of edge 0.1 m (2 elements a side) on a lattice of pitch 0.104 m, each turned by
/// up to `max_angle` degrees about a random axis and shifted by up to 4 mm; search gap 5 mm.
std::string blockPile(int dim, int n, double max_angle, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::ostringstream d;
  d << "dimension: " << dim << "\n";
  if (dim == 2)
    d << "geometry: plane_strain\n";
  d << "time: {end: 1.0e-6}\n"
       "materials:\n"
       "  - {name: rock, model: elastic, density: 2600, youngs_modulus: 40.0e9, "
       "poisson_ratio: 0.25}\n"
       "parts:\n";
  const int count = dim == 2 ? n * n : n * n * n;
  for (int b = 0; b < count; ++b)
  {
    const int i = b % n, j = (b / n) % n, k = b / (n * n);
    d << "  - name: b" << b << "\n    material: rock\n";
    if (dim == 2)
      d << "    mesh: {type: block, element: quad4, elements: [2, 2], origin: [-0.05, -0.05], "
           "size: [0.1, 0.1]}\n";
    else
      d << "    mesh: {type: block, element: hex8, elements: [2, 2, 2], origin: [-0.05, -0.05, "
           "-0.05], size: [0.1, 0.1, 0.1]}\n";
    const double angle = max_angle * u(rng);
    if (dim == 2)
      d << "    rotate: {angle: " << angle << "}\n";
    else
      d << "    rotate: {angle: " << angle << ", axis: [" << u(rng) << ", " << u(rng) << ", "
        << u(rng) + 1.5 << "]}\n";
    d << "    translate: [" << 0.104 * i + 0.004 * u(rng) << ", " << 0.104 * j + 0.004 * u(rng);
    if (dim == 3)
      d << ", " << 0.104 * k + 0.004 * u(rng);
    d << "]\n";
  }
  d << "contact:\n  search_gap: 0.005\n  surfaces:\n"
       "    - {name: joints, part: \"*\", option: implicit, a: 0.1, E0: 0.5, G: 0.3, C: 0, "
       "phi0: 35, phi1: 35}\n";
  return d.str();
}

struct Search
{
  std::set<std::pair<Index, Index>> found, rules;
  long cp_count = 0;
};

/// The CPs of cycle 0's search, and every pair of faces the rules of 3.2 accept at x^0.
Search searchAgainstRules(const std::string &deck_text, const std::string &name, int dim)
{
  Solver s(deckFromText(deck_text, name), MPI_COMM_SELF);
  // cycle 0 searches at the half-step positions x^0 + dt v^0 / 2 = x^0 (the blocks are at rest)
  auto x = Kokkos::create_mirror_view_and_copy(HostSpace(), s.nodes().x);
  s.cycle();
  const ContactSystem &c = *s.contact();
  Search r;
  const CommonPlaneData &cp = c.planes();
  auto f1 = Kokkos::create_mirror_view_and_copy(HostSpace(), cp.face1);
  auto f2 = Kokkos::create_mirror_view_and_copy(HostSpace(), cp.face2);
  for (Index p = 0; p < cp.count; ++p)
    r.found.insert({f1(p), f2(p)});
  r.cp_count = cp.count;

  const ContactFaceData &F = c.faces();
  auto nodes = Kokkos::create_mirror_view_and_copy(HostSpace(), F.nodes);
  auto num = Kokkos::create_mirror_view_and_copy(HostSpace(), F.num_nodes);
  auto element = Kokkos::create_mirror_view_and_copy(HostSpace(), F.element);
  auto depth = Kokkos::create_mirror_view_and_copy(HostSpace(), F.depth);
  auto surface = Kokkos::create_mirror_view_and_copy(HostSpace(), F.surface);
  auto params = Kokkos::create_mirror_view_and_copy(HostSpace(), F.params);
  const Real g_search = 0.005;
  std::vector<FaceGeometry> geo(size_t(F.count));
  std::vector<std::array<std::array<Real, 3>, kMaxFaceNodes>> xf(size_t(F.count));
  for (Index f = 0; f < F.count; ++f)
  {
    Real xh[kMaxFaceNodes][3];
    for (int a = 0; a < num(f); ++a)
      for (int d = 0; d < 3; ++d)
        xh[a][d] = xf[size_t(f)][size_t(a)][size_t(d)] = x(nodes(f, a), d);
    geo[size_t(f)] =
        dim == 2 ? faceGeometry<2>(xh, num(f), false) : faceGeometry<3>(xh, num(f), false);
  }
  for (Index i = 0; i < F.count; ++i)
    for (Index j = i + 1; j < F.count; ++j)
    {
      const FaceGeometry &a = geo[size_t(i)], &b = geo[size_t(j)];
      if (!a.valid || !b.valid || element(i) == element(j))
        continue; // rule 3 (and degenerate faces)
      if (!(a.n[0] * b.n[0] + a.n[1] * b.n[1] + a.n[2] * b.n[2] < -0.5))
        continue; // rule 2
      bool share = false;
      for (int p = 0; p < num(i); ++p)
        for (int q = 0; q < num(j); ++q)
          share = share || nodes(i, p) == nodes(j, q);
      if (share)
        continue; // rule 3
      Real side_i = 0, side_j = 0;
      for (int d = 0; d < 3; ++d)
      {
        side_i += (b.c[d] - a.c[d]) * a.n[d];
        side_j -= (b.c[d] - a.c[d]) * b.n[d];
      }
      const Real ap = 0.5 * (params(surface(i)).a + params(surface(j)).a);
      const Real delta = candidatePenetration(a.diameter, b.diameter, depth(i), depth(j), ap);
      if (!(side_i > -delta && side_j > -delta))
        continue; // rule 5
      Real x1[kMaxFaceNodes][3], x2[kMaxFaceNodes][3];
      for (int p = 0; p < kMaxFaceNodes; ++p)
        for (int d = 0; d < 3; ++d)
          x1[p][d] = xf[size_t(i)][size_t(p)][size_t(d)],
          x2[p][d] = xf[size_t(j)][size_t(p)][size_t(d)];
      const CpGeometry g = dim == 2 ? computeCommonPlane<2>(x1, num(i), x2, num(j), false)
                                    : computeCommonPlane<3>(x1, num(i), x2, num(j), false);
      if (g.valid && -g.u0 <= g_search && cpIsActive(g)) // rules 6 and 7
        r.rules.insert({i, j});
    }
  return r;
}

void expectSamePairs(const Search &r, const char *what)
{
  long missing = 0, extra = 0;
  for (const auto &p : r.rules)
    missing += r.found.count(p) == 0 ? 1 : 0;
  for (const auto &p : r.found)
    extra += r.rules.count(p) == 0 ? 1 : 0;
  std::printf("[candidate search] %s: %zu pairs by the rules, %ld CPs, %ld missing, %ld extra\n",
              what, r.rules.size(), r.cp_count, missing, extra);
  EXPECT_EQ(missing, 0);
  EXPECT_EQ(extra, 0);
  EXPECT_EQ(size_t(r.cp_count), r.found.size()); // no pair twice
}

} // namespace

TEST(CandidateSearch, FindsExactlyThePairsTheRulesAcceptAmongTurnedBlocks3D)
{
  // turned by up to 10 degrees: most faces in the axis classes, pairs across the classes' edge
  const Search near_axes = searchAgainstRules(blockPile(3, 3, 10, 7), "search_pile_3d_10", 3);
  expectSamePairs(near_axes, "3D, up to 10 degrees");
  EXPECT_GT(near_axes.rules.size(), 50u); // the pile touches: the comparison is not empty
  // up to 40 degrees: most normals in no axis class
  const Search turned = searchAgainstRules(blockPile(3, 3, 40, 11), "search_pile_3d_40", 3);
  expectSamePairs(turned, "3D, up to 40 degrees");
  EXPECT_GT(turned.rules.size(), 20u);
}

TEST(CandidateSearch, FindsExactlyThePairsTheRulesAcceptAmongTurnedBlocks2D)
{
  const Search r = searchAgainstRules(blockPile(2, 6, 25, 5), "search_pile_2d", 2);
  expectSamePairs(r, "2D, up to 25 degrees");
  EXPECT_GT(r.rules.size(), 20u);
}
