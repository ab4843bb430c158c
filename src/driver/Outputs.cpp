#include "driver/Outputs.hpp"

#include "BuildCommit.hpp"
#include "driver/Preflight.hpp"
#include "driver/Restart.hpp"
#include "io/RestartFile.hpp"
#include "driver/Solver.hpp"

#include "contact/ContactSystem.hpp"
#include "core/InputError.hpp"
#include "parallel/Decomposition.hpp"
#include "material/MaterialLibrary.hpp"
#include "parallel/Mpi.hpp"

#include <algorithm>
#include <filesystem>
#include <limits>
#include <map>
#include <set>

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

/// Decomposed runs: every rank's CPs (each reported by one rank) on rank 0, in the serial order
/// (ascending face keys).
ContactPointsHost gatherPoints(const ContactPointsHost &c, MPI_Comm comm)
{
  ContactPointsHost mine = c;
  const std::vector<std::vector<double> *> fields = mine.scalars();
  const size_t n = mine.area.size();
  const int width = 3 + int(fields.size());
  std::vector<double> rows;
  for (size_t p = 0; p < n; ++p)
  {
    rows.insert(rows.end(), mine.poc.begin() + long(3 * p), mine.poc.begin() + long(3 * p + 3));
    for (auto *f : fields)
      rows.push_back((*f)[p]);
  }
  const int rank = mpiRank(comm), size = mpiSize(comm);
  int count = int(rows.size());
  std::vector<int> counts(static_cast<size_t>(size)), displs(static_cast<size_t>(size), 0);
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
  for (int r = 1; r < size; ++r)
    displs[size_t(r)] = displs[size_t(r - 1)] + counts[size_t(r - 1)];
  std::vector<double> all(rank == 0 ? size_t(displs.back() + counts.back()) : 0);
  MPI_Gatherv(rows.data(), count, MPI_DOUBLE, all.data(), counts.data(), displs.data(), MPI_DOUBLE,
              0, comm);
  ContactPointsHost out;
  const size_t total = all.size() / size_t(width);
  std::vector<size_t> order(total);
  for (size_t p = 0; p < total; ++p)
    order[p] = p;
  auto key = [&](size_t p, int k) { return all[p * size_t(width) + size_t(width - 2 + k)]; };
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return key(a, 0) < key(b, 0) || (key(a, 0) == key(b, 0) && key(a, 1) < key(b, 1));
  });
  const std::vector<std::vector<double> *> out_fields = out.scalars();
  for (size_t p : order)
  {
    const double *r = &all[p * size_t(width)];
    out.poc.insert(out.poc.end(), r, r + 3);
    for (size_t k = 0; k < out_fields.size(); ++k)
      out_fields[k]->push_back(r[3 + k]);
  }
  return out;
}

/// The files a run writes into its directory (and scripts/run.sh's plot of them), removed
/// before a run so that none of a previous run's is left beside this run's; a restarted run
/// that continues the directory's outputs keeps those it continues (kContinuedFiles).
const std::vector<std::string> kContinuedFiles = {"fields.xmf",  "fields.h5",   "contacts.xmf",
                                                  "contacts.h5", "history.csv", "gauges.csv",
                                                  "rcforc.csv",  "spcforc.csv", "matsum.csv"};
const std::vector<std::string> kReplacedFiles = {
    "summary.json",   "deck.resolved.yaml", "gauges.png",       "fields_pressure.png",
    "fields.xmf.tmp", "contacts.xmf.tmp",   "summary.json.tmp", "deck.resolved.yaml.tmp"};

} // namespace

namespace
{
/// Mean conjugate-gradient iterations of the cycles that solved ties alone (10.8); 0 without.
double tieIterationsMean(const ContactSystem *contact)
{
  return contact && contact->tieSolves() > 0
             ? double(contact->tieIterations()) / double(contact->tieSolves())
             : 0.0;
}
} // namespace

