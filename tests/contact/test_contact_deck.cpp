// The deck's contact section (docs/input.md): parsing, Table 1 unit conversion to SI, the
// resolved deck round trip, and errors naming the key.
#include "ContactTestUtil.hpp"
#include "contact/ContactSetup.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace scpdyn;
using namespace scpdyn::test;

namespace
{

const char *kBase = R"(dimension: 2
time: {end: 1.0e-6}
materials:
  - {name: rock, density: 2600, youngs_modulus: 4.0e10, poisson_ratio: 0.25}
parts:
  - {name: a, material: rock, mesh: {elements: [2, 2], size: [0.01, 0.01]}}
  - {name: b, material: rock, mesh: {elements: [3, 3], origin: [0.01, 0], size: [0.01, 0.01]}}
face_sets:
  - {name: right_of_a, box: {min: [0.01, 0], max: [0.01, 0.01]}}
)";

std::string errorOf(const std::string &contact)
{
  try
  {
    deckFromText(std::string(kBase) + contact, "contact_deck");
  }
  catch (const InputError &e)
  {
    return e.what();
  }
  return "(no error)";
}

} // namespace

TEST(ContactDeck, Table1UnitsBecomeSI)
{
  const Deck d = deckFromText(std::string(kBase) + R"(contact:
  search_interval: once
  surfaces:
    - {name: j, part: "*", option: explicit, a: 0.2, E0: 0.5, G: 0.3, C: 0.001, phi0: 38,
       phi1: 30, usp0: 50, psi0: 5, sigma_cr: 0.1, C_safe: off}
    - {name: k, face_set: right_of_a, option: sticky, Emax: 100, sigma_t: 0.002}
)",
                              "units");
  ASSERT_EQ(d.contact.surfaces.size(), 2u);
  EXPECT_EQ(d.contact.search_interval, 0);
  const JointParams p = jointParamsOf(d.contact.surfaces[0], 0);
  // exact factors: mm -> m, GPa -> Pa, degrees -> radians
  EXPECT_DOUBLE_EQ(p.a, 2e-4);
  EXPECT_DOUBLE_EQ(p.E0, 5e8);
  EXPECT_DOUBLE_EQ(p.G, 3e8);
  EXPECT_DOUBLE_EQ(p.C, 1e6);
  EXPECT_NEAR(p.phi0, 38 * M_PI / 180, 1e-15);
  EXPECT_NEAR(p.psi0, 5 * M_PI / 180, 1e-15);
  EXPECT_DOUBLE_EQ(p.sigma_cr, 1e8);
  EXPECT_DOUBLE_EQ(p.usp0, 50);
  EXPECT_EQ(p.option, ContactOption::Explicit);
  EXPECT_GT(p.C_safe, 1e30); // off
  // derived defaults (D8), (D9) of docs/theory.md
  EXPECT_DOUBLE_EQ(p.Emax, 1e4 * 5e8);
  EXPECT_NEAR(p.sigma_t, 1e6 / std::tan(38 * M_PI / 180), 1e-6);
  const JointParams q = jointParamsOf(d.contact.surfaces[1], 1);
  EXPECT_EQ(q.option, ContactOption::Sticky);
  EXPECT_DOUBLE_EQ(q.Emax, 1e11);
  EXPECT_DOUBLE_EQ(q.sigma_t, 2e6);
  EXPECT_EQ(q.bc_id, 1);
}

