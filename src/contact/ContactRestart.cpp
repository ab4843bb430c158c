// The contact's part of a restart file: the CP list by face keys with every CP's history and
// per-cycle fields, the per-node impulse and the energy accumulators (docs/theory.md 3.5, 12),
// in an order no decomposition changes.
#include "contact/ContactSystem.hpp"
#include "contact/ContactKernels.hpp"
#include "core/HostCopy.hpp"
#include "core/InputError.hpp"
#include "io/RestartFile.hpp"
#include "parallel/Mpi.hpp"

#include <algorithm>
#include <unordered_map>

namespace scpdyn
{
namespace
{
// CpState as doubles: every member in declaration order (ints are exact in a double)
constexpr int kCpStateValues = 22;
static_assert(sizeof(CpState) == 20 * sizeof(Real) + 2 * sizeof(int),
              "a new CpState member needs its place in packState/unpackState and a new "
              "kRestartFormatVersion");

void packState(const CpState &s, double *o)
{
  int k = 0;
  o[k++] = s.u;
  o[k++] = s.umax;
  o[k++] = s.Fn;
  for (int d = 0; d < 3; ++d)
    o[k++] = s.Fs[d];
  o[k++] = s.usp;
  for (int d = 0; d < 3; ++d)
    o[k++] = s.us[d];
  for (int d = 0; d < 3; ++d)
    o[k++] = s.n_old[d];
  o[k++] = s.u_z;
  o[k++] = s.Ac_old;
  o[k++] = s.open;
  o[k++] = s.failed;
  o[k++] = s.sigma_t_scale;
  for (int d = 0; d < 3; ++d)
    o[k++] = s.V_model[d];
  o[k++] = s.dt_model;
}

CpState unpackState(const double *o)
{
  CpState s;
  int k = 0;
  s.u = o[k++];
  s.umax = o[k++];
  s.Fn = o[k++];
  for (int d = 0; d < 3; ++d)
    s.Fs[d] = o[k++];
  s.usp = o[k++];
  for (int d = 0; d < 3; ++d)
    s.us[d] = o[k++];
  for (int d = 0; d < 3; ++d)
    s.n_old[d] = o[k++];
  s.u_z = o[k++];
  s.Ac_old = o[k++];
  s.open = int(o[k++]);
  s.failed = int(o[k++]);
  s.sigma_t_scale = o[k++];
  for (int d = 0; d < 3; ++d)
    s.V_model[d] = o[k++];
  s.dt_model = o[k++];
  return s;
}

/// \brief The per-cycle fields of the CPs (the outputs of the cycle after a restart read some).
template <class Fn>
void eachPlaneField(const CommonPlaneData &cp, Fn &&fn)
{
  fn(cp.normal);
  fn(cp.poc);
  fn(cp.force);
  fn(cp.area);
  fn(cp.face_area1);
  fn(cp.face_area2);
  fn(cp.mstar);
  fn(cp.stored);
  fn(cp.w1);
  fn(cp.w2);
  fn(cp.status);
}

/// \brief Values per CP in the file: its two face keys, its history, its per-cycle fields and
/// its approach velocity.
int planeRowWidth(const CommonPlaneData &cp)
{
  int width = 2 + kCpStateValues + 1;
  eachPlaneField(cp, [&](const auto &v) { width += flatWidth(v); });
  return width;
}

/// \brief The rows of `rows` (`width` values each) in ascending order of their first two
/// values, the face keys: the order of a CP list (3.5) whatever rank wrote a row.
std::vector<double> sortedByKeys(const std::vector<double> &rows, int width)
{
  const size_t n = rows.size() / size_t(width);
  std::vector<size_t> order(n);
  for (size_t p = 0; p < n; ++p)
    order[p] = p;
  auto key = [&](size_t p) { return std::make_pair(rows[p * width], rows[p * width + 1]); };
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return key(a) < key(b); });
  std::vector<double> out;
  out.reserve(rows.size());
  for (size_t p : order)
    out.insert(out.end(), rows.begin() + long(p * width), rows.begin() + long((p + 1) * width));
  return out;
}
} // namespace