std::string formatBytes(double bytes)
{
  const char *units[] = {"B", "kB", "MB", "GB", "TB", "PB"};
  int u = 0;
  while (u < 5 && std::abs(bytes) >= 1000)
    bytes /= 1000, ++u;
  char text[48];
  std::snprintf(text, sizeof text, "%.3g %s", bytes, units[u]);
  return text;
}

namespace
{
// the widest "%.17g" number (-1.2345678901234567e-300) and its separator
constexpr double kCsvValueBytes = 25;
// HDF5 group and dataset headers of one frame, and the frame's share of the XDMF text
constexpr double kFrameOverheadBytes = 8192;
} // namespace

double nextOutputTime(double next, double interval, double t, double eps)
{
  const double due = t + eps;
  for (int step = 0; step < 64 && next <= due; ++step)
    next += interval;
  if (next > due)
    return next;
  const double multiple = (std::floor(due / interval) + 1) * interval;
  return std::isfinite(multiple) && multiple > due
             ? multiple
             : std::nextafter(due, std::numeric_limits<double>::infinity());
}

RunEstimate estimateRun(const Solver &solver)
{
  const Deck &deck = solver.deck();
  RunEstimate e;
  e.first_dt = solver.nextDt();
  const double end = deck.end_time;
  e.cycles = e.first_dt > 0 && std::isfinite(e.first_dt) ? std::ceil(end / e.first_dt)
                                                         : std::numeric_limits<double>::infinity();
  if (deck.max_cycles > 0)
    e.cycles = std::min(e.cycles, double(deck.max_cycles));
  // the first row and frame, one per interval (at most one per cycle), and the last
  auto periodic = [&](double interval) {
    return interval > 0 ? std::min(e.cycles, std::floor(end / interval) + 1) : e.cycles;
  };
  e.history_rows = 1 + periodic(deck.history_interval);
  e.frames = 1 + (deck.field_interval > 0 ? periodic(deck.field_interval) : 1);
  const double gauge_columns = solver.gauges().empty() ? 0 : 1 + double(solver.gauges().size());
  const RunHistoryColumns more = runHistoryColumns(deck);
  double more_columns = double(more.parts.size()) + 1;
  for (const auto *c : {&more.contact, &more.reactions})
    more_columns += c->empty() ? 0 : 1 + double(c->size());
  e.row_bytes = kCsvValueBytes * (13 + gauge_columns + more_columns);
  std::set<std::string> history_fields;
  for (const auto &m : solver.materialParams())
    for (const auto &n : historyNames(m))
      if (!n.empty())
        history_fields.insert(n);
  const double nodes = double(solver.globalNodeCount());
  const double cells = double(solver.globalElementCount());
  double contact_faces = solver.contact() ? double(solver.contact()->numOwnFaces()) : 0;
  if (solver.numRanks() > 1)
    contact_faces = allReduceSum(contact_faces, solver.comm());
  // coords, displacement, velocity; stress (6), 5 scalars, the named history fields; a
  // contact point: its position, vertex and 8 scalars, one CP per contact face at most
  e.frame_bytes = 8 * (9 * nodes + (11 + double(history_fields.size())) * cells) +
                  (3 * 8 + 4 + 8 * 8) * contact_faces +
                  kFrameOverheadBytes * (solver.contact() ? 2 : 1);
  const double mesh_bytes = 8 * 3 * nodes + 4 * (2 * kMaxElementNodes + 1) * cells;
  e.bytes = e.history_rows * e.row_bytes + e.frames * e.frame_bytes + mesh_bytes;
  return e;
}

