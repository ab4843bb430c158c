// The Solver's state in a restart file: everything a cycle reads from the one before it
// (driver/Solver.hpp, model/Model.hpp, contact/ContactSystem.hpp). The mesh, the materials'
// parameters, the boundary conditions' definitions and the masses come from the deck again.
#include "driver/Restart.hpp"

#include "contact/ContactSystem.hpp"
#include "core/HostCopy.hpp"
#include "core/InputError.hpp"
#include "driver/OutputGather.hpp"
#include "driver/Solver.hpp"
#include "io/RestartFile.hpp"
#include "parallel/Decomposition.hpp"
#include "parallel/Mpi.hpp"

#include <memory>

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
  fn("nodes.damping_impulse", n.damping_impulse);
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

namespace
{
/// \brief This rank's nodes and elements in the file's order: the global node id, and the
/// serial device order of the elements (one rank: the local order). Collective.
class GlobalOrder
{
public:
  explicit GlobalOrder(const Model &m) : _m(m)
  {
    if (m.dd)
      _gather = std::make_unique<OutputGather>(m.comm, *m.dd);
  }
  long nodeRow(Index n) const { return _m.dd ? long(_m.dd->global_node[size_t(n)]) : long(n); }
  long elementRow(Index e) const { return _m.dd ? long(_m.dd->output_cell[size_t(e)]) : long(e); }
  long nodes() const { return _m.globalNodeCount(); }
  long elements() const { return _m.globalElementCount(); }
  /// \brief `local` (`ncomp` values per local node or element, extra rows ignored) in the
  /// file's order on rank 0.
  std::vector<double> gatherNodes(std::vector<double> local, int ncomp) const
  {
    local.resize(size_t(_m.nodes.count) * size_t(ncomp));
    return _gather ? _gather->nodes(local, ncomp) : local;
  }
  std::vector<double> gatherElements(std::vector<double> local, int ncomp) const
  {
    local.resize(size_t(_m.elems.count) * size_t(ncomp));
    return _gather ? _gather->cells(local, ncomp) : local;
  }

private:
  const Model &_m;
  std::unique_ptr<OutputGather> _gather;
};

/// \brief The rows of `global` (file order, `ncomp` per row) that `row` picks for each of the
/// first `count` entries of `v`; the entries after them (ghost nodes) keep their values.
template <class View, class Row>
void scatterRows(const View &v, Index count, const std::vector<double> &global, int ncomp, Row row)
{
  if (v.extent(0) == 0)
    return;
  std::vector<double> flat = flatten(v);
  for (Index i = 0; i < count; ++i)
    for (int c = 0; c < ncomp; ++c)
      flat[size_t(i) * size_t(ncomp) + size_t(c)] =
          global[size_t(row(i)) * size_t(ncomp) + size_t(c)];
  unflatten(v, flat);
}
} // namespace

std::vector<Index> Solver::nodeSlotGlobalIds() const
{
  std::vector<Index> id(_m.nodes.x.extent(0), -1);
  for (Index n = 0; n < _m.nodes.count; ++n)
    id[size_t(n)] = globalNode(n);
  if (_m.dd && _m.dd->ghosts)
  {
    const std::vector<Index> &ghost = _m.dd->ghosts->ghostGlobal();
    for (size_t g = 0; g < ghost.size() && size_t(_m.nodes.count) + g < id.size(); ++g)
      id[size_t(_m.nodes.count) + g] = ghost[g];
  }
  return id;
}

