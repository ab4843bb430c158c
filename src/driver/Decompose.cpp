// Domain decomposition of the Solver (issue 4, scp-method.md 2.1 and steps 7 and 10b): set-up
// on the global mesh, then this rank's piece; the shared-node exchanges of the cycle; the
// collective error check that keeps the ranks in step when one of them fails.
#include "driver/Decomposition.hpp"
#include "core/HostCopy.hpp"
#include "driver/Solver.hpp"

#include "contact/ContactSystem.hpp"
#include "parallel/LocalDomain.hpp"
#include "parallel/Mpi.hpp"
#include "parallel/Partitioner.hpp"

#include <algorithm>

namespace scpdyn
{

Index Solver::globalNode(Index local) const
{
  return _dd ? _dd->global_node[size_t(local)] : local;
}

Index Solver::globalElement(Index mesh_element) const
{
  return _dd ? _dd->global_element[size_t(mesh_element)] : mesh_element;
}

long Solver::globalNodeCount() const { return _dd ? _dd->global_nodes : long(_nodes.count); }

long Solver::globalElementCount() const { return _dd ? _dd->global_elements : long(_elems.count); }

void Solver::decompose()
{
  _dd = std::make_shared<SolverDecomposition>();
  _global_mesh = std::make_unique<HostMesh>(std::move(_mesh));
  const HostMesh &global = *_global_mesh;
  // the serial set-up finds unused nodes as zero masses; a local mesh has none, so look here
  {
    std::vector<char> used(size_t(global.numNodes()), 0);
    for (const HostPart &p : global.parts)
      for (Index n : p.connectivity)
        used[size_t(n)] = 1;
    const auto it = std::find(used.begin(), used.end(), char(0));
    if (it != used.end())
      throw InputError(_deck.path + ": parts: node " + std::to_string(it - used.begin()) +
                       " belongs to no element (zero mass)");
  }
  const std::vector<int> element_rank = partitionElementsOnRoot(global, _external_faces, _comm);
  LocalDomain d = buildLocalDomain(global, element_rank, _rank);
  _dd->halo = std::make_unique<NodeHalo>(d, _comm);
  _dd->owned = ownedNodes(d);
  _dd->shared_nodes = toDevice(d.shared.local, "shared_nodes");
  _dd->global_nodes = long(global.numNodes());
  _dd->global_elements = long(global.numElements());

  // output cell order: the serial device order (grouped by type, ascending id within a type)
  std::vector<long> before(5, 0); // elements of types < t
  for (const HostPart &p : global.parts)
    before[size_t(p.type) + 1] += p.numElements();
  for (size_t t = 1; t < before.size(); ++t)
    before[t] += before[t - 1];
  std::vector<long> seen(4, 0);
  std::vector<Index> serial_cell; // per local mesh element
  Index g = 0;
  size_t next = 0;
  for (const HostPart &p : global.parts)
    for (Index e = 0; e < p.numElements(); ++e, ++g)
    {
      const long cell = before[size_t(p.type)] + seen[size_t(p.type)]++;
      if (next < d.global_element.size() && d.global_element[next] == g)
      {
        serial_cell.push_back(Index(cell));
        ++next;
      }
    }
  _dd->output_cell = std::move(serial_cell);

  _external_faces = localFaces(_external_faces, d);
  _dd->global_node = std::move(d.global_node);
  _dd->global_element = std::move(d.global_element);
  _mesh = std::move(d.mesh);
}

void Solver::finishDecomposition()
{
  // output cells by device element instead of by mesh element
  std::vector<Index> by_device(_dd->output_cell.size());
  for (size_t e = 0; e < by_device.size(); ++e)
    by_device[size_t(_host_to_device_element[e])] = _dd->output_cell[e];
  _dd->output_cell = std::move(by_device);
  _dd->owned_device = IndexView("owned_nodes", _dd->owned.size());
  auto h = Kokkos::create_mirror_view(_dd->owned_device);
  for (size_t n = 0; n < _dd->owned.size(); ++n)
    h(n) = _dd->owned[n];
  Kokkos::deep_copy(_dd->owned_device, h);
  const size_t n = size_t(_nodes.count);
  _dd->f_contact = VectorView("f_contact_partial", n);
  _dd->f_load = VectorView("f_load_partial", n);
}

void Solver::checkSetNotEmpty(std::size_t local_count, const std::string &message) const
{
  const long long total = _dd ? allReduceSum((long long)local_count, _comm) : (long long)local_count;
  if (total == 0)
    throw InputError(message);
}

void Solver::unifyNodeSet(std::vector<Index> &nodes) const
{
  // A set built from the parts of local elements can miss a shared node on the rank whose
  // elements there belong to other parts; a BC must act on every copy alike, so a shared node
  // is in the set when it is on any rank.
  if (!_dd)
    return;
  RealView flag("node_set_flag", size_t(_nodes.count));
  auto h = Kokkos::create_mirror_view(flag);
  for (Index n : nodes)
    h(n) = 1;
  Kokkos::deep_copy(flag, h);
  _dd->halo->sum(flag);
  Kokkos::deep_copy(h, flag);
  nodes.clear();
  for (Index n = 0; n < _nodes.count; ++n)
    if (h(n) > 0)
      nodes.push_back(n);
}

void Solver::collectiveCheck(const std::string &local_error) const
{
  if (!_dd)
  {
    if (!local_error.empty())
      throw SimulationError(local_error);
    return;
  }
  // the lowest failing rank's message goes to every rank, so all of them stop together
  int first = local_error.empty() ? _num_ranks : _rank;
  MPI_Allreduce(MPI_IN_PLACE, &first, 1, MPI_INT, MPI_MIN, _comm);
  if (first == _num_ranks)
    return;
  int length = int(local_error.size());
  MPI_Bcast(&length, 1, MPI_INT, first, _comm);
  std::string message = local_error;
  message.resize(size_t(length));
  MPI_Bcast(&message[0], length, MPI_CHAR, first, _comm);
  throw SimulationError(message);
}

void Solver::stepExchangeSharedNodeForces()
{
  if (!_dd)
    return;
  ScopedStep t(_timers, "07_shared_node_forces");
  _dd->halo->sum(_nodes.f_int);
}

void Solver::stepExchangeLoadPartials()
{
  if (!_dd)
    return;
  ScopedStep t(_timers, "10b_shared_node_loads");
  auto shared = _dd->shared_nodes;
  const Index ns = Index(shared.extent(0));
  if (_contact)
  {
    // contact: f_contact = the contact force summed over the copies, the same bits on every
    // copy; the partials come from the contact's own field, which holds zero at a node this
    // rank's contact does not touch (f_contact there holds the last cycle's sum)
    auto fc = _contact->nodalForces();
    auto part = _dd->f_contact, f = _nodes.f_contact;
    Kokkos::parallel_for(
        "scpdyn::comm::packContactPartials", Kokkos::RangePolicy<ExecSpace>(0, ns),
        KOKKOS_LAMBDA(const Index s) {
          const Index k = shared(s);
          for (int d = 0; d < 3; ++d)
            part(k, d) = fc(k, d);
        });
    _dd->halo->sum(part);
    Kokkos::parallel_for(
        "scpdyn::comm::addContactTotals", Kokkos::RangePolicy<ExecSpace>(0, ns),
        KOKKOS_LAMBDA(const Index s) {
          const Index k = shared(s);
          for (int d = 0; d < 3; ++d)
            f(k, d) = part(k, d);
        });
  }
  if (!_bc.pressure_value.empty())
  {
    // pressure: f_ext = m g + (face loads summed over the copies); zeroForces' m g exactly
    auto part = _dd->f_load, f = _nodes.f_ext;
    auto mass = _nodes.mass;
    const Real g0 = _deck.gravity[0], g1 = _deck.gravity[1], g2 = _deck.gravity[2];
    Kokkos::deep_copy(part, 0.0);
    NodeFields into = _nodes;
    into.f_ext = part;
    applyFaceLoads(_bc, into, _dt, _deck.dimension, _deck.geometry);
    _dd->halo->sum(part);
    Kokkos::parallel_for(
        "scpdyn::comm::addLoadTotals", Kokkos::RangePolicy<ExecSpace>(0, ns),
        KOKKOS_LAMBDA(const Index s) {
          const Index k = shared(s);
          const Real m = mass(k);
          f(k, 0) = m * g0 + part(k, 0);
          f(k, 1) = m * g1 + part(k, 1);
          f(k, 2) = m * g2 + part(k, 2);
        });
  }
}

} // namespace scpdyn