std::string estimateRefusal(const Deck &deck, const RunEstimate &e)
{
  char text[640];
  if (!(e.cycles <= deck.max_estimated_cycles))
  {
    std::snprintf(text, sizeof text,
                  "time.max_estimated_cycles: the run needs about %.3g cycles (time.end %.3g s / "
                  "first time step %.3g s), more than the limit %.3g; check time.courant, "
                  "time.dt_max and the materials' moduli and densities, set time.max_cycles, or "
                  "raise time.max_estimated_cycles",
                  e.cycles, deck.end_time, e.first_dt, deck.max_estimated_cycles);
    return text;
  }
  if (!(e.bytes <= deck.max_output_bytes))
  {
    std::snprintf(text, sizeof text,
                  "output.max_output_bytes: the run would write about %s (%.3g history rows of "
                  "%s, %.3g field frames of %s), more than the limit %s; raise "
                  "output.history_interval or output.field_interval, or raise "
                  "output.max_output_bytes",
                  formatBytes(e.bytes).c_str(), e.history_rows, formatBytes(e.row_bytes).c_str(),
                  e.frames, formatBytes(e.frame_bytes).c_str(),
                  formatBytes(deck.max_output_bytes).c_str());
    return text;
  }
  return std::string();
}

Outputs::Outputs(const Solver &solver, const std::string &dir, const RestartReader *restart)
    : _solver(solver), _dir(dir)
{
  const RunEstimate e = estimateRun(solver);
  const std::string refusal = estimateRefusal(solver.deck(), e);
  if (!refusal.empty()) // the same numbers on every rank: all ranks stop here
    throw InputError(refusal);
  const Preflight p = preflight(solver, e);
  _preflight = preflightJson(p);
  if (root())
  {
    std::fputs(preflightText(p).c_str(), stdout);
    std::fflush(stdout); // before the progress lines on stderr, when both go to one terminal
  }
  std::string error;
  if (root())
    try
    {
      ensureDirectory(dir);
      _lock = std::make_unique<OutputDirectoryLock>(dir);
      if (!_lock->warning().empty())
        std::fprintf(stderr, "scpdyn: warning: %s\n", _lock->warning().c_str());
      // a restart into the directory of the run it continues goes on with that run's files;
      // into another directory it starts them afresh at the restart time
      if (restart && std::filesystem::is_regular_file(dir + "/history.csv"))
        _continued.rows = 0;
      std::vector<std::string> files = kReplacedFiles;
      if (_continued.rows < 0)
        files.insert(files.end(), kContinuedFiles.begin(), kContinuedFiles.end());
      const std::vector<std::string> removed = removeFiles(dir, files);
      if (!removed.empty() && _continued.rows < 0)
      {
        std::string names;
        for (const auto &n : removed)
          names += (names.empty() ? "" : ", ") + n;
        std::fprintf(stderr, "scpdyn: removed the previous run's outputs from %s: %s\n",
                     dir.c_str(), names.c_str());
      }
    }
    catch (const std::runtime_error &ex)
    {
      error = ex.what();
    }
  if (solver.numRanks() > 1)
    error = firstErrorOfAnyRank(error, solver.comm());
  if (!error.empty())
    throw InputError(error);
  if (solver.numRanks() > 1)
    MPI_Bcast(&_continued.rows, 1, MPI_LONG, 0, solver.comm());
  if (_continued.rows >= 0)
  {
    const std::vector<double> c = restart->reals("outputs.counts", 4);
    _rows = _continued.rows = long(c[0]);
    _frames = _continued_frames.frames = int(c[1]);
    _last_row_time = _continued.last_time = c[2];
    _last_frame_time = _continued_frames.last_time = c[3];
    if (root())
      std::fprintf(stderr,
                   "scpdyn: continuing the outputs in %s after cycle %ld (%ld rows, %ld frames "
                   "kept)\n",
                   dir.c_str(), solver.cycles(), _rows, _frames);
  }
  _start = _last_progress = std::chrono::steady_clock::now();
}

Outputs::~Outputs() = default;

bool Outputs::root() const { return _solver.rank() == 0; }

