// Verification T1a (verification.md): 1D elastic plate impact in uniaxial strain, on a
// built-in mesh of each element type. A steel striker (0.1 m, 10 m/s) glued to a steel
// target (0.1 m): plateau stress rho c_L v / 2 at mid-target, arrival time, momentum.
#include "TestUtil.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace scpdyn;

namespace
{
constexpr Real kRho = 7850, kE = 200e9, kNu = 0.3, kV = 10, kL = 0.1, kH = 0.001;
const Real kM = kE * (1 - kNu) / ((1 + kNu) * (1 - 2 * kNu));
const Real kC = std::sqrt(kM / kRho); // 5856.4 m/s

std::string deckFor(const std::string &element)
{
  const bool d1 = element == "line2", d3 = element == "hex8" || element == "tet4";
  const std::string dim = d1 ? "1" : d3 ? "3" : "2";
  auto vec = [&](Real a, Real b, Real c) {
    std::ostringstream os;
    os.precision(17);
    os << "[" << a;
    if (!d1)
      os << ", " << b;
    if (d3)
      os << ", " << c;
    os << "]";
    return os.str();
  };
  auto ivec = [&](int a) {
    return d1   ? "[" + std::to_string(a) + "]"
           : d3 ? "[" + std::to_string(a) + ", 1, 1]"
                : "[" + std::to_string(a) + ", 1]";
  };
  std::ostringstream d;
  d << "dimension: " << dim << "\n"
    << "time: {end: 40.0e-6, courant: 0.5}\n"
    << "materials:\n  - {name: steel, model: elastic, density: 7850, youngs_modulus: 200.0e9, "
       "poisson_ratio: 0.3}\n"
    << "parts:\n"
    << "  - {name: striker, material: steel, merge_nodes: true, initial_velocity: " << vec(kV, 0, 0)
    << ",\n     mesh: {type: block, element: " << element << ", elements: " << ivec(100)
    << ", origin: " << vec(0, 0, 0) << ", size: " << vec(kL, kH, kH) << "}}\n"
    << "  - {name: target, material: steel, merge_nodes: true,\n"
    << "     mesh: {type: block, element: " << element << ", elements: " << ivec(100)
    << ", origin: " << vec(kL, 0, 0) << ", size: " << vec(kL, kH, kH) << "}}\n";
  if (!d1)
  {
    d << "node_sets:\n  - {name: all, box: {min: " << vec(-1, -1, -1) << ", max: " << vec(1, 1, 1)
      << "}}\n"
      << "boundary_conditions:\n  - {type: velocity, node_set: all, component: y, value: 0.0}\n";
    if (d3)
      d << "  - {type: velocity, node_set: all, component: z, value: 0.0}\n";
  }
  d << "gauges:\n  - {name: mid, kind: element, point: " << vec(1.5 * kL + kH / 2, kH / 2, kH / 2)
    << ", quantities: [sxx]}\n";
  return d.str();
}

void checkPlateImpact(const std::string &element)
{
  Solver s(test::deckFromText(deckFor(element), "t1_" + element));
  const Real p0 = s.energies().momentum[0];
  std::vector<Real> t, sxx;
  while (s.time() < s.deck().end_time)
  {
    s.cycle();
    t.push_back(s.time());
    sxx.push_back(s.gaugeValues()[0]);
  }
  const EnergyReport r = s.energies();

  // the gauge element's centre is at 1.5 L + h/2: the front arrives at (0.5 L + h/2) / c; the
  // tensile reflection from the target's free end ends the plateau 2 (0.5 L - h/2) / c later
  const Real t_arrive = (0.5 * kL + kH / 2) / kC;
  const Real duration = 2 * (0.5 * kL - kH / 2) / kC;
  const Real sigma = -kRho * kC * kV / 2; // -229.9 MPa
  Real sum = 0;
  int count = 0;
  Real t50 = -1;
  for (size_t k = 0; k < t.size(); ++k)
  {
    if (t[k] > t_arrive + 0.2 * duration && t[k] < t_arrive + 0.8 * duration)
    {
      sum += sxx[k];
      ++count;
    }
    if (t50 < 0 && sxx[k] < 0.5 * sigma)
      t50 = t[k];
  }
  ASSERT_GT(count, 20);
  const Real plateau = sum / count;
  std::printf("[T1a %s] plateau %.6e Pa (exact %.6e, error %.3e), arrival %.4e s (exact %.4e, "
              "%.2f h/c), momentum drift %.2e, hourglass/internal %.2e, balance %.2e\n",
              element.c_str(), plateau, sigma, plateau / sigma - 1, t50, t_arrive,
              (t50 - t_arrive) / (kH / kC), std::abs(r.momentum[0] - p0) / std::abs(p0),
              r.hourglass / r.internal, r.balance_error);
  // tolerances of verification.md T1 for the suggested mesh (h = 1 mm, S = 0.5)
  EXPECT_NEAR(plateau / sigma, 1.0, 0.01);
  EXPECT_LT(std::abs(t50 - t_arrive), 2 * kH / kC);
  // no external force acts along x: momentum is exact up to round-off of the sums
  EXPECT_LT(std::abs(r.momentum[0] - p0), 1e-12 * std::abs(p0));
  EXPECT_LT(r.hourglass, 0.01 * r.internal);
  EXPECT_LT(std::abs(r.balance_error), 5e-3); // T9: <= 0.5 % for an elastic problem
}
} // namespace

TEST(PlateImpactT1, Line2UniaxialStrain) { checkPlateImpact("line2"); }
TEST(PlateImpactT1, Quad4PlaneStrainColumn) { checkPlateImpact("quad4"); }
TEST(PlateImpactT1, Hex8Column) { checkPlateImpact("hex8"); }
TEST(PlateImpactT1, Tet4Column) { checkPlateImpact("tet4"); }
