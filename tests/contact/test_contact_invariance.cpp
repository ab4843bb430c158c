// Invariants of the CP forces (docs/theory.md 8.3, 3.5) and the contact outputs: forces sum to
// zero, swapping the face order gives the same physics with opposite CP forces, the outputs
// (contacts.xmf/h5, summary.json, history.csv) carry the contact data.
#include "ContactTestUtil.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

using namespace scpdyn;
using namespace scpdyn::test;

namespace
{

std::string fig5(bool swapped)
{
  std::string y =
      readText(std::string(SCPDYN_SOURCE_DIR) + "/inputs/paper/fig5_implicit_S0.5.yaml");
  if (swapped)
  {
    // list the target first: every face key of the interface changes side (3.5)
    const auto a = y.find("  - name: impactor"), b = y.find("  - name: target");
    const auto e = y.find("contact:");
    const std::string imp = y.substr(a, b - a), tgt = y.substr(b, e - b);
    y = y.substr(0, a) + tgt + imp + y.substr(e);
  }
  return y;
}

/// contact force summed over the nodes of each part (by the part's name)
std::map<std::string, std::array<double, 3>> partForces(const Solver &s)
{
  auto f = Kokkos::create_mirror_view_and_copy(HostSpace(), s.contact()->nodalForces());
  std::map<std::string, std::array<double, 3>> out;
  for (const HostPart &p : s.mesh().parts)
  {
    std::vector<Index> nodes(p.connectivity);
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    std::array<double, 3> sum{{0, 0, 0}};
    for (Index n : nodes)
      for (int d = 0; d < 3; ++d)
        sum[size_t(d)] += f(n, d);
    out[p.name] = sum;
  }
  return out;
}

} // namespace

// The CP forces on the nodes sum to zero (to round-off of |F| ~ 1e8 N per metre), and the
// weights of each active CP sum to 1 on each face.
TEST(ContactInvariance, ForcesSumToZero)
{
  Solver s(deckFromText(fig5(false), "inv_sum"));
  double largest = 0, worst = 0;
  while (s.time() < 1.0e-6)
  {
    s.cycle();
    auto f = Kokkos::create_mirror_view_and_copy(HostSpace(), s.contact()->nodalForces());
    double sum[3] = {0, 0, 0};
    for (Index n = 0; n < s.nodes().count; ++n)
      for (int d = 0; d < 3; ++d)
      {
        sum[d] += f(n, d);
        largest = std::max(largest, std::fabs(f(n, d)));
      }
    for (int d = 0; d < 3; ++d)
      worst = std::max(worst, std::fabs(sum[d]));
  }
  ASSERT_GT(largest, 1e6);
  EXPECT_LT(worst, 1e-12 * largest * 100); // 100 nodes' worth of round-off
  const CommonPlaneData &cp = s.contact()->planes();
  auto w1 = Kokkos::create_mirror_view_and_copy(HostSpace(), cp.w1);
  auto w2 = Kokkos::create_mirror_view_and_copy(HostSpace(), cp.w2);
  auto status = Kokkos::create_mirror_view_and_copy(HostSpace(), cp.status);
  for (Index p = 0; p < cp.count; ++p)
    if (status(p) != CpInactive)
    {
      EXPECT_NEAR(w1(p, 0) + w1(p, 1), 1.0, 1e-14);
      EXPECT_NEAR(w2(p, 0) + w2(p, 1), 1.0, 1e-14);
    }
}

// Listing the parts the other way round swaps face 1 and face 2 of every CP (their keys, hence
// the sign of n and of the CP force): the contact forces on each part and the motion are the
// same to round-off (relative 1e-9 after 10 cycles of a 1 km/s impact; the two runs differ only
// in the order of floating-point operations).
TEST(ContactInvariance, SwappingFaceOrderGivesTheSameForces)
{
  Solver a(deckFromText(fig5(false), "inv_a"));
  Solver b(deckFromText(fig5(true), "inv_b"));
  for (int c = 0; c < 10; ++c)
  {
    a.cycle();
    b.cycle();
  }
  const auto fa = partForces(a), fb = partForces(b);
  const double scale = std::fabs(fa.at("impactor")[0]);
  ASSERT_GT(scale, 1e6);
  for (const char *part : {"impactor", "target"})
    for (int d = 0; d < 2; ++d)
      EXPECT_NEAR(fa.at(part)[size_t(d)], fb.at(part)[size_t(d)], 1e-9 * scale) << part << d;
  EXPECT_NEAR(fa.at("impactor")[0], -fa.at("target")[0], 1e-12 * scale);
  // the CP forces themselves are opposite: face 1 of run a is face 2 of run b
  auto Fa = Kokkos::create_mirror_view_and_copy(HostSpace(), a.contact()->planes().force);
  auto Fb = Kokkos::create_mirror_view_and_copy(HostSpace(), b.contact()->planes().force);
  auto Pa = Kokkos::create_mirror_view_and_copy(HostSpace(), a.contact()->planes().poc);
  auto Pb = Kokkos::create_mirror_view_and_copy(HostSpace(), b.contact()->planes().poc);
  ASSERT_EQ(a.contact()->count(), b.contact()->count());
  int matched = 0;
  for (Index p = 0; p < a.contact()->count(); ++p)
    for (Index q = 0; q < b.contact()->count(); ++q)
      if (std::fabs(Pa(p, 1) - Pb(q, 1)) < 1e-9 && std::fabs(Pa(p, 0) - Pb(q, 0)) < 1e-6)
      {
        ++matched;
        EXPECT_NEAR(Fa(p, 0), -Fb(q, 0), 1e-9 * scale);
        EXPECT_NEAR(Fa(p, 1), -Fb(q, 1), 1e-9 * scale);
      }
  EXPECT_EQ(matched, a.contact()->count());
}

TEST(ContactInvariance, OutputsCarryTheContact)
{
  std::string yaml = fig5(false);
  yaml = replaced(yaml, "end: 3.0e-6", "end: 1.0e-6");
  const std::string dir = runDeck(yaml, "inv_outputs");
  const std::string summary = readText(dir + "/summary.json");
  EXPECT_NE(summary.find("\"common_planes_max\": 30"), std::string::npos) << summary;
  auto h = readCsv(dir + "/history.csv");
  ASSERT_TRUE(h.count("contact") && h.count("contact_dissipation"));
  EXPECT_GT(h["contact"].back(), 0);
  const std::string xmf = readText(dir + "/contacts.xmf");
  EXPECT_NE(xmf.find("CollectionType=\"Temporal\""), std::string::npos);
  EXPECT_NE(xmf.find("TopologyType=\"Polyvertex\" NumberOfElements=\"30\""), std::string::npos);
  for (const char *name : {"area", "normal_force", "shear_force", "closure", "slip", "state"})
    EXPECT_NE(xmf.find(std::string("Attribute Name=\"") + name + "\""), std::string::npos) << name;
  EXPECT_TRUE(std::filesystem::exists(dir + "/contacts.h5"));
}