void Outputs::begin(const RestartReader *restart)
{
  const Deck &deck = _solver.deck();
  const DomainDecomposition *dd = _solver.decomposition();
  _has_contacts = _solver.contact() != nullptr;
  _has_sleepy = _has_contacts && _solver.contact()->hasSleepy();
  _material_used.assign(_solver.materialParams().size(), 0);
  {
    auto mat = Kokkos::create_mirror_view_and_copy(HostSpace(), _solver.elements().material);
    for (Index e = 0; e < _solver.elements().count; ++e)
      _material_used[size_t(mat(e))] = 1;
    if (dd && !_material_used.empty())
      MPI_Allreduce(MPI_IN_PLACE, _material_used.data(), int(_material_used.size()), MPI_INT,
                    MPI_MAX, _solver.comm());
  }
  if (root())
    writeResolvedDeck(deck, _dir + "/deck.resolved.yaml");

  FieldMeshDesc desc;
  desc.dim = deck.dimension;
  desc.coords0 = toVector(_solver.nodes().x0, _solver.nodes().count);
  auto conn = Kokkos::create_mirror_view_and_copy(HostSpace(), _solver.elements().conn);
  std::vector<int> rows; // decomposed: fixed-width rows of global node ids, -1 padded
  for (const auto &g : _solver.groups())
    for (Index e = g.begin; e < g.end; ++e)
    {
      desc.cell_types.push_back(int(g.type));
      for (int a = 0; a < nodesPerElement(g.type); ++a)
        desc.connectivity.push_back(conn(e, a));
      for (int a = 0; dd && a < kMaxElementNodes; ++a)
        rows.push_back(a < nodesPerElement(g.type) ? int(dd->global_node[size_t(conn(e, a))]) : -1);
    }
  FieldDistribution dist;
  if (dd)
  {
    std::vector<long> node_rows = ownedNodeRows(*dd), cell_rows = cellRows(*dd);
    dist.comm = _solver.comm();
    dist.node_rows = node_rows;
    dist.cell_rows = cell_rows;
    // the mesh goes to rank 0 once; the frames are written collectively (FieldDistribution)
    const OutputGather gather(_solver.comm(), dd->global_nodes, dd->global_elements,
                              std::move(node_rows), std::move(cell_rows));
    desc.coords0 = gather.nodes(desc.coords0, 3);
    desc.cell_types = gather.cellsInt(desc.cell_types, 1);
    rows = gather.cellsInt(rows, kMaxElementNodes);
    desc.connectivity.clear();
    for (size_t c = 0; c < desc.cell_types.size(); ++c)
      for (int a = 0; a < nodesPerElement(ElementType(desc.cell_types[c])); ++a)
        desc.connectivity.push_back(rows[c * kMaxElementNodes + size_t(a)]);
  }
  // a directory whose files cannot be continued is the user's choice of directory: an input
  // error, the same on every rank (the field file is opened by all, the others by rank 0)
  const std::string fix = "; give --restart another output directory (-o) to start the outputs "
                          "afresh at the restart time";
  try
  {
    _fields = dd ? std::make_unique<FieldWriter>(_dir, desc, dist, _continued_frames)
                 : std::make_unique<FieldWriter>(_dir, desc, _continued_frames);
  }
  catch (const std::runtime_error &e)
  {
    if (!continuesOutputs())
      throw;
    throw InputError(e.what() + fix);
  }
  _run_histories = std::make_unique<RunHistories>(_solver);
  std::string error;
  if (root())
    try
    {
      openRootWriters();
    }
    catch (const std::runtime_error &e)
    {
      if (!continuesOutputs())
        throw;
      error = e.what() + fix;
    }
  if (_solver.numRanks() > 1)
    error = firstErrorOfAnyRank(error, _solver.comm());
  if (!error.empty())
    throw InputError(error);
  startTimes(restart);
}

