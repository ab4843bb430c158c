#pragma once
// Host drivers for the material tests: one material point taken through strain paths by
// calling updateMaterial() exactly as the element kernel does.
#include "input/Deck.hpp"
#include "material/MaterialLibrary.hpp"
#include "material/MaterialUpdate.hpp"

#include <cmath>
#include <initializer_list>
#include <string>
#include <utility>

namespace scpdyn::test
{

/// \brief A deck-side material spec from (key, value) pairs.
inline MaterialSpec makeSpec(const std::string &model, const std::string &eos,
                             std::initializer_list<std::pair<const char *, double>> values)
{
  MaterialSpec s;
  s.name = "m";
  s.model = model;
  s.eos = eos;
  int line = 10;
  for (const auto &kv : values)
  {
    s.values[kv.first] = kv.second;
    s.lines[kv.first] = line++;
  }
  return s;
}

/// \brief The parameter sets the tests share (docs/theory.md, materials): AISI 4340 steel
/// (Johnson-Cook, Mie-Grueneisen), TNT (JWL with programmed burn), the paper's limestone
/// (geomaterial).
inline MaterialSpec steel4340()
{
  return makeSpec("johnson_cook", "mie_gruneisen",
                  {{"density", 7830},
                   {"shear_modulus", 77.5e9},
                   {"A", 792e6},
                   {"B", 510e6},
                   {"n", 0.26},
                   {"C", 0.014},
                   {"m", 1.03},
                   {"melt_temperature", 1793},
                   {"specific_heat", 477},
                   {"eos.c0", 4578},
                   {"eos.s", 1.33},
                   {"eos.gamma0", 1.67}});
}

inline MaterialSpec tnt()
{
  return makeSpec("high_explosive", "jwl",
                  {{"density", 1630},
                   {"eos.A", 371.2e9},
                   {"eos.B", 3.231e9},
                   {"eos.R1", 4.15},
                   {"eos.R2", 0.95},
                   {"eos.omega", 0.30},
                   {"eos.E0", 7.0e9},
                   {"D", 6930},
                   {"pcj", 21.0e9}});
}

inline MaterialSpec limestone()
{
  return makeSpec("geomaterial", "linear",
                  {{"density", 2600},
                   {"youngs_modulus", 43.875e9},
                   {"poisson_ratio", 0.25},
                   {"porosity", 0.04},
                   {"crush_pressure", 200e6},
                   {"lock_pressure", 2e9},
                   {"solid_bulk_modulus", 70e9},
                   {"intact_strength", 50e6},
                   {"intact_friction", 1.5},
                   {"max_strength", 1.5e9},
                   {"damaged_friction", 1.2},
                   {"tensile_strength", 8e6},
                   {"damage_strain", 0.01},
                   {"dilatancy", 0.1},
                   {"dilatancy_pressure", 250e6},
                   {"compaction_hardening", 0.2}});
}

/// \brief One material point: state plus the density it is at.
struct MaterialPoint
{
  MaterialParams p;
  Real stress[6] = {0, 0, 0, 0, 0, 0};
  Real e = 0, eps = 0, rho = 0, c = 0, time = 0, length = 1;
  Real history[kHistorySize] = {};
  /// stress work per unit mass of the last step, trapezoidal, computed independently
  Real last_work = 0;

  explicit MaterialPoint(const MaterialParams &params, const Real centroid[3] = nullptr)
      : p(params), rho(params.density)
  {
    const Real zero[3] = {0, 0, 0};
    initializeMaterialHistory(p, centroid ? centroid : zero, history);
    e = initialSpecificEnergy(p);
  }

  /// \brief One step with rate of deformation D over dt; the density follows the exact
  /// volumetric kinematics rho_new = rho exp(-tr D dt).
  void step(const Real D[6], Real dt, Real q = 0)
  {
    MaterialStep st;
    for (int k = 0; k < 6; ++k)
      st.D[k] = D[k];
    st.dt = dt;
    st.rho_old = rho;
    st.rho_new = rho * std::exp(-(D[0] + D[1] + D[2]) * dt);
    st.q = q;
    st.time = time + 0.5 * dt;
    st.length = length;
    Real old[6];
    for (int k = 0; k < 6; ++k)
      old[k] = stress[k];
    c = updateMaterial(p, st, stress, e, eps, history);
    Real mid[6];
    for (int k = 0; k < 6; ++k)
      mid[k] = 0.5 * (old[k] + stress[k]);
    const Real trD = D[0] + D[1] + D[2];
    last_work = dt / (0.5 * (st.rho_old + st.rho_new)) * (contract(mid, D) - q * trD);
    rho = st.rho_new;
    time += dt;
  }

  Real pressure() const { return -(stress[0] + stress[1] + stress[2]) / 3; }
  Real mises() const
  {
    Real s[6];
    for (int k = 0; k < 6; ++k)
      s[k] = stress[k];
    makeDeviatoric(s);
    return vonMises(s);
  }
};

/// \brief Relative difference with a floor on the scale.
inline double relErr(double a, double b, double floor = 1e-300)
{
  const double scale = std::fabs(b) > floor ? std::fabs(b) : floor;
  return std::fabs(a - b) / scale;
}

} // namespace scpdyn::test
