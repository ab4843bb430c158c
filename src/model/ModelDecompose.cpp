// Set-up of a decomposed run (docs/theory.md 2.1): the whole mesh is split, then each rank keeps
// its own piece; node sets made consistent over the copies of a shared node. The numbering maps
// of the Model (global ids of local nodes and elements).
#include "model/ModelSetup.hpp"
#include "core/HostCopy.hpp"

#include "parallel/Decomposition.hpp"
#include "parallel/LocalDomain.hpp"
#include "parallel/Mpi.hpp"
#include "parallel/Partitioner.hpp"

#include <algorithm>
#include <functional>

namespace scpdyn
{

Index Model::globalNode(Index local) const { return dd ? dd->global_node[size_t(local)] : local; }

Index Model::globalElement(Index mesh_element) const
{
  return dd ? dd->global_element[size_t(mesh_element)] : mesh_element;
}

long Model::globalNodeCount() const { return dd ? dd->global_nodes : long(nodes.count); }

long Model::globalElementCount() const { return dd ? dd->global_elements : long(elems.count); }

Index Model::meshElementOfDevice(Index device) const
{
  for (size_t k = 0; k < host_to_device_element.size(); ++k)
    if (host_to_device_element[k] == device)
      return Index(k);
  return device;
}

void ModelSetup::decompose()
{
  _m.dd = std::make_shared<DomainDecomposition>();
  _m.global_mesh = std::make_unique<HostMesh>(std::move(_m.mesh));
  const HostMesh &global = *_m.global_mesh;
  // the serial set-up finds unused nodes as zero masses; a local mesh has none, so look here
  {
    std::vector<char> used(size_t(global.numNodes()), 0);
    for (const HostPart &p : global.parts)
      for (Index n : p.connectivity)
        used[size_t(n)] = 1;
    const auto it = std::find(used.begin(), used.end(), char(0));
    if (it != used.end())
      throw InputError(_m.deck.path + ": parts: node " + std::to_string(it - used.begin()) +
                       " belongs to no element (zero mass)");
  }
  const std::vector<int> element_rank = partitionElementsOnRoot(global, _m.external_faces, _m.comm);
  LocalDomain d = buildLocalDomain(global, element_rank, _m.rank);
  _m.dd->halo = std::make_unique<NodeHalo>(d, _m.comm);
  _m.dd->owned = ownedNodes(d);
  _m.dd->shared_nodes = toDevice(d.shared.local, "shared_nodes");
  _m.dd->shared = d.shared;
  _m.dd->shared_index.assign(d.global_node.size(), -1);
  for (Index s = 0; s < d.shared.size(); ++s)
    _m.dd->shared_index[size_t(d.shared.local[size_t(s)])] = s;
  _m.dd->global_nodes = long(global.numNodes());
  _m.dd->global_elements = long(global.numElements());

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
  _m.dd->output_cell = std::move(serial_cell);

  _m.external_faces = localFaces(_m.external_faces, d);
  _m.interior_faces = localFaces(_m.interior_faces, d);
  _m.dd->global_node = std::move(d.global_node);
  _m.dd->global_element = std::move(d.global_element);
  _m.mesh = std::move(d.mesh);
}

void ModelSetup::finishDecomposition()
{
  // output cells by device element instead of by mesh element
  std::vector<Index> by_device(_m.dd->output_cell.size());
  for (size_t e = 0; e < by_device.size(); ++e)
    by_device[size_t(_m.host_to_device_element[e])] = _m.dd->output_cell[e];
  _m.dd->output_cell = std::move(by_device);
  _m.dd->owned_device = IndexView("owned_nodes", _m.dd->owned.size());
  auto h = Kokkos::create_mirror_view(_m.dd->owned_device);
  for (size_t n = 0; n < _m.dd->owned.size(); ++n)
    h(n) = _m.dd->owned[n];
  Kokkos::deep_copy(_m.dd->owned_device, h);
  if (orderedAssembly(_m.deck, _m.dd != nullptr))
    setupCornerSum();
  const size_t n = size_t(_m.nodes.count);
  _m.dd->f_contact = VectorView("f_contact_partial", n);
  _m.dd->f_load = VectorView("f_load_partial", n);
}

std::vector<std::vector<NodeTerm>>
ModelSetup::cornerTerms(const std::function<TermKey(Index, int)> &key,
                        const std::function<Index(Index, int)> &slot,
                        std::vector<std::pair<Index, int>> *corners) const
{
  std::vector<std::vector<NodeTerm>> terms(size_t(_m.dd->shared.size()));
  auto conn = Kokkos::create_mirror_view_and_copy(HostSpace(), _m.elems.conn);
  for (Index e = 0; e < _m.elems.count; ++e)
    for (int a = 0; a < kMaxElementNodes && conn(e, a) >= 0; ++a)
    {
      const Index s = _m.dd->shared_index[size_t(conn(e, a))];
      if (s < 0)
        continue;
      Index q = 0;
      if (slot)
        q = slot(e, a);
      else
      {
        q = Index(corners->size());
        corners->push_back({e, a});
      }
      terms[size_t(s)].push_back({key(e, a), q});
    }
  return terms;
}

void ModelSetup::sumSharedMasses(const RealView::HostMirror &element_mass,
                                 const RealView::HostMirror &node_mass) const
{
  // the serial set-up adds m / n in mesh element order (part by part), then corner order
  std::vector<Index> mesh_of(_m.host_to_device_element.size());
  for (size_t k = 0; k < mesh_of.size(); ++k)
    mesh_of[size_t(_m.host_to_device_element[k])] = Index(k);
  std::vector<std::pair<Index, int>> corners;
  const auto terms = cornerTerms(
      [&](Index e, int a) {
        return TermKey{_m.dd->global_element[size_t(mesh_of[size_t(e)])], a, 0};
      },
      {}, &corners);
  auto conn = Kokkos::create_mirror_view_and_copy(HostSpace(), _m.elems.conn);
  std::vector<Real> values, sums(node_mass.extent(0));
  for (const auto &[e, a] : corners)
  {
    int nn = 0;
    while (nn < kMaxElementNodes && conn(e, nn) >= 0)
      ++nn;
    values.push_back(element_mass(e) / nn);
  }
  OrderedNodeSum(_m.comm, _m.dd->shared, terms).sumHost(values, 1, sums);
  for (Index n : _m.dd->shared.local)
    node_mass(n) = sums[size_t(n)];
}

void ModelSetup::setupCornerSum()
{
  // the serial run adds a node's corner forces in device element order, then corner order
  // (plain adds, or NodeCorners' ascending slots): the key; the value is the corner's slot
  auto base = Kokkos::create_mirror_view_and_copy(HostSpace(), _m.corners.corner_base);
  auto mask = Kokkos::create_mirror_view_and_copy(HostSpace(), _m.corners.shared_corners);
  const std::vector<Index> &cell = _m.dd->output_cell;
  const auto terms = cornerTerms(
      [&](Index e, int a) {
        return TermKey{cell[size_t(e)], a, 0};
      },
      [&](Index e, int a) {
        return base(e) + Index(__builtin_popcount(unsigned(mask(e)) & ((1u << a) - 1u)));
      },
      nullptr);
  _m.dd->corner_sum =
      std::make_unique<OrderedNodeSum>(_m.comm, _m.dd->shared, terms, &_m.dd->ordered_bytes);
}

void ModelSetup::checkSetNotEmpty(std::size_t local_count, const std::string &message) const
{
  const long long total =
      _m.dd ? allReduceSum((long long)local_count, _m.comm) : (long long)local_count;
  if (total == 0)
    throw InputError(message);
}

void ModelSetup::unifyNodeSet(std::vector<Index> &nodes) const
{
  // A set built from the parts of local elements can miss a shared node on the rank whose
  // elements there belong to other parts; a BC must act on every copy alike, so a shared node
  // is in the set when it is on any rank.
  if (!_m.dd)
    return;
  RealView flag("node_set_flag", size_t(_m.nodes.count));
  auto h = Kokkos::create_mirror_view(flag);
  for (Index n : nodes)
    h(n) = 1;
  Kokkos::deep_copy(flag, h);
  _m.dd->halo->sum(flag);
  Kokkos::deep_copy(h, flag);
  nodes.clear();
  for (Index n = 0; n < _m.nodes.count; ++n)
    if (h(n) > 0)
      nodes.push_back(n);
}

} // namespace scpdyn