void Outputs::openRootWriters()
{
  const Deck &deck = _solver.deck();
  if (_has_contacts)
    _contacts = std::make_unique<PointSetWriter>(_dir, "contacts", -1.0, _continued_frames);

  std::vector<std::string> history{"time",
                                   "cycle",
                                   "dt",
                                   "kinetic",
                                   "internal",
                                   "hourglass",
                                   "external_work",
                                   "contact",
                                   "energy_balance_error",
                                   "momentum_x",
                                   "momentum_y",
                                   "momentum_z",
                                   "contact_dissipation"};
  if (_has_sleepy)
    history.push_back("failed_contacts");
  history.push_back("eroded_energy");
  history.push_back("eroded_elements");
  if (deck.settling.active())
    history.push_back("damping_energy");
  _history = std::make_unique<CsvWriter>(_dir + "/history.csv", history, _continued);
  std::vector<std::string> columns{"time"};
  for (const auto &g : _solver.gauges())
    columns.push_back(g.column);
  if (!_solver.gauges().empty())
    _gauges = std::make_unique<CsvWriter>(_dir + "/gauges.csv", columns, _continued);
  const RunHistoryColumns more = runHistoryColumns(deck);
  auto csv = [&](const char *name, const std::vector<std::string> &names) {
    std::vector<std::string> all{"time"};
    all.insert(all.end(), names.begin(), names.end());
    return names.empty() ? nullptr
                         : std::make_unique<CsvWriter>(_dir + "/" + name, all, _continued);
  };
  _rcforc = _has_contacts ? csv("rcforc.csv", more.contact) : nullptr;
  _spcforc = csv("spcforc.csv", more.reactions);
  _matsum = csv("matsum.csv", more.parts);
}

void Outputs::startTimes(const RestartReader *restart)
{
  const Deck &deck = _solver.deck();
  if (!restart)
  {
    writeFrame();
    writeRows();
    _next_field = deck.field_interval;
    _next_history = deck.history_interval;
    _next_restart = deck.restart_interval;
    return;
  }
  // the restart cycle's frame and rows belong to the run that wrote the file
  _last_frame_cycle = _last_row_cycle = _solver.cycles();
  const std::vector<double> t = restart->reals("outputs.times", 5);
  _next_field = t[0];
  _next_history = t[1];
  _next_restart = t[2];
  _max_balance_error = t[3];
  _last_balance_error = t[4];
}

void Outputs::writeRestart()
{
  const std::string path = restartFileName(_dir, _solver.cycles());
  if (!_restart_files.empty() && _restart_files.back() == path)
    return;
  // the rows the file counts are on disk before the file is: a restart continues after them
  for (CsvWriter *c : {_history.get(), _gauges.get(), _rcforc.get(), _spcforc.get(), _matsum.get()})
    if (c)
      c->flush();
  RestartWriter w(path, restartDeckHash(_solver.deck()),
                  _solver.numRanks() > 1 ? _solver.comm() : MPI_COMM_NULL);
  _solver.saveState(w);
  w.put("outputs.times", std::vector<double>{_next_field, _next_history, _next_restart,
                                             _max_balance_error, _last_balance_error});
  w.put("outputs.counts",
        std::vector<double>{double(_rows), double(_frames), _last_row_time, _last_frame_time});
  w.commit();
  _restart_files.push_back(path);
  while (int(_restart_files.size()) > _solver.deck().restart_keep)
  {
    std::error_code ec;
    if (root())
      std::filesystem::remove(_restart_files.front(), ec);
    _restart_files.pop_front();
  }
}

void Outputs::writeFrame()
{
  if (_last_frame_cycle == _solver.cycles())
    return;
  _last_frame_cycle = _solver.cycles();
  ++_frames;
  _last_frame_time = _solver.time();
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
  auto eroded = Kokkos::create_mirror_view_and_copy(HostSpace(), el.eroded);
  std::vector<double> s6(ne * 6), p(ne), rho(ne), e(ne), ep(ne), pt(ne), er(ne);
  for (size_t k = 0; k < ne; ++k)
  {
    for (int j = 0; j < 6; ++j)
      s6[6 * k + size_t(j)] = stress(k, j);
    p[k] = -(stress(k, 0) + stress(k, 1) + stress(k, 2)) / 3;
    rho[k] = mass(k) / volume(k);
    e[k] = energy(k);
    ep[k] = eps(k);
    pt[k] = part(k);
    er[k] = eroded(k) != 0 ? 1 : 0;
  }
  // named material history slots (damage, tensile_strength, burn_fraction, ...): one cell
  // field per name, zero in elements whose material does not have it
  auto history = Kokkos::create_mirror_view_and_copy(HostSpace(), el.history);
  auto mat = Kokkos::create_mirror_view_and_copy(HostSpace(), el.material);
  std::vector<std::vector<std::string>> names;
  for (const auto &m : _solver.materialParams())
    names.push_back(historyNames(m));
  std::map<std::string, std::vector<double>> named;
  if (_solver
          .decomposition()) // the fields every rank writes: those of the materials used on any rank
    for (size_t m = 0; m < names.size(); ++m)
      for (const auto &n : names[m])
        if (_material_used[m] && !n.empty())
          named[n].resize(ne, 0.0);
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
  f.cell_scalars = {{"pressure", p},
                    {"density", rho},
                    {"specific_internal_energy", e},
                    {"plastic_strain", ep},
                    {"part", pt}};
  if (_solver.elementControls().erosion)
    f.cell_scalars.push_back({"eroded", er});
  for (auto &kv : named)
    f.cell_scalars.push_back({kv.first, std::move(kv.second)});
  if (_fields)
    _fields->write(f);
  writeContactFrame();
}

