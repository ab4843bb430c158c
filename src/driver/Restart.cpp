// The Solver's state in a restart file: everything a cycle reads from the one before it
// (driver/Solver.hpp, model/Model.hpp, contact/ContactSystem.hpp). The mesh, the materials'
// parameters, the boundary conditions' definitions and the masses come from the deck again.
#include "driver/Restart.hpp"

#include "contact/ContactSystem.hpp"
#include "core/HostCopy.hpp"
#include "core/InputError.hpp"
#include "driver/Solver.hpp"
#include "io/RestartFile.hpp"

namespace scpdyn
{
namespace
{
std::vector<int> textCodes(const std::string &s) { return std::vector<int>(s.begin(), s.end()); }
std::string codesText(const std::vector<int> &c) { return std::string(c.begin(), c.end()); }

void putStep(RestartWriter &out, const std::string &name, const Solver::SmallestStep &s)
{
  out.put(name, std::vector<double>{s.dt, s.time, double(s.cycle)});
  out.put(name + "_control", textCodes(s.control));
}

Solver::SmallestStep getStep(const RestartReader &in, const std::string &name)
{
  const std::vector<double> v = in.reals(name, 3);
  Solver::SmallestStep s;
  s.dt = v[0];
  s.time = v[1];
  s.cycle = long(v[2]);
  s.control = codesText(in.ints(name + "_control"));
  return s;
}

/// The views of one entity a cycle carries over, by name (empty views are skipped alike on
/// writing and reading).
template <class Fn>
void eachNodeField(const NodeFields &n, Fn &&fn)
{
  fn("nodes.x", n.x);
  fn("nodes.v", n.v);
  fn("nodes.f_int", n.f_int);
  fn("nodes.f_contact", n.f_contact);
  fn("nodes.f_ext", n.f_ext);
  fn("nodes.external_impulse", n.external_impulse);
  fn("nodes.reaction", n.reaction);
}

template <class Fn>
void eachElementField(const ElementFields &e, Fn &&fn)
{
  fn("elements.volume", e.volume);
  fn("elements.stress", e.stress);
  fn("elements.energy", e.energy);
  fn("elements.plastic_strain", e.plastic_strain);
  fn("elements.q", e.q);
  fn("elements.sound_speed", e.sound_speed);
  fn("elements.hourglass_energy", e.hourglass_energy);
  fn("elements.history", e.history);
  fn("elements.hourglass", e.hourglass);
  fn("elements.eroded", e.eroded);
}
} // namespace

std::string restartDeckHash(const Deck &deck)
{
  Deck d = deck;
  d.path.clear();
  const Deck defaults;
  d.output_dir.clear();
  d.field_interval = defaults.field_interval;
  d.history_interval = defaults.history_interval;
  d.progress_interval = defaults.progress_interval;
  d.max_output_bytes = defaults.max_output_bytes;
  d.restart_interval = defaults.restart_interval;
  d.restart_keep = defaults.restart_keep;
  d.end_time = defaults.end_time;
  d.max_cycles = defaults.max_cycles;
  return textHash(resolvedDeckText(d));
}

std::string restartFileName(const std::string &dir, long cycle)
{
  return dir + "/restart_" + std::to_string(cycle) + ".h5";
}

void Solver::saveState(RestartWriter &out) const
{
  out.put("solver.scalars",
          std::vector<double>{_time, _dt, _dt_next, double(_cycle), _external_work, _kinetic_mid,
                              _initial_energy, _energy_scale, _limits.element, _limits.contact,
                              _forces_zeroed ? 1.0 : 0.0, _last_sums.kinetic,
                              _last_sums.kinetic_mid, _last_sums.external_work,
                              _last_sums.momentum[0], _last_sums.momentum[1],
                              _last_sums.momentum[2], _eroded_energy, double(_eroded_elements)});
  putStep(out, "solver.smallest_step", _smallest_step);
  putStep(out, "solver.next_step", _next_step);
  putStep(out, "solver.first_step", _first_step);
  // global ids: identity on one rank; a reader checks them against its own numbering
  std::vector<double> node_id(size_t(_m.nodes.count)), element_id(size_t(_m.elems.count));
  for (Index n = 0; n < _m.nodes.count; ++n)
    node_id[size_t(n)] = double(globalNode(n));
  for (Index e = 0; e < _m.elems.count; ++e)
    element_id[size_t(e)] = double(globalElement(meshElementOfDevice(e)));
  out.put("nodes.global_id", node_id);
  out.put("elements.global_id", element_id);
  eachNodeField(_m.nodes, [&](const char *name, const auto &v) { out.put(name, flatten(v)); });
  eachElementField(_m.elems, [&](const char *name, const auto &v) { out.put(name, flatten(v)); });
  out.put("bc.velocity_current", flatten(_m.bc.velocity_current));
  if (_m.contact)
    _m.contact->saveState(out);
}

void Solver::loadState(const RestartReader &in)
{
  const std::vector<double> s = in.reals("solver.scalars", 19);
  _time = s[0];
  _dt = s[1];
  _dt_next = s[2];
  _cycle = long(s[3]);
  _external_work = s[4];
  _kinetic_mid = s[5];
  _initial_energy = s[6];
  _energy_scale = s[7];
  _limits.element = s[8];
  _limits.contact = s[9];
  _forces_zeroed = s[10] != 0;
  _last_sums.kinetic = s[11];
  _last_sums.kinetic_mid = s[12];
  _last_sums.external_work = s[13];
  for (int i = 0; i < 3; ++i)
    _last_sums.momentum[i] = s[14 + size_t(i)];
  _eroded_energy = s[17];
  _eroded_elements = long(s[18]);
  _smallest_step = getStep(in, "solver.smallest_step");
  _next_step = getStep(in, "solver.next_step");
  _first_step = getStep(in, "solver.first_step");
  const std::vector<double> node_id = in.reals("nodes.global_id", _m.nodes.count);
  const std::vector<double> element_id = in.reals("elements.global_id", _m.elems.count);
  for (Index n = 0; n < _m.nodes.count; ++n)
    if (node_id[size_t(n)] != double(globalNode(n)))
      throw InputError("restart file '" + in.path() + "': node numbering differs from this " +
                       "deck's (another mesh)");
  for (Index e = 0; e < _m.elems.count; ++e)
    if (element_id[size_t(e)] != double(globalElement(meshElementOfDevice(e))))
      throw InputError("restart file '" + in.path() + "': element numbering differs from " +
                       "this deck's (another mesh)");
  auto load = [&](const char *name, const auto &v) {
    const long m = long(v.size());
    unflatten(v, in.reals(name, m));
  };
  eachNodeField(_m.nodes, load);
  eachElementField(_m.elems, load);
  load("bc.velocity_current", _m.bc.velocity_current);
  if (_m.contact)
    _m.contact->loadState(in);
  _gravity = gravityAt(_time);
}

} // namespace scpdyn
