#include "driver/Outputs.hpp"

#include "driver/Solver.hpp"

#include "contact/ContactSystem.hpp"
#include "material/MaterialLibrary.hpp"

#include <map>

#include <cmath>
#include <cstdio>

namespace scpdyn
{
namespace
{
std::vector<double> toVector(const VectorView &v, Index count)
{
  auto h = Kokkos::create_mirror_view_and_copy(HostSpace(), v);
  return std::vector<double>(h.data(), h.data() + size_t(count) * 3);
}
} // namespace

Outputs::Outputs(const Solver &solver, const std::string &dir) : _solver(solver), _dir(dir)
{
  ensureDirectory(dir);
  _start = _last_progress = std::chrono::steady_clock::now();
}

Outputs::~Outputs() = default;

void Outputs::begin()
{
  const Deck &deck = _solver.deck();
  writeResolvedDeck(deck, _dir + "/deck.resolved.yaml");

  FieldMeshDesc desc;
  desc.dim = deck.dimension;
  desc.coords0 = toVector(_solver.nodes().x0, _solver.nodes().count);
  auto conn = Kokkos::create_mirror_view_and_copy(HostSpace(), _solver.elements().conn);
  for (const auto &g : _solver.groups())
    for (Index e = g.begin; e < g.end; ++e)
    {
      desc.cell_types.push_back(int(g.type));
      for (int a = 0; a < nodesPerElement(g.type); ++a)
        desc.connectivity.push_back(conn(e, a));
    }
  _fields = std::make_unique<FieldWriter>(_dir, desc);
  if (_solver.contact())
    _contacts = std::make_unique<PointSetWriter>(_dir, "contacts");

  _history = std::make_unique<CsvWriter>(
      _dir + "/history.csv",
      std::vector<std::string>{"time", "cycle", "dt", "kinetic", "internal", "hourglass",
                               "external_work", "contact", "energy_balance_error", "momentum_x",
                               "momentum_y", "momentum_z", "contact_dissipation"});
  std::vector<std::string> columns{"time"};
  for (const auto &g : _solver.gauges())
    columns.push_back(g.column);
  _gauges = std::make_unique<CsvWriter>(_dir + "/gauges.csv", columns);
  writeFrame();
  writeRows();
  _next_field = deck.field_interval;
  _next_history = deck.history_interval;
}

void Outputs::writeFrame()
{
  if (_last_frame_cycle == _solver.cycles())
    return;
  _last_frame_cycle = _solver.cycles();
  const NodeFields &nodes = _solver.nodes();
  const ElementFields &el = _solver.elements();
  FieldFrame f;
  f.time = _solver.time();
  f.cycle = _solver.cycles();
  f.coords = toVector(nodes.x, nodes.count);
  std::vector<double> disp(f.coords.size());
  auto x0 = toVector(nodes.x0, nodes.count);
  for (size_t k = 0; k < disp.size(); ++k)
    disp[k] = f.coords[k] - x0[k];
  f.node_vectors.push_back({"displacement", disp});
  f.node_vectors.push_back({"velocity", toVector(nodes.v, nodes.count)});

  const size_t ne = size_t(el.count);
  auto stress = Kokkos::create_mirror_view_and_copy(HostSpace(), el.stress);
  auto mass = Kokkos::create_mirror_view_and_copy(HostSpace(), el.mass);
  auto volume = Kokkos::create_mirror_view_and_copy(HostSpace(), el.volume);
  auto energy = Kokkos::create_mirror_view_and_copy(HostSpace(), el.energy);
  auto eps = Kokkos::create_mirror_view_and_copy(HostSpace(), el.plastic_strain);
  auto part = Kokkos::create_mirror_view_and_copy(HostSpace(), el.part);
  std::vector<double> s6(stress.data(), stress.data() + ne * 6), p(ne), rho(ne), e(ne), ep(ne),
      pt(ne);
  for (size_t k = 0; k < ne; ++k)
  {
    p[k] = -(stress(k, 0) + stress(k, 1) + stress(k, 2)) / 3;
    rho[k] = mass(k) / volume(k);
    e[k] = energy(k);
    ep[k] = eps(k);
    pt[k] = part(k);
  }
  // named material history slots (damage, tensile_strength, burn_fraction, ...): one cell
  // field per name, zero in elements whose material does not have it
  auto history = Kokkos::create_mirror_view_and_copy(HostSpace(), el.history);
  auto mat = Kokkos::create_mirror_view_and_copy(HostSpace(), el.material);
  std::vector<std::vector<std::string>> names;
  for (const auto &m : _solver.materialParams())
    names.push_back(historyNames(m));
  std::map<std::string, std::vector<double>> named;
  for (size_t k = 0; k < ne; ++k)
  {
    const auto &n = names[size_t(mat(k))];
    for (size_t slot = 0; slot < n.size(); ++slot)
      if (!n[slot].empty())
      {
        auto &field = named[n[slot]];
        field.resize(ne, 0.0);
        field[k] = history(k, slot);
      }
  }
  f.cell_tensors6.push_back({"stress", s6});
  f.cell_scalars = {{"pressure", p}, {"density", rho}, {"specific_internal_energy", e},
                    {"plastic_strain", ep}, {"part", pt}};
  for (auto &kv : named)
    f.cell_scalars.push_back({kv.first, std::move(kv.second)});
  _fields->write(f);
  writeContactFrame();
}

void Outputs::writeContactFrame()
{
  if (!_contacts)
    return;
  const ContactPointsHost c = _solver.contact()->points();
  PointFrame f;
  f.time = _solver.time();
  f.cycle = _solver.cycles();
  f.points = c.poc;
  f.scalars = {{"area", c.area},           {"normal_force", c.normal_force},
               {"shear_force", c.shear_force}, {"closure", c.closure},
               {"slip", c.slip},           {"state", c.state},
               {"face1_key", c.key1},      {"face2_key", c.key2}};
  _contacts->write(f);
}

void Outputs::writeRows()
{
  if (_last_row_cycle == _solver.cycles())
    return;
  _last_row_cycle = _solver.cycles();
  const EnergyReport r = _solver.energies();
  _last_balance_error = r.balance_error;
  _max_balance_error = std::max(_max_balance_error, std::abs(r.balance_error));
  _history->row({_solver.time(), double(_solver.cycles()), _solver.dt(), r.kinetic, r.internal,
                 r.hourglass, r.external_work, r.contact, r.balance_error, r.momentum[0],
                 r.momentum[1], r.momentum[2], r.contact_dissipation});
  std::vector<double> row{_solver.time()};
  for (Real v : _solver.gaugeValues())
    row.push_back(v);
  _gauges->row(row);
}

void Outputs::afterCycle()
{
  const Deck &deck = _solver.deck();
  const double t = _solver.time();
  const double eps = 1e-9 * deck.end_time;
  if (deck.field_interval > 0 && t >= _next_field - eps)
  {
    writeFrame();
    while (_next_field <= t + eps)
      _next_field += deck.field_interval;
  }
  if (deck.history_interval <= 0 || t >= _next_history - eps)
  {
    writeRows();
    while (deck.history_interval > 0 && _next_history <= t + eps)
      _next_history += deck.history_interval;
  }
  const auto now = std::chrono::steady_clock::now();
  if (std::chrono::duration<double>(now - _last_progress).count() >= deck.progress_interval)
  {
    _last_progress = now;
    const double wall = std::chrono::duration<double>(now - _start).count();
    const double frac = t / deck.end_time;
    std::fprintf(stderr, "scpdyn: cycle %ld  t = %.4e s  dt = %.3e s  %5.1f%%  ETA %.1f s\n",
                 _solver.cycles(), t, _solver.dt(), 100 * frac,
                 frac > 0 ? wall * (1 - frac) / frac : 0.0);
  }
}

void Outputs::finish(const std::string &error)
{
  writeFrame();
  writeRows();
  _history->close();
  _gauges->close();
  _fields->close();
  if (_contacts)
    _contacts->close();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - _start).count();
  JsonObject timers;
  double cycle_time = 0;
  for (const auto &kv : _solver.timers().seconds())
  {
    timers.add(kv.first, kv.second);
    cycle_time += kv.second;
  }
  const double element_cycles = double(_solver.elements().count) * double(_solver.cycles());
  JsonObject s;
  s.add("title", _solver.deck().title)
      .add("status", error.empty() ? std::string("completed") : std::string("failed"))
      .add("error", error)
      .add("cycles", _solver.cycles())
      .add("end_time", _solver.time())
      .add("wall_time", wall)
      .add("cycle_time", cycle_time)
      .add("timers", timers)
      .add("ranks", 1)
      .add("threads", int(ExecSpace().concurrency()))
      .add("nodes", long(_solver.nodes().count))
      .add("elements", long(_solver.elements().count))
      .add("energy_balance_error", std::abs(_last_balance_error))
      .add("energy_balance_error_max", _max_balance_error)
      .add("common_planes_max", long(_solver.contact() ? _solver.contact()->maxCount() : 0))
      .add("element_cycles_per_second", cycle_time > 0 ? element_cycles / cycle_time : 0.0)
      .add("ns_per_element_cycle", element_cycles > 0 ? 1e9 * cycle_time / element_cycles : 0.0);
  writeJson(_dir + "/summary.json", s);
}

} // namespace scpdyn