void Outputs::writeContactFrame()
{
  if (!_has_contacts)
    return;
  ContactPointsHost c = _solver.contact()->points();
  if (_solver.numRanks() > 1)
    c = gatherPoints(c, _solver.comm());
  if (!root())
    return;
  PointFrame f;
  f.time = _solver.time();
  f.cycle = _solver.cycles();
  f.points = c.poc;
  f.scalars = {{"area", c.area},
               {"normal_force", c.normal_force},
               {"shear_force", c.shear_force},
               {"closure", c.closure},
               {"slip", c.slip},
               {"state", c.state},
               {"failed", c.failed},
               {"face1_key", c.key1},
               {"face2_key", c.key2}};
  if (_contacts)
    _contacts->write(f);
}

void Outputs::writeRows()
{
  if (_last_row_cycle == _solver.cycles())
    return;
  _last_row_cycle = _solver.cycles();
  ++_rows;
  _last_row_time = _solver.time();
  const EnergyReport r = _solver.energies();
  _last_balance_error = r.balance_error;
  _max_balance_error = std::max(_max_balance_error, std::abs(r.balance_error));
  std::vector<double> row{_solver.time()};
  for (Real v : _solver.gaugeValues())
    row.push_back(v);
  const RunHistories::Rows more = _run_histories->rows();
  const double failed = _has_sleepy ? double(_solver.contact()->failedCount()) : 0.0;
  if (!root())
    return;
  for (auto [writer, values] : {std::make_pair(_rcforc.get(), &more.contact),
                                std::make_pair(_spcforc.get(), &more.reactions),
                                std::make_pair(_matsum.get(), &more.parts)})
    if (writer)
    {
      std::vector<double> r{_solver.time()};
      r.insert(r.end(), values->begin(), values->end());
      writer->row(r);
    }
  std::vector<double> history{_solver.time(),       double(_solver.cycles()),
                              _solver.dt(),         r.kinetic,
                              r.internal,           r.hourglass,
                              r.external_work,      r.contact,
                              r.balance_error,      r.momentum[0],
                              r.momentum[1],        r.momentum[2],
                              r.contact_dissipation};
  if (_has_sleepy)
    history.push_back(failed);
  history.push_back(r.eroded);
  history.push_back(double(r.eroded_elements));
  if (_solver.deck().settling.active())
    history.push_back(r.damping);
  _history->row(history);
  if (_gauges)
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
    _next_field = nextOutputTime(_next_field, deck.field_interval, t, eps);
  }
  if (deck.history_interval <= 0 || t >= _next_history - eps)
  {
    writeRows();
    if (deck.history_interval > 0)
      _next_history = nextOutputTime(_next_history, deck.history_interval, t, eps);
  }
  if (deck.restart_interval > 0 && t >= _next_restart - eps)
  {
    _next_restart = nextOutputTime(_next_restart, deck.restart_interval, t, eps);
    writeRestart();
  }
  const auto now = std::chrono::steady_clock::now();
  if (root() &&
      std::chrono::duration<double>(now - _last_progress).count() >= deck.progress_interval)
  {
    _last_progress = now;
    const double wall = std::chrono::duration<double>(now - _start).count();
    // the run ends at the end time or at time.max_cycles, whichever comes first
    double frac = t / deck.end_time;
    if (deck.max_cycles > 0)
      frac = std::max(frac, double(_solver.cycles()) / double(deck.max_cycles));
    frac = std::min(frac, 1.0);
    std::fprintf(stderr, "scpdyn: cycle %ld  t = %.4e s  dt = %.3e s  %5.1f%%  ETA %.1f s\n",
                 _solver.cycles(), t, _solver.dt(), 100 * frac,
                 frac > 0 ? wall * (1 - frac) / frac : 0.0);
  }
}