void ContactSystem::saveState(RestartWriter &out, MPI_Comm comm,
                              const std::vector<Index> &node_global, const VectorView &v) const
{
  const Index n = _cp.count;
  const int width = planeRowWidth(_cp);
  auto key1 = Kokkos::create_mirror_view_and_copy(HostSpace(), _cp.key1);
  auto key2 = Kokkos::create_mirror_view_and_copy(HostSpace(), _cp.key2);
  auto face1 = Kokkos::create_mirror_view_and_copy(HostSpace(), _cp.face1);
  auto state = Kokkos::create_mirror_view_and_copy(HostSpace(), _cp.state);
  auto ghost = Kokkos::create_mirror_view_and_copy(HostSpace(), _faces.ghost);
  auto approach = Kokkos::create_mirror_view_and_copy(HostSpace(), _approach);
  std::vector<std::vector<double>> fields;
  std::vector<int> widths;
  eachPlaneField(_cp, [&](const auto &f) {
    fields.push_back(flatten(f));
    widths.push_back(flatWidth(f));
  });
  std::vector<double> rows;
  for (Index p = 0; p < n; ++p)
  {
    if (ghost(face1(p))) // a CP on two ranks is written by the rank of its face 1
      continue;
    rows.push_back(double(key1(p)));
    rows.push_back(double(key2(p)));
    const size_t at = rows.size();
    rows.resize(at + kCpStateValues);
    packState(state(p), &rows[at]);
    for (size_t i = 0; i < fields.size(); ++i)
      for (int c = 0; c < widths[i]; ++c)
        rows.push_back(fields[i][size_t(p) * size_t(widths[i]) + size_t(c)]);
    rows.push_back(size_t(p) < approach.extent(0) ? approach(p) : 0.0);
  }
  const std::vector<double> planes = sortedByKeys(gatherToRoot(rows, comm), width);
  out.put("contact.scalars",
          std::vector<double>{
              _joint_work, _joint_work_peak, _joint_work_gross, _stored_peak, _slide_work,
              _slide_work_peak, _dt_prev, double(_max_count), double(_binned_cycle), _geom.h_max,
              double(planes.size() / size_t(width)), _slide_carried, _motion, _motion_gap,
              double(_searches), double(_tie_solves), double(_tie_iterations)});
  out.put("contact.planes", planes);
  // the same lists on every rank (elementsEroded())
  out.put("contact.eroded", std::vector<double>(_eroded.begin(), _eroded.end()));
  out.put("contact.eroded_pending",
          std::vector<double>(_eroded_pending.begin(), _eroded_pending.end()));

  // what each rank adds up alone: its contact work and stored energy, and its last impulses
  // with the work they still do in the next cycle, 1/2 v^n.I^{n-1/2} (finish())
  auto impulse = Kokkos::create_mirror_view_and_copy(HostSpace(), _impulse);
  auto used = Kokkos::create_mirror_view_and_copy(HostSpace(), _faces.nodes_used);
  auto vh = Kokkos::create_mirror_view_and_copy(HostSpace(), v);
  auto copy = Kokkos::create_mirror_view_and_copy(HostSpace(), _copy_node);
  Real lag = 0;
  for (size_t i = 0; i < used.extent(0); ++i)
    if (contact_kernels::countsNodeWork(copy, used(i))) // as finish() counts them
      for (int d = 0; d < _dim; ++d)
        lag -= 0.5 * vh(used(i), d) * impulse(used(i), d);
  out.put("contact.rank_partials", gatherToRoot({_work, _stored, lag}, comm));
  std::vector<double> impulses;
  for (size_t k = 0; k < impulse.extent(0) && k < node_global.size(); ++k)
    if (node_global[k] >= 0 && (impulse(k, 0) != 0 || impulse(k, 1) != 0 || impulse(k, 2) != 0))
      impulses.insert(impulses.end(),
                      {double(node_global[k]), impulse(k, 0), impulse(k, 1), impulse(k, 2)});
  std::vector<int> counts;
  out.put("contact.impulse", gatherToRoot(impulses, comm, &counts));
  out.put("contact.impulse_counts", counts);
}

