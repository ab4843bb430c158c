// Energies, gauges: what the solver reports about its state.
#include "driver/Solver.hpp"

#include "contact/ContactSystem.hpp"
#include "contact/JointGauge.hpp"
#include "driver/Decomposition.hpp"
#include "parallel/Mpi.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace scpdyn
{

void Solver::setupGauges()
{
  // gauges are resolved on the whole mesh (every rank alike), then kept by the rank that owns
  // the node or holds the element; the others keep id -1
  const HostMesh &mesh = _global_mesh ? *_global_mesh : _mesh;
  std::vector<Index> ids;
  std::vector<Index> codes;
  for (size_t g = 0; g < _deck.gauges.size(); ++g)
  {
    const GaugeSpec &spec = _deck.gauges[g];
    const std::string key = _deck.path + ": gauges[" + std::to_string(g) + "]";
    if (spec.kind == GaugeKind::Joint && !_contact)
      throw InputError(key + ".kind: a joint gauge needs a 'contact' section");
    const bool on_element = spec.kind == GaugeKind::Element;
    Index id = spec.id;
    if (spec.has_point)
    {
      // nearest node, or the element with the nearest centroid
      Real best = std::numeric_limits<Real>::max();
      const Index count = on_element ? mesh.numElements() : mesh.numNodes();
      Index e_first = 0;
      size_t part = 0;
      for (Index k = 0; k < count; ++k)
      {
        Real c[3] = {0, 0, 0};
        if (on_element)
        {
          while (k >= e_first + mesh.parts[part].numElements())
            e_first += mesh.parts[part++].numElements();
          const HostPart &p = mesh.parts[part];
          const int nn = nodesPerElement(p.type);
          for (int a = 0; a < nn; ++a)
            for (int i = 0; i < 3; ++i)
              c[i] += mesh.coords[size_t(p.connectivity[size_t((k - e_first) * nn + a)])][size_t(i)] / nn;
        }
        else
          for (int i = 0; i < 3; ++i)
            c[i] = mesh.coords[size_t(k)][size_t(i)];
        Real d = 0;
        for (int i = 0; i < 3; ++i)
          d += (c[i] - spec.point[size_t(i)]) * (c[i] - spec.point[size_t(i)]);
        if (d < best)
        {
          best = d;
          id = k;
        }
      }
    }
    const Index limit = on_element ? mesh.numElements() : mesh.numNodes();
    if (id < 0 || id >= limit)
      throw InputError(key + ": " + (on_element ? "element " : "node ") + std::to_string(id) +
                       " does not exist (the mesh has " + std::to_string(limit) + ")");
    Index device_id = on_element ? _host_to_device_element[size_t(id)] : id;
    if (_dd)
    {
      const auto &map = on_element ? _dd->global_element : _dd->global_node;
      const auto it = std::lower_bound(map.begin(), map.end(), id);
      const Index local = it != map.end() && *it == id ? Index(it - map.begin()) : -1;
      device_id = local < 0                          ? -1
                  : on_element                       ? _host_to_device_element[size_t(local)]
                  : _dd->owned[size_t(local)] != 0   ? local
                                                     : -1;
    }
    const bool joint = spec.kind == GaugeKind::Joint; // the nearest node carries it with the material
    const auto &names = gaugeQuantities(spec.kind);
    for (const auto &q : spec.quantities)
    {
      const int code = int(std::find(names.begin(), names.end(), q) - names.begin());
      if (code == int(names.size()))
        throw InputError(key + ".quantities: unknown quantity '" + q + "' for a " + deckName(spec.kind) +
                         " gauge");
      // a joint gauge's slot is filled by jointGaugeValues(); the kernel leaves it at 0
      const Index slot_id = joint ? -1 : device_id;
      _gauges.push_back({spec.name + ":" + q, on_element, slot_id, code,
                         joint ? int(_joint_gauges.size()) : -1});
      ids.push_back(slot_id);
      codes.push_back(joint ? 0 : code + (on_element ? 100 : 0));
    }
    if (joint)
      _joint_gauges.push_back({device_id, spec.radius});
  }
  _gauge_id = IndexView("gauge_id", ids.size());
  _gauge_code = IndexView("gauge_code", codes.size());
  auto h_id = Kokkos::create_mirror_view(_gauge_id);
  auto h_code = Kokkos::create_mirror_view(_gauge_code);
  for (size_t k = 0; k < ids.size(); ++k)
  {
    h_id(k) = ids[k];
    h_code(k) = codes[k];
  }
  Kokkos::deep_copy(_gauge_id, h_id);
  Kokkos::deep_copy(_gauge_code, h_code);
}

std::vector<Real> Solver::gaugeValues() const
{
  const size_t count = _gauges.size();
  if (count == 0)
    return {};
  RealView values("gauge_values", count);
  auto id = _gauge_id;
  auto code = _gauge_code;
  auto x = _nodes.x, x0 = _nodes.x0, v = _nodes.v;
  auto stress = _elems.stress;
  auto mass = _elems.mass, volume = _elems.volume, energy = _elems.energy;
  auto eps = _elems.plastic_strain, q = _elems.q;
  Kokkos::parallel_for(
      "scpdyn::output::gauges", Kokkos::RangePolicy<ExecSpace>(0, Index(count)),
      KOKKOS_LAMBDA(const Index g) {
        const Index k = id(g);
        const int c = code(g);
        Real value = 0;
        if (k < 0)
          ; // another rank's gauge
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
  if (_dd) // exact: one rank holds each value, the others add zeros
    allReduceSum(out.data(), int(count), _comm);
  if (!_joint_gauges.empty())
    jointGaugeValues(out);
  return out;
}

void Solver::jointGaugeValues(std::vector<Real> &out) const
{
  // the anchor nodes' positions from the ranks that own them; then each rank's sums over its
  // CPs near them, added over the ranks; then the quantities
  const size_t n = _joint_gauges.size();
  std::vector<Real> centre(3 * n, 0.0);
  for (size_t j = 0; j < n; ++j)
    if (_joint_gauges[j].anchor >= 0)
    {
      auto x = Kokkos::create_mirror_view_and_copy(
          HostSpace(), Kokkos::subview(_nodes.x, _joint_gauges[j].anchor, Kokkos::ALL));
      for (int i = 0; i < 3; ++i)
        centre[3 * j + size_t(i)] = x(i);
    }
  if (_dd)
    allReduceSum(centre.data(), int(centre.size()), _comm);
  constexpr int K = JointGaugeSums::kCount;
  std::vector<Real> sums(n * K, 0.0);
  for (size_t j = 0; j < n; ++j)
  {
    const Real r = _joint_gauges[j].radius;
    const Real radius = r > 0 ? r : 0.5 * _contact->largestFaceSize();
    const JointGaugeSums s =
        jointGaugeSums(_contact->planes(), _contact->faces(), &centre[3 * j], radius);
    std::copy(s.begin(), s.begin() + K, sums.begin() + long(j * K));
  }
  if (_dd)
    allReduceSum(sums.data(), int(sums.size()), _comm);
  for (size_t k = 0; k < _gauges.size(); ++k)
    if (_gauges[k].joint >= 0)
    {
      JointGaugeSums s;
      std::copy(sums.begin() + long(size_t(_gauges[k].joint) * K),
                sums.begin() + long(size_t(_gauges[k].joint) * K + K), s.begin());
      out[k] = jointGaugeQuantity(s, _gauges[k].quantity);
    }
}

EnergyReport Solver::energies() const
{
  EnergyReport r;
  auto mass = _elems.mass, energy = _elems.energy, hg = _elems.hourglass_energy;
  Real internal = 0, hourglass = 0;
  Kokkos::parallel_reduce(
      "scpdyn::output::internalEnergy", Kokkos::RangePolicy<ExecSpace>(0, _elems.count),
      KOKKOS_LAMBDA(const Index e, Real &s) { s += mass(e) * energy(e); }, internal);
  Kokkos::parallel_reduce(
      "scpdyn::output::hourglassEnergy", Kokkos::RangePolicy<ExecSpace>(0, _elems.count),
      KOKKOS_LAMBDA(const Index e, Real &s) { s += hg(e); }, hourglass);
  if (_contact) // work done on the joints = stored + dissipated (closes the balance)
  {
    r.contact = _contact->energy();
    r.contact_dissipation = _contact->dissipatedEnergy();
  }
  if (_dd)
  {
    Real sums[4] = {internal, hourglass, r.contact, r.contact_dissipation};
    allReduceSum(sums, 4, _comm);
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
  // the leapfrog conserves 1/2 m v^n.v^{n+1} + IE(x^{n+1/2}) (verification.md T1)
  const Real total = _kinetic_mid + internal + hourglass + r.contact;
  const Real scale = std::max({_energy_scale, std::abs(_initial_energy) + std::abs(_external_work),
                               std::numeric_limits<Real>::min()});
  r.balance_error = (total - _initial_energy - _external_work) / scale;
  return r;
}

} // namespace scpdyn