void Outputs::finish(const std::string &error)
{
  finishWith(error.empty() ? "completed" : "failed", error, "");
}

void Outputs::finishInterrupted(const std::string &signal)
{
  finishWith("interrupted", "", signal);
}

void Outputs::finishWith(const std::string &status, const std::string &error,
                         const std::string &signal)
{
  writeFrame();
  writeRows();
  double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - _start).count();
  // per-step timers: the slowest rank's time (what the run waits for), and min / mean / max
  // over the ranks in timers_ranks
  std::vector<std::string> names;
  std::vector<double> mine;
  for (const auto &kv : _solver.timers().seconds())
  {
    names.push_back(kv.first);
    mine.push_back(kv.second);
  }
  mine.push_back(_solver.cycleWallTime());
  mine.push_back(wall);
  const int ranks = _solver.numRanks();
  std::vector<double> lo = mine, hi = mine, mean = mine;
  if (ranks > 1)
  {
    // the same steps ran on every rank (same deck), so the timer lists match
    MPI_Allreduce(mine.data(), lo.data(), int(mine.size()), MPI_DOUBLE, MPI_MIN, _solver.comm());
    MPI_Allreduce(mine.data(), hi.data(), int(mine.size()), MPI_DOUBLE, MPI_MAX, _solver.comm());
    allReduceSum(mean.data(), int(mean.size()), _solver.comm());
    for (double &m : mean)
      m /= ranks;
    wall = hi.back();
  }
  JsonObject decomposition;
  if (const DomainDecomposition *dd = _solver.decomposition())
  {
    // per rank: subdomain size and bytes sent per cycle (shared-node sums of steps 7, 9b and 10
    // and of the constraint solves, ghost copies of step 8, ghost rebuilds of step 4)
    const double cycles = std::max(1.0, double(_solver.cycles()));
    const double halo =
        double(dd->halo->bytesSent() - dd->halo_bytes_setup) + double(dd->ordered_bytes);
    const double ghost = dd->ghosts ? double(dd->ghosts->bytesGathered()) : 0.0;
    const double values[] = {double(_solver.elements().count),
                             double(_solver.nodes().count),
                             double(dd->halo->numSharedNodes()),
                             double(dd->halo->numNeighbours()),
                             dd->ghosts ? double(dd->ghosts->faces().size()) : 0.0,
                             dd->ghosts ? double(dd->ghosts->numGhostNodes()) : 0.0,
                             halo / cycles,
                             ghost / cycles,
                             double(dd->rebuild_bytes) / cycles,
                             (halo + ghost + double(dd->rebuild_bytes)) / cycles};
    const char *names[] = {"elements",
                           "nodes",
                           "shared_nodes",
                           "neighbours",
                           "ghost_faces",
                           "ghost_nodes",
                           "bytes_shared_node_sums_per_cycle",
                           "bytes_ghost_copies_per_cycle",
                           "bytes_ghost_rebuilds_per_cycle",
                           "bytes_per_cycle"};
    const int n = int(sizeof values / sizeof values[0]);
    std::vector<double> v_lo(values, values + n), v_hi = v_lo, v_mean = v_lo;
    MPI_Allreduce(values, v_lo.data(), n, MPI_DOUBLE, MPI_MIN, _solver.comm());
    MPI_Allreduce(values, v_hi.data(), n, MPI_DOUBLE, MPI_MAX, _solver.comm());
    allReduceSum(v_mean.data(), n, _solver.comm());
    for (int k = 0; k < n; ++k)
    {
      JsonObject st;
      st.add("min", v_lo[size_t(k)])
          .add("mean", v_mean[size_t(k)] / ranks)
          .add("max", v_hi[size_t(k)]);
      decomposition.add(names[k], st);
    }
  }
  _fields->close();                                       // collective in a decomposed run
  const EnergyReport final_energies = _solver.energies(); // collective too
  if (!root())
    return;
  _history->close();
  for (CsvWriter *w : {_gauges.get(), _rcforc.get(), _spcforc.get(), _matsum.get()})
    if (w)
      w->close();
  if (_contacts)
    _contacts->close();
  JsonObject timers, timer_stats;
  double cycle_time = 0;
  for (size_t k = 0; k < names.size(); ++k)
  {
    timers.add(names[k], hi[k]);
    JsonObject st;
    st.add("min", lo[k]).add("mean", mean[k]).add("max", hi[k]);
    timer_stats.add(names[k], st);
    cycle_time += hi[k];
  }
  const double element_cycles = double(_solver.globalElementCount()) * double(_solver.cycles());
  JsonObject s;
  s.add("title", _solver.deck().title)
      .add("deck", std::filesystem::absolute(_solver.deck().path).lexically_normal().string())
      .add("commit", std::string(SCPDYN_COMMIT))
      .add("status", status)
      .add("error", error);
  if (!signal.empty())
    s.add("interrupted_by", signal);
  s.add("cycles", _solver.cycles())
      .add("end_time", _solver.time())
      .add("wall_time", wall)
      .add("cycle_time", cycle_time)
      .add("cycle_wall_time", hi[hi.size() - 2])
      .add("timers", timers)
      .add("timers_ranks", timer_stats)
      .add("ranks", ranks)
      .add("threads", int(ExecSpace().concurrency()))
      .add("nodes", _solver.globalNodeCount())
      .add("nodes_in_element_sweep", _solver.sweepNodeCount())
      .add("elements", _solver.globalElementCount())
      .add("energy_balance_error", std::abs(_last_balance_error))
      .add("energy_balance_error_max", _max_balance_error)
      .add("common_planes_max", long(_solver.contact() ? _solver.contact()->maxCount() : 0))
      .add("contact_searches", long(_solver.contact() ? _solver.contact()->searches() : 0))
      .add("tie_iterations_mean", tieIterationsMean(_solver.contact()))
      .add("element_cycles_per_second", cycle_time > 0 ? element_cycles / cycle_time : 0.0)
      .add("ns_per_element_cycle", element_cycles > 0 ? 1e9 * cycle_time / element_cycles : 0.0);
  if (ranks > 1)
    s.add("decomposition", decomposition);
  const Solver::SmallestStep &small = _solver.smallestStep();
  JsonObject dt_min;
  dt_min.add("value", small.dt)
      .add("cycle", small.cycle)
      .add("time", small.time)
      .add("control", small.control);
  s.add("dt_min", dt_min);
  const EnergyReport &e = final_energies;
  JsonObject energies;
  energies.add("kinetic", e.kinetic)
      .add("internal", e.internal)
      .add("hourglass", e.hourglass)
      .add("contact", e.contact)
      .add("external_work", e.external_work);
  if (_solver.deck().settling.active())
    energies.add("damping", e.damping);
  s.add("energies", energies);
  JsonObject parts; // the values of the `part` field of fields.h5, by name
  for (size_t p = 0; p < _solver.mesh().parts.size(); ++p)
    parts.add(std::to_string(p), _solver.mesh().parts[p].name);
  s.add("parts", parts);
  s.add("preflight", _preflight);
  writeJson(_dir + "/summary.json", s);
}

} // namespace scpdyn