TEST(ContactDeck, ResolvedDeckRoundTrips)
{
  const Deck a = deckFromText(std::string(kBase) + R"(contact:
  search_interval: 3
  constraint_passes: 12
  search_gap: 0.002
  surfaces:
    - {name: j, part: "*", option: implicit, a: 0.1, E0: 0.05, C_safe: off, velocity: average,
       distribution: poc, implicit_shear: false}
    - {name: k, face_set: right_of_a, option: slide_line, Emax: 7.5}
)",
                              "roundtrip");
  const std::string file = contactWorkDir("deck") + "/resolved.yaml";
  writeResolvedDeck(a, file);
  const Deck b = parseDeck(file);
  ASSERT_EQ(b.contact.surfaces.size(), 2u);
  EXPECT_EQ(b.contact.search_interval, 3);
  EXPECT_EQ(b.contact.constraint_passes, 12);
  EXPECT_EQ(b.contact.search_gap, 0.002);
  for (size_t s = 0; s < 2; ++s)
  {
    const SurfaceSpec &x = a.contact.surfaces[s], &y = b.contact.surfaces[s];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.part, y.part);
    EXPECT_EQ(x.face_set, y.face_set);
    EXPECT_EQ(x.option, y.option);
    EXPECT_EQ(x.a, y.a);
    EXPECT_EQ(x.E0, y.E0);
    EXPECT_EQ(x.Emax, y.Emax);
    EXPECT_EQ(x.sigma_t, y.sigma_t);
    EXPECT_EQ(x.C_safe, y.C_safe);
    EXPECT_EQ(x.velocity, y.velocity);
    EXPECT_EQ(x.distribution, y.distribution);
    EXPECT_EQ(x.implicit_shear, y.implicit_shear);
  }
  EXPECT_TRUE(std::isinf(b.contact.surfaces[0].C_safe));
  EXPECT_EQ(b.contact.surfaces[1].sigma_t, -1); // still "auto"
}

TEST(ContactDeck, ErrorsNameTheKey)
{
  EXPECT_NE(errorOf("contact:\n  surfaces:\n    - {name: j, part: c, option: sticky}\n")
                .find("contact.surfaces[0].part (line 12): unknown part 'c'"),
            std::string::npos);
  EXPECT_NE(errorOf("contact:\n  surfaces:\n    - {name: j, part: a, option: stiky}\n")
                .find("contact.surfaces[0].option (line 12)"),
            std::string::npos);
  // a modulus given in Pa where Table 1 units (GPa) are expected
  EXPECT_NE(errorOf("contact:\n  surfaces:\n    - {name: j, part: a, E0: 5.0e8}\n")
                .find("contact.surfaces[0].E0 (line 12): is in GPa"),
            std::string::npos);
  EXPECT_NE(
      errorOf("contact:\n  search_interval: sometimes\n  surfaces:\n    - {name: j, part: a}\n")
          .find("contact.search_interval (line 11): must be 'once' or an integer"),
      std::string::npos);
  EXPECT_NE(errorOf("contact:\n  surfaces:\n    - {name: j, part: a, face_set: right_of_a}\n")
                .find("contact.surfaces[0]"),
            std::string::npos);
}

TEST(ContactDeck, FacesOfSurfacesAndMasses)
{
  // two quads of 1 cm: every external face is a contact face; face mass = element mass / 2
  const Deck d = deckFromText(
      std::string(kBase) + "contact:\n  surfaces:\n    - {name: j, part: \"*\", option: sticky}\n",
      "faces");
  Solver s(d);
  const ContactSystem *c = s.contact();
  ASSERT_NE(c, nullptr);
  // external faces: part a 2x2 -> 8 faces, part b 3x3 -> 12 faces
  EXPECT_EQ(c->faces().count, 20);
  auto mass = Kokkos::create_mirror_view_and_copy(HostSpace(), c->faces().mass);
  auto el = Kokkos::create_mirror_view_and_copy(HostSpace(), c->faces().element);
  auto emass = Kokkos::create_mirror_view_and_copy(HostSpace(), s.elements().mass);
  for (Index f = 0; f < c->faces().count; ++f)
    EXPECT_DOUBLE_EQ(mass(f), 0.5 * emass(el(f)));
  // keys ascend (face 1 of every CP is the smaller key, docs/theory.md 3.5)
  for (size_t f = 1; f < c->faceInfo().size(); ++f)
    EXPECT_LT(c->faceInfo()[f - 1].key, c->faceInfo()[f].key);
}