void Solver::saveState(RestartWriter &out) const
{
  // the scalars are global (the reductions of step 12 give every rank the same), rank 0's
  out.put("solver.scalars",
          std::vector<double>{_time, _dt, _dt_next, double(_cycle), _external_work, _kinetic_mid,
                              _initial_energy, _energy_scale, _limits.element, _limits.contact,
                              _forces_zeroed ? 1.0 : 0.0, _last_sums.kinetic,
                              _last_sums.kinetic_mid, _last_sums.external_work,
                              _last_sums.momentum[0], _last_sums.momentum[1],
                              _last_sums.momentum[2], _eroded_energy, double(_eroded_elements)});
  out.put("solver.settling", std::vector<double>{_damping_work, _damped_last ? 1.0 : 0.0});
  putStep(out, "solver.smallest_step", _smallest_step);
  putStep(out, "solver.next_step", _next_step);
  putStep(out, "solver.first_step", _first_step);
  const GlobalOrder order(_m);
  // global ids in the file's order: a reader checks them against its own numbering
  std::vector<double> node_id(size_t(_m.nodes.count)), element_id(size_t(_m.elems.count));
  for (Index n = 0; n < _m.nodes.count; ++n)
    node_id[size_t(n)] = double(globalNode(n));
  for (Index e = 0; e < _m.elems.count; ++e)
    element_id[size_t(e)] = double(globalElement(meshElementOfDevice(e)));
  out.put("nodes.global_id", order.gatherNodes(node_id, 1));
  out.put("elements.global_id", order.gatherElements(element_id, 1));
  // a field a run does not keep (an empty View) is written empty
  eachNodeField(_m.nodes, [&](const char *name, const auto &v) {
    out.put(name,
            v.extent(0) ? order.gatherNodes(flatten(v), flatWidth(v)) : std::vector<double>());
  });
  eachElementField(_m.elems, [&](const char *name, const auto &v) {
    out.put(name,
            v.extent(0) ? order.gatherElements(flatten(v), flatWidth(v)) : std::vector<double>());
  });
  if (_m.contact)
    _m.contact->saveState(out, _m.dd ? _m.comm : MPI_COMM_NULL, nodeSlotGlobalIds(), _m.nodes.v);
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
  if (_m.deck.settling.active()) // a deck with a settling stage is a newer file's
  {
    const std::vector<double> settling = in.reals("solver.settling", 2);
    _damping_work = settling[0];
    _damped_last = settling[1] != 0;
  }
  _smallest_step = getStep(in, "solver.smallest_step");
  _next_step = getStep(in, "solver.next_step");
  _first_step = getStep(in, "solver.first_step");
  // every rank reads the same arrays and checks them alike: an error is every rank's
  const GlobalOrder order(_m);
  const std::vector<double> node_id = in.reals("nodes.global_id", order.nodes());
  const std::vector<double> element_id = in.reals("elements.global_id", order.elements());
  for (long n = 0; n < order.nodes(); ++n)
    if (node_id[size_t(n)] != double(n))
      throw InputError("restart file '" + in.path() + "': node numbering differs from this " +
                       "deck's (another mesh)");
  std::string mismatch;
  for (Index e = 0; e < _m.elems.count; ++e)
    if (element_id[size_t(order.elementRow(e))] != double(globalElement(meshElementOfDevice(e))))
      mismatch = "restart file '" + in.path() + "': element numbering differs from this " +
                 "deck's (another mesh)";
  const std::string error = _m.dd ? firstErrorOfAnyRank(mismatch, _m.comm) : mismatch;
  if (!error.empty())
    throw InputError(error);
  eachNodeField(_m.nodes, [&](const char *name, const auto &v) {
    const int c = v.extent(0) ? flatWidth(v) : 0;
    scatterRows(v, _m.nodes.count, in.reals(name, order.nodes() * c), c,
                [&](Index n) { return order.nodeRow(n); });
  });
  eachElementField(_m.elems, [&](const char *name, const auto &v) {
    const int c = v.extent(0) ? flatWidth(v) : 0;
    scatterRows(v, _m.elems.count, in.reals(name, order.elements() * c), c,
                [&](Index e) { return order.elementRow(e); });
  });
  // the held parts released by then (the velocities are the file's)
  markReleased(_m.release, _time, _m.nodes);
  // the values step 12 of the last cycle set, at the time it ended (the same bits)
  updateVelocityValues(_m.bc, _time);
  if (_m.contact)
  {
    // the faces erosion had exposed; then the ghost faces at the restart positions hold the
    // faces of every CP of this rank
    _m.contact->loadErosion(in);
    if (_m.dd)
    {
      _m.dd->own_faces = _m.contact->ownFaces();
      rebuildGhostFaces();
    }
    _m.contact->loadState(in, _m.dd ? _m.comm : MPI_COMM_NULL, nodeSlotGlobalIds());
    if (_m.dd && !_m.contact->searchDue(_cycle))
      restrictGhosts();
  }
  _gravity = gravityAt(_time);
}

} // namespace scpdyn