void ContactSystem::loadState(const RestartReader &in, MPI_Comm comm,
                              const std::vector<Index> &node_global)
{
  const std::string where = "restart file '" + in.path() + "': ";
  const std::vector<double> sc = in.reals("contact.scalars", 17);
  _joint_work = sc[0];
  _joint_work_peak = sc[1];
  _joint_work_gross = sc[2];
  _stored_peak = sc[3];
  _slide_work = sc[4];
  _slide_work_peak = sc[5];
  _dt_prev = sc[6];
  _max_count = Index(sc[7]);
  _binned_cycle = long(sc[8]);
  _geom.h_max = sc[9];
  const long n = long(sc[10]);
  _slide_carried = sc[11];
  _motion = sc[12];
  _motion_gap = sc[13];
  _searches = long(sc[14]);
  _tie_solves = long(sc[15]);
  _tie_iterations = long(sc[16]);
  const int width = planeRowWidth(_cp);
  const std::vector<double> rows = in.reals("contact.planes", n * width);

  // this rank's CPs: those with a face of its own and the other its own or a ghost face
  auto key = Kokkos::create_mirror_view_and_copy(HostSpace(), _faces.key);
  auto ghost = Kokkos::create_mirror_view_and_copy(HostSpace(), _faces.ghost);
  const long *keys = key.data();
  auto faceOf = [&](double k) {
    const long *it = std::lower_bound(keys, keys + _faces.count, long(k));
    return it == keys + _faces.count || *it != long(k) ? Index(-1) : Index(it - keys);
  };
  std::vector<Index> take, f1, f2;
  long owned = 0;
  for (long p = 0; p < n; ++p)
  {
    const Index a = faceOf(rows[size_t(p) * width]), b = faceOf(rows[size_t(p) * width + 1]);
    if (a < 0 || b < 0 || (ghost(a) && ghost(b)))
      continue;
    take.push_back(Index(p));
    f1.push_back(a);
    f2.push_back(b);
    owned += ghost(a) ? 0 : 1;
  }
  if (comm != MPI_COMM_NULL)
    MPI_Allreduce(MPI_IN_PLACE, &owned, 1, MPI_LONG, MPI_SUM, comm);
  if (owned != n) // the same sum on every rank: all of them stop
    throw InputError(where + std::to_string(n - owned) + " of its " + std::to_string(n) +
                     " common planes are between faces that are not contact faces of this deck");

  const Index m = Index(take.size());
  _cp = allocatePlanes(m);
  ++_cp_generation;
  auto surface = Kokkos::create_mirror_view_and_copy(HostSpace(), _faces.surface);
  auto part = Kokkos::create_mirror_view_and_copy(HostSpace(), _faces.part);
  auto fparams = Kokkos::create_mirror_view_and_copy(HostSpace(), _faces.params);
  auto face1 = Kokkos::create_mirror_view(_cp.face1), face2 = Kokkos::create_mirror_view(_cp.face2);
  auto key1 = Kokkos::create_mirror_view(_cp.key1), key2 = Kokkos::create_mirror_view(_cp.key2);
  auto state = Kokkos::create_mirror_view(_cp.state);
  auto params = Kokkos::create_mirror_view(_cp.params);
  _approach = RealView("cp_approach", size_t(m));
  auto approach = Kokkos::create_mirror_view(_approach);
  for (Index q = 0; q < m; ++q)
  {
    const double *row = &rows[size_t(take[size_t(q)]) * width];
    key1(q) = long(row[0]);
    key2(q) = long(row[1]);
    face1(q) = f1[size_t(q)];
    face2(q) = f2[size_t(q)];
    params(q) = planeParams(fparams(surface(face1(q))), fparams(surface(face2(q))),
                            part(face1(q)) == part(face2(q)));
    state(q) = unpackState(row + 2);
    approach(q) = row[width - 1];
  }
  Kokkos::deep_copy(_cp.face1, face1);
  Kokkos::deep_copy(_cp.face2, face2);
  Kokkos::deep_copy(_cp.key1, key1);
  Kokkos::deep_copy(_cp.key2, key2);
  Kokkos::deep_copy(_cp.state, state);
  Kokkos::deep_copy(_cp.params, params);
  Kokkos::deep_copy(_approach, approach);
  int column = 2 + kCpStateValues;
  eachPlaneField(_cp, [&](const auto &f) {
    const int c = flatWidth(f);
    std::vector<double> flat(size_t(m) * size_t(c));
    for (Index q = 0; q < m; ++q)
      for (int j = 0; j < c; ++j)
        flat[size_t(q) * size_t(c) + size_t(j)] =
            rows[size_t(take[size_t(q)]) * width + size_t(column + j)];
    unflatten(f, flat);
    column += c;
  });
  loadRankPartials(in, comm, node_global);
  countPlanes(); // the self-contact CPs: whether the slide-line solve runs before the next search
}

void ContactSystem::loadRankPartials(const RestartReader &in, MPI_Comm comm,
                                     const std::vector<Index> &node_global)
{
  const std::string where = "restart file '" + in.path() + "': ";
  const std::vector<double> partials = in.reals("contact.rank_partials");
  const long writers = long(partials.size() / 3);
  const std::vector<int> counts = in.ints("contact.impulse_counts", writers);
  const std::vector<double> impulses = in.reals("contact.impulse");
  long total = 0;
  for (int c : counts)
    total += c;
  if (writers < 1 || partials.size() % 3 != 0 || total != long(impulses.size()))
    throw InputError(where + "truncated or corrupt (contact partial sums)");
  int rank = 0, size = 1;
  if (comm != MPI_COMM_NULL)
  {
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &size);
  }
  Kokkos::deep_copy(_impulse, 0.0);
  _work = _stored = 0;
  if (writers != size)
  { // another decomposition: the sums on rank 0, with the impulses' work of the next cycle
    for (long r = 0; rank == 0 && r < writers; ++r)
    {
      _work += partials[size_t(3 * r)] + partials[size_t(3 * r + 2)];
      _stored += partials[size_t(3 * r + 1)];
    }
    return;
  }
  // the same decomposition: each rank its own partials and impulses, by global node
  _work = partials[size_t(3 * rank)];
  _stored = partials[size_t(3 * rank + 1)];
  std::unordered_map<Index, size_t> slot;
  for (size_t k = 0; k < node_global.size(); ++k)
    if (node_global[k] >= 0)
      slot.emplace(node_global[k], k);
  size_t at = 0;
  for (int r = 0; r < rank; ++r)
    at += size_t(counts[size_t(r)]);
  auto impulse = Kokkos::create_mirror_view_and_copy(HostSpace(), _impulse);
  const size_t end = at + size_t(counts[size_t(rank)]);
  for (size_t i = at; i + 4 <= end; i += 4)
  {
    const auto it = slot.find(Index(impulses[i]));
    if (it != slot.end() && it->second < impulse.extent(0))
      for (int d = 0; d < 3; ++d)
        impulse(it->second, d) = impulses[i + 1 + size_t(d)];
  }
  Kokkos::deep_copy(_impulse, impulse);
}

} // namespace scpdyn
