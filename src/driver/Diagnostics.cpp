// Energies, gauges: what the solver reports about its state.
#include "driver/Solver.hpp"

#include "contact/ContactSystem.hpp"
#include "contact/JointGauge.hpp"
#include "parallel/Decomposition.hpp"
#include "parallel/Mpi.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace scpdyn
{

std::vector<Real> Solver::gaugeValues() const
{
  const size_t count = _m.gauges.size();
  if (count == 0)
    return {};
  RealView values("gauge_values", count);
  auto id = _m.gauge_id;
  auto code = _m.gauge_code;
  auto x = _m.nodes.x, x0 = _m.nodes.x0, v = _m.nodes.v;
  auto stress = _m.elems.stress;
  auto mass = _m.elems.mass, volume = _m.elems.volume, energy = _m.elems.energy;
  auto eps = _m.elems.plastic_strain, q = _m.elems.q;
  Kokkos::parallel_for(
      "scpdyn::output::gauges", Kokkos::RangePolicy<ExecSpace>(0, Index(count)),
      KOKKOS_LAMBDA(const Index g) {
        const Index k = id(g);
        const int c = code(g);
        // another rank's gauge adds -0, which leaves every value as it is (a -0 too)
        Real value = -0.0;
        if (k < 0)
          ;
        else if (c < 100)
          value = c < 3 ? x(k, c) : c < 6 ? x(k, c - 3) - x0(k, c - 3) : v(k, c - 6);
        else
        {
          const int e = c - 100;
          if (e < 6)
            value = stress(k, e);
          else if (e == 6)
            value = -(stress(k, 0) + stress(k, 1) + stress(k, 2)) / 3;
          else if (e == 7)
            value = mass(k) / volume(k);
          else if (e == 8)
            value = eps(k);
          else if (e == 9)
            value = energy(k);
          else
            value = q(k);
        }
        values(g) = value;
      });
  auto h = Kokkos::create_mirror_view_and_copy(HostSpace(), values);
  std::vector<Real> out(h.data(), h.data() + count);
  if (_m.dd) // exact: one rank holds each value, the others add -0
    allReduceSum(out.data(), int(count), _m.comm);
  if (!_m.joint_gauges.empty())
    jointGaugeValues(out);
  return out;
}

void Solver::jointGaugeValues(std::vector<Real> &out) const
{
  // the anchor nodes' positions from the ranks that own them; then each rank's sums over its
  // CPs near them, added over the ranks; then the quantities
  const size_t n = _m.joint_gauges.size();
  std::vector<Real> centre(3 * n, -0.0); // the other ranks add -0: exact
  for (size_t j = 0; j < n; ++j)
    if (_m.joint_gauges[j].anchor >= 0)
    {
      auto x = Kokkos::create_mirror_view_and_copy(
          HostSpace(), Kokkos::subview(_m.nodes.x, _m.joint_gauges[j].anchor, Kokkos::ALL));
      for (int i = 0; i < 3; ++i)
        centre[3 * j + size_t(i)] = x(i);
    }
  if (_m.dd)
    allReduceSum(centre.data(), int(centre.size()), _m.comm);
  constexpr int K = JointGaugeSums::kCount;
  std::vector<Real> sums(n * K, 0.0);
  for (size_t j = 0; j < n; ++j)
  {
    const Real r = _m.joint_gauges[j].radius;
    const Real radius = r > 0 ? r : 0.5 * _m.contact->largestFaceSize();
    const JointGaugeSums s =
        jointGaugeSums(_m.contact->planes(), _m.contact->faces(), &centre[3 * j], radius);
    std::copy(s.begin(), s.begin() + K, sums.begin() + long(j * K));
  }
  if (_m.dd)
    allReduceSum(sums.data(), int(sums.size()), _m.comm);
  for (size_t k = 0; k < _m.gauges.size(); ++k)
    if (_m.gauges[k].joint >= 0)
    {
      JointGaugeSums s;
      std::copy(sums.begin() + long(size_t(_m.gauges[k].joint) * K),
                sums.begin() + long(size_t(_m.gauges[k].joint) * K + K), s.begin());
      out[k] = jointGaugeQuantity(s, _m.gauges[k].quantity);
    }
}

EnergyReport Solver::energies() const
{
  EnergyReport r;
  auto mass = _m.elems.mass, energy = _m.elems.energy, hg = _m.elems.hourglass_energy;
  auto eroded = _m.elems.eroded; // an eroded element's energy is in _eroded_energy
  Real internal = 0, hourglass = 0;
  Kokkos::parallel_reduce(
      "scpdyn::output::internalEnergy", Kokkos::RangePolicy<ExecSpace>(0, _m.elems.count),
      KOKKOS_LAMBDA(const Index e, Real &s) { s += eroded(e) ? 0 : mass(e) * energy(e); },
      internal);
  Kokkos::parallel_reduce(
      "scpdyn::output::hourglassEnergy", Kokkos::RangePolicy<ExecSpace>(0, _m.elems.count),
      KOKKOS_LAMBDA(const Index e, Real &s) { s += eroded(e) ? 0 : hg(e); }, hourglass);
  if (_m.contact) // work done on the joints = stored + dissipated (closes the balance)
  {
    r.contact = _m.contact->energy();
    r.contact_dissipation = _m.contact->dissipatedEnergy();
  }
  if (_m.dd)
  {
    Real sums[4] = {internal, hourglass, r.contact, r.contact_dissipation};
    allReduceSum(sums, 4, _m.comm);
    internal = sums[0];
    hourglass = sums[1];
    r.contact = sums[2];
    r.contact_dissipation = sums[3];
  }
  r.internal = internal;
  r.hourglass = hourglass;
  r.kinetic = _last_sums.kinetic;
  for (int i = 0; i < 3; ++i)
    r.momentum[i] = _last_sums.momentum[i];
  r.external_work = _external_work;
  r.damping = -_damping_work;
  // the leapfrog conserves 1/2 m v^n.v^{n+1} + IE(x^{n+1/2}) (verification.md T1)
  r.eroded = _eroded_energy;
  r.eroded_elements = _eroded_elements;
  const Real total = _kinetic_mid + internal + hourglass + r.contact + _eroded_energy;
  const Real scale = std::max({_energy_scale, std::abs(_initial_energy) + std::abs(_external_work),
                               std::numeric_limits<Real>::min()});
  r.balance_error = (total - _initial_energy - _external_work - _damping_work) / scale;
  return r;
}

} // namespace scpdyn
