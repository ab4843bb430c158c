// Set-up (steps 1 and 2 of the cycle): meshes from the deck, sets, device fields, boundary
// conditions, the initial state and the node sweep. The decomposition, the contact system and
// the gauges are in the files beside this one.
#include "model/ModelSetup.hpp"
#include "core/HostCopy.hpp"
#include "core/RealText.hpp"

#include "bc/TimeFunctions.hpp"
#include "contact/ContactSystem.hpp"
#include "element/ElementKinematics.hpp"
#include "input/YamlReader.hpp"
#include "integrate/LateNodes.hpp"
#include "integrate/NodeUpdate.hpp"
#include "material/MaterialLibrary.hpp"
#include "material/MaterialUpdate.hpp"
#include "mesh/GmshReader.hpp"
#include "mesh/MeshGenerators.hpp"
#include "mesh/MeshOps.hpp"
#include "mesh/PartOverlap.hpp"
#include "parallel/Decomposition.hpp"
#include "parallel/Mpi.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <limits>
#include <map>
#include <numeric>
#include <unistd.h>

namespace scpdyn
{
namespace
{

// Peak resident memory of a run per element and per node of its mesh (checkMeshSize()),
// measured: 1.05 GB for a 100^3 hex8 block (1e6 elements, 1.03e6 nodes, one cycle with its two
// field frames), 157 MB for 50^3
constexpr long double kSetupBytesPerElement = 900, kSetupBytesPerNode = 150;

/// "; did you mean 'x'?" or the list of the sets there are (deck and gmsh sets alike).
template <class Sets>
std::string setSuggestion(const std::string &name, const Sets &sets)
{
  std::vector<std::string> names;
  for (const auto &kv : sets)
    names.push_back(kv.first);
  return names.empty() ? std::string(" (the deck and its meshes define no such set)")
                       : input_impl::suggestion(name, names);
}

} // namespace

namespace
{

int materialIndex(const Deck &deck, const std::string &name)
{
  for (size_t i = 0; i < deck.materials.size(); ++i)
    if (deck.materials[i].name == name)
      return int(i);
  return -1;
}

/// part `name` or the parts a generator expanded from it ("name.<...>")
bool partMatches(const std::string &part_name, const std::string &pattern)
{
  return part_name == pattern ||
         (part_name.size() > pattern.size() && part_name.compare(0, pattern.size(), pattern) == 0 &&
          part_name[pattern.size()] == '.');
}

/// Host evaluation of the element measure with the kernels' own functions.
Real hostElementVolume(ElementType type, const Real x[][3], bool axi)
{
  Real B[kMaxElementNodes][3];
  switch (type)
  {
  case ElementType::Line2:
    return elementGradients<ElementType::Line2>(x, B);
  case ElementType::Quad4:
    return axi ? quad4RadialVolume(x) : elementGradients<ElementType::Quad4>(x, B);
  case ElementType::Hex8:
    return elementGradients<ElementType::Hex8>(x, B);
  case ElementType::Tet4:
    return elementGradients<ElementType::Tet4>(x, B);
  }
  return 0;
}

} // namespace

Model::Model(const Deck &d, MPI_Comm c) : deck(d), comm(c)
{
  ModelSetup setup(*this);
  setup.run();
}

Model::~Model() = default;

void ModelSetup::run()
{
  _m.rank = mpiRank(_m.comm);
  _m.num_ranks = mpiSize(_m.comm);
  for (const auto &m : _m.deck.materials)
    _m.materials_host.push_back(makeMaterialParams(m));
  _m.bc.functions = _m.deck.functions;
  setupMesh();
  if (_m.num_ranks > 1)
    decompose();
  setupFields();
  if (_m.dd)
    finishDecomposition();
  setupSets();
  setupBoundaryConditions();
  _m.external_loads = hasExternalLoads(_m.bc, _m.deck.gravity.data());
  setupContact();
  setupPartRelease();
  setupNodeSweep();
  setupGauges();
  setupInitialState();
  _m.global_mesh.reset(); // from here on a rank holds its own piece only
  if (_m.dd)
    _m.dd->halo_bytes_setup = _m.dd->halo->bytesSent();
}

void ModelSetup::warnUnconnectedGroups(const HostMesh &g, const std::string &key) const
{
  // each physical group of a gmsh file is its own part with its own copy of the nodes: groups
  // drawn as one body (materials, regions) then touch without being joined
  std::map<std::array<Real, 3>, int> part_at;
  std::map<std::pair<int, int>, long> shared;
  for (size_t p = 0; p < g.parts.size(); ++p)
  {
    std::vector<Index> nodes(g.parts[p].connectivity.begin(), g.parts[p].connectivity.end());
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    for (Index n : nodes)
    {
      const auto it = part_at.emplace(g.coords[size_t(n)], int(p)).first;
      if (it->second != int(p))
        ++shared[{it->second, int(p)}];
    }
  }
  for (const auto &kv : shared)
    std::fprintf(stderr,
                 "scpdyn: warning: %s: physical groups '%s' and '%s' share %ld node positions "
                 "but are not joined (merge_nodes: false): they are separate bodies unless a "
                 "contact surface ties them; merge_nodes: true joins them\n",
                 key.c_str(), g.parts[size_t(kv.first.first)].name.c_str(),
                 g.parts[size_t(kv.first.second)].name.c_str(), kv.second);
}

void ModelSetup::checkMeshSize() const
{
  // counts in long double: a deck's [2147483647, 1] must not overflow before it is refused
  long double elements = 0, nodes = 0;
  const int dim = _m.deck.dimension;
  for (const PartSpec &spec : _m.deck.parts)
  {
    const MeshSpec &m = spec.mesh;
    if (m.type == MeshType::Gmsh)
      continue; // bounded by the file, read as it is
    long double cells = 1, cell_nodes = 1, bricks = 1;
    for (int d = 0; d < dim; ++d)
    {
      cells *= m.elements[size_t(d)];
      cell_nodes *= m.elements[size_t(d)] + 1.0L;
      if (m.type == MeshType::BrickWall) // a staggered course has one brick more
        bricks *= m.count[size_t(d)] + (d == m.stagger_axis ? 1.0L : 0.0L);
    }
    const long double per_cell = m.element == ElementType::Tet4 ? 6 : 1;
    elements += bricks * cells * per_cell;
    nodes += bricks * cell_nodes;
  }
  const long double index_limit = std::numeric_limits<Index>::max();
  if (elements > index_limit || nodes > index_limit)
    throw InputError(_m.deck.path + ": parts: the meshes have " + formatReal(double(elements)) +
                     " elements and " + formatReal(double(nodes)) +
                     " nodes, beyond the index limit of " + formatReal(double(index_limit)) +
                     " per rank");
  // every rank holds the whole mesh while it sets up
  const long double bytes = kSetupBytesPerElement * elements + kSetupBytesPerNode * nodes;
  const long double physical = (long double)sysconf(_SC_PHYS_PAGES) * sysconf(_SC_PAGE_SIZE);
  if (physical > 0 && bytes > 0.8L * physical)
    throw InputError(_m.deck.path + ": parts: the meshes have " + formatReal(double(elements)) +
                     " elements and " + formatReal(double(nodes)) + " nodes: about " +
                     formatReal(std::round(double(bytes / (1 << 30)) * 10) / 10) +
                     " GiB per rank to set up, more than 80 % of this machine's " +
                     formatReal(std::round(double(physical / (1 << 30)) * 10) / 10) + " GiB");
}

void ModelSetup::setupMesh()
{
  checkMeshSize();
  std::vector<int> merge_parts;
  for (size_t s = 0; s < _m.deck.parts.size(); ++s)
  {
    const PartSpec &spec = _m.deck.parts[s];
    const std::string key = "parts[" + std::to_string(s) + "].mesh";
    const size_t first_part = _m.mesh.parts.size();
    const size_t first_node = _m.mesh.coords.size();
    try
    {
      const MeshSpec &m = spec.mesh;
      if (m.type == MeshType::Block)
        appendBlock(_m.mesh, spec.name, m.element, m.elements, m.origin, m.size);
      else if (m.type == MeshType::BrickWall)
        appendBrickWall(_m.mesh, spec.name, m.element, m.elements, m.origin, m.brick_size, m.count,
                        m.stagger, m.stagger_axis, m.bond);
      else
      {
        HostMesh g = readGmsh41(m.file);
        if (!spec.merge_nodes && _m.rank == 0)
          warnUnconnectedGroups(g, "parts[" + std::to_string(s) + "] ('" + spec.name + "')");
        if (_m.mesh.dim != 0 && g.dim != _m.mesh.dim)
          throw std::runtime_error("mesh dimension " + std::to_string(g.dim) +
                                   " differs from the other parts");
        appendMesh(_m.mesh, std::move(g), spec.name + ".");
      }
    }
    catch (const InputError &)
    {
      throw;
    }
    catch (const std::exception &e)
    {
      throw InputError(_m.deck.path + ": " + key + ": " + e.what());
    }
    const PartPlacement &pl = spec.placement;
    if (pl.moves())
      moveNodesRigidly(_m.mesh, first_node, pl.angle * M_PI / 180, pl.axis, pl.point, pl.translate);
    const int mat = materialIndex(_m.deck, spec.material);
    for (size_t p = first_part; p < _m.mesh.parts.size(); ++p)
    {
      _m.mesh.parts[p].material = mat;
      if (spec.merge_nodes)
        merge_parts.push_back(int(p));
    }
    _m.part_spec.resize(_m.mesh.parts.size(), int(s));
  }
  if (_m.mesh.dim != _m.deck.dimension)
    throw InputError(_m.deck.path + ": dimension: the deck says " +
                     std::to_string(_m.deck.dimension) + " but the meshes are " +
                     std::to_string(_m.mesh.dim) + "-dimensional");
  try
  {
    if (merge_parts.size() > 1)
      mergeCoincidentNodes(_m.mesh, merge_parts, 1e-9 * meshBox(_m.mesh).diagonal());
    checkElements(_m.mesh);
  }
  catch (const std::exception &e)
  {
    throw InputError(_m.deck.path + ": parts: " + e.what());
  }
  if (_m.rank == 0)
    for (const PartOverlap &o : overlappingParts(_m.mesh))
      std::fprintf(stderr,
                   "scpdyn: warning: parts: part '%s' overlaps part '%s' at t = 0 (%ld element "
                   "centroids of the first inside elements of the second, e.g. element %ld): "
                   "overlapping parts pass through each other, contact or not\n",
                   _m.mesh.parts[size_t(o.part_a)].name.c_str(),
                   _m.mesh.parts[size_t(o.part_b)].name.c_str(), o.count, long(o.element));
  _m.external_faces = extractExternalFaces(_m.mesh);
  std::vector<char> eroding(_m.mesh.parts.size(), 0);
  for (size_t p = 0; p < _m.mesh.parts.size(); ++p)
    eroding[p] = _m.materials_host[size_t(_m.mesh.parts[p].material)].erosion.active ? 1 : 0;
  if (std::find(eroding.begin(), eroding.end(), char(1)) != eroding.end() &&
      !_m.deck.contact.surfaces.empty())
    _m.interior_faces = interiorFaces(_m.mesh, eroding);
}

void ModelSetup::setupFields()
{
  const Index num_nodes = _m.mesh.numNodes();
  const Index num_elems = _m.mesh.numElements();
  const bool axi = _m.deck.dimension == 2 && _m.deck.geometry == Geometry2D::Axisymmetric;

  // device element order: grouped by type (stable in part order), so every launch is one type
  std::vector<std::pair<ElementType, Index>> order; // type, host element id
  std::vector<int> elem_part;
  std::vector<Index> elem_first(_m.mesh.parts.size() + 1, 0);
  for (size_t p = 0; p < _m.mesh.parts.size(); ++p)
    elem_first[p + 1] = elem_first[p] + _m.mesh.parts[p].numElements();
  for (size_t p = 0; p < _m.mesh.parts.size(); ++p)
    for (Index e = 0; e < _m.mesh.parts[p].numElements(); ++e)
      order.push_back({_m.mesh.parts[p].type, elem_first[p] + e});
  std::stable_sort(order.begin(), order.end(),
                   [](const auto &a, const auto &b) { return int(a.first) < int(b.first); });
  _m.host_to_device_element.assign(size_t(num_elems), -1);
  for (size_t k = 0; k < order.size(); ++k)
    _m.host_to_device_element[size_t(order[k].second)] = Index(k);
  for (size_t k = 0; k < order.size(); ++k)
    if (_m.groups.empty() || _m.groups.back().type != order[k].first)
      _m.groups.push_back({order[k].first, Index(k), Index(k + 1)});
    else
      _m.groups.back().end = Index(k + 1);

  _m.nodes.count = num_nodes;
  _m.nodes.x0 = VectorView("x0", size_t(num_nodes));
  _m.nodes.x = VectorView("x", size_t(num_nodes));
  _m.nodes.v = VectorView("v", size_t(num_nodes));
  _m.nodes.f_int = VectorView("f_int", size_t(num_nodes));
  _m.nodes.f_ext = VectorView("f_ext", size_t(num_nodes));
  if (!_m.deck.contact.surfaces.empty())
    _m.nodes.f_contact = VectorView("f_contact", size_t(num_nodes));
  _m.nodes.external_impulse = VectorView("external_impulse", size_t(num_nodes));
  if (_m.deck.settling.active())
    _m.nodes.damping_impulse = VectorView("damping_impulse", size_t(num_nodes));
  _m.nodes.mass = RealView("node_mass", size_t(num_nodes));
  _m.nodes.bc = DeviceView<int *[3]>("node_bc", size_t(num_nodes));

  _m.elems.count = num_elems;
  const size_t ne = size_t(num_elems);
  _m.elems.conn = ConnView("conn", ne, kMaxElementNodes);
  _m.elems.part = IndexView("part", ne);
  _m.elems.material = IndexView("material", ne);
  _m.elems.mass = RealView("element_mass", ne);
  _m.elems.volume = RealView("volume", ne);
  _m.elems.stress = SymTensorView("stress", ne);
  _m.elems.energy = RealView("energy", ne);
  _m.elems.plastic_strain = RealView("plastic_strain", ne);
  _m.elems.q = RealView("q", ne);
  _m.elems.sound_speed = RealView("sound_speed", ne);
  _m.elems.hourglass_energy = RealView("hourglass_energy", ne);
  _m.elems.history = HistoryView("history", ne);
  _m.elems.hourglass = HourglassView("hourglass", ne);
  _m.elems.eroded = DeviceView<std::uint8_t *>("eroded", ne);

  auto h_x0 = Kokkos::create_mirror_view(_m.nodes.x0);
  auto h_mass = Kokkos::create_mirror_view(_m.nodes.mass);
  auto h_conn = Kokkos::create_mirror_view(_m.elems.conn);
  auto h_part = Kokkos::create_mirror_view(_m.elems.part);
  auto h_mat = Kokkos::create_mirror_view(_m.elems.material);
  auto h_emass = Kokkos::create_mirror_view(_m.elems.mass);
  auto h_bc = Kokkos::create_mirror_view(_m.nodes.bc);
  for (Index n = 0; n < num_nodes; ++n)
  {
    for (int i = 0; i < 3; ++i)
    {
      h_x0(n, i) = _m.mesh.coords[size_t(n)][size_t(i)];
      h_bc(n, i) = -1;
    }
    h_mass(n) = 0;
  }
  for (size_t p = 0; p < _m.mesh.parts.size(); ++p)
  {
    const HostPart &part = _m.mesh.parts[p];
    const int nn = nodesPerElement(part.type);
    const MaterialParams &mat = _m.materials_host[size_t(part.material)];
    for (Index e = 0; e < part.numElements(); ++e)
    {
      const Index d = _m.host_to_device_element[size_t(elem_first[p] + e)];
      Real x[kMaxElementNodes][3];
      for (int a = 0; a < kMaxElementNodes; ++a)
        h_conn(d, a) = -1;
      for (int a = 0; a < nn; ++a)
      {
        const Index n = part.connectivity[size_t(e * nn + a)];
        h_conn(d, a) = n;
        for (int i = 0; i < 3; ++i)
          x[a][i] = _m.mesh.coords[size_t(n)][size_t(i)];
      }
      if (axi)
        for (int a = 0; a < nn; ++a)
          if (x[a][0] < 0)
            throw InputError(_m.deck.path + ": parts[" + std::to_string(p) + "] ('" + part.name +
                             "'): node " +
                             std::to_string(globalNode(part.connectivity[size_t(e * nn + a)])) +
                             " is at radius x = " + formatReal(x[a][0]) +
                             " < 0: an axisymmetric mesh lies in x >= 0 (x is the radius, the "
                             "axis is x = 0)");
      const Real m = mat.density * hostElementVolume(part.type, x, axi);
      h_emass(d) = m;
      h_part(d) = Index(p);
      h_mat(d) = part.material;
      for (int a = 0; a < nn; ++a)
        h_mass(h_conn(d, a)) += m / nn;
    }
  }
  for (Index n = 0; n < num_nodes; ++n)
    if (!(h_mass(n) > 0))
      throw InputError(_m.deck.path + ": parts: node " + std::to_string(globalNode(n)) +
                       " belongs to no element (zero mass)");
  Kokkos::deep_copy(_m.elems.conn, h_conn);
  if (_m.dd) // step 2 [A]: every copy of a shared node holds the total mass
    sumSharedMasses(h_emass, h_mass);
  Kokkos::deep_copy(_m.nodes.x0, h_x0);
  Kokkos::deep_copy(_m.nodes.x, h_x0);
  Kokkos::deep_copy(_m.nodes.mass, h_mass);
  Kokkos::deep_copy(_m.nodes.bc, h_bc);
  Kokkos::deep_copy(_m.elems.part, h_part);
  Kokkos::deep_copy(_m.elems.material, h_mat);
  Kokkos::deep_copy(_m.elems.mass, h_emass);

  _m.materials = DeviceView<MaterialParams *>("materials", _m.materials_host.size());
  auto h_materials = Kokkos::create_mirror_view(_m.materials);
  for (size_t i = 0; i < _m.materials_host.size(); ++i)
    h_materials(i) = _m.materials_host[i];
  Kokkos::deep_copy(_m.materials, h_materials);

  _m.elems.row_pack = markRowPacks(_m.elems, _m.groups);
  if (orderedAssembly(_m.deck, _m.dd != nullptr))
    _m.corners = makeNodeCorners(_m.elems, _m.groups, num_nodes, ExecSpace().concurrency(),
                                 _m.dd ? _m.dd->shared.local : std::vector<Index>());
}

/// Step 12 inside step 6 for the nodes nothing after it touches (NodeSweep), when the element
/// step runs chunks in a known order: one thread, or the corner gather's chunks.
void ModelSetup::setupNodeSweep()
{
#if defined(KOKKOS_ENABLE_CUDA) || defined(KOKKOS_ENABLE_HIP) || defined(KOKKOS_ENABLE_SYCL)
  const bool ordered = false; // no chunks on a device
#else
  const bool ordered = ExecSpace().concurrency() == 1 || orderedAssembly(_m.deck, _m.dd != nullptr);
#endif
  if (_m.deck.node_update != NodeUpdateMode::Fused || !ordered)
    return;
  // every room that acts on nodes between steps 6 and 12 declares them (LateNodes.hpp)
  LateNodes late(_m.nodes.count);
  declareLateNodes(_m.bc, late);
  if (_m.contact)
    _m.contact->declareLateNodes(late);
  if (_m.dd) // step 7 sums the shared nodes; a node this rank does not own is counted elsewhere
  {
    late.declare("shared-node exchange", _m.dd->shared_nodes);
    std::vector<char> not_owned(_m.dd->owned.size());
    for (size_t n = 0; n < not_owned.size(); ++n)
      not_owned[n] = char(!_m.dd->owned[n]);
    late.declareFlagged("nodes of other ranks", not_owned);
  }
  _m.sweep = makeNodeSweep(_m.elems, _m.groups, _m.nodes,
                           orderedAssembly(_m.deck, _m.dd != nullptr) ? _m.corners.chunks : 1,
                           late.mask());
  _m.sweep_nodes =
      _m.dd ? long(allReduceSum((long long)_m.sweep.early_nodes, _m.comm)) : _m.sweep.early_nodes;
}

void ModelSetup::setupSets()
{
  _m.node_sets = _m.mesh.node_sets;
  _m.face_sets = _m.mesh.face_sets;
  auto partsMatching = [&](const std::string &pattern, const std::string &key) {
    std::vector<int> parts;
    for (size_t p = 0; p < _m.mesh.parts.size(); ++p)
      if (partMatches(_m.mesh.parts[p].name, pattern))
        parts.push_back(int(p));
    if (parts.empty())
      throw InputError(_m.deck.path + ": " + key + ": no part named '" + pattern + "'");
    return parts;
  };
  const Real tol = 1e-9;
  for (size_t i = 0; i < _m.deck.node_sets.size(); ++i)
  {
    const SetSpec &s = _m.deck.node_sets[i];
    const std::string key = "node_sets[" + std::to_string(i) + "]";
    // part, box, or both: the part's nodes in the box
    std::vector<Index> nodes;
    if (!s.part.empty())
    {
      nodes = nodesOfParts(_m.mesh, partsMatching(s.part, key + ".part"));
      unifyNodeSet(nodes);
    }
    if (s.has_box)
    {
      std::vector<Index> in_box = nodesInBox(_m.mesh, s.box_min, s.box_max, tol);
      if (!s.part.empty())
      {
        std::vector<Index> both;
        std::sort(nodes.begin(), nodes.end());
        std::set_intersection(nodes.begin(), nodes.end(), in_box.begin(), in_box.end(),
                              std::back_inserter(both));
        in_box.swap(both);
      }
      nodes.swap(in_box);
    }
    checkSetNotEmpty(nodes.size(),
                     _m.deck.path + ": " + key + ": node set '" + s.name + "' selects no node");
    if (_m.mesh.node_sets.count(s.name)) // else the deck's set silently replaced the file's
      throw InputError(_m.deck.path + ": " + key + ".name: '" + s.name +
                       "' is also a physical group of a gmsh mesh; rename one of them");
    _m.node_sets[s.name] = nodes;
  }
  for (size_t i = 0; i < _m.deck.face_sets.size(); ++i)
  {
    const SetSpec &s = _m.deck.face_sets[i];
    const std::string key = "face_sets[" + std::to_string(i) + "]";
    std::vector<HostFace> faces =
        s.part.empty() ? _m.external_faces
                       : facesOfParts(_m.external_faces, partsMatching(s.part, key + ".part"));
    if (s.has_box)
      faces = facesInBox(faces, _m.mesh, s.box_min, s.box_max, tol);
    checkSetNotEmpty(faces.size(),
                     _m.deck.path + ": " + key + ": face set '" + s.name + "' selects no face");
    if (_m.mesh.face_sets.count(s.name))
      throw InputError(_m.deck.path + ": " + key + ".name: '" + s.name +
                       "' is also a physical group of a gmsh mesh; rename one of them");
    _m.face_sets[s.name] = faces;
  }
}

void ModelSetup::setupBoundaryConditions()
{
  std::vector<Index> force_node, force_bc;
  std::vector<std::array<Index, 4>> pface;
  std::vector<Index> pface_nodes, pface_bc;
  auto h_bc = Kokkos::create_mirror_view(_m.nodes.bc);
  Kokkos::deep_copy(h_bc, _m.nodes.bc);
  for (size_t i = 0; i < _m.deck.boundary_conditions.size(); ++i)
  {
    const BoundaryConditionSpec &b = _m.deck.boundary_conditions[i];
    const std::string key = _m.deck.path + ": boundary_conditions[" + std::to_string(i) + "]";
    const int fn = findFunction(_m.deck.functions, b.function, key + ".function");
    if (b.type == ConditionType::Pressure)
    {
      auto it = _m.face_sets.find(b.set);
      if (it == _m.face_sets.end())
        throw InputError(key + ".face_set (line " + std::to_string(b.set_line) +
                         "): unknown face set '" + b.set + "'" +
                         setSuggestion(b.set, _m.face_sets));
      const int k = int(_m.bc.pressure_value.size());
      _m.bc.pressure_value.push_back(b.value);
      _m.bc.pressure_function.push_back(fn);
      for (const HostFace &f : it->second)
      {
        std::array<Index, 4> nodes = {f.nodes[0], f.nodes[1], f.nodes[2], f.nodes[3]};
        if (f.num_nodes == 1)
        {
          // 1D: the element's other node fixes the outward direction
          const Index d = _m.host_to_device_element[size_t(f.element)];
          auto conn = Kokkos::create_mirror_view_and_copy(
              HostSpace(), Kokkos::subview(_m.elems.conn, d, Kokkos::ALL));
          nodes[1] = conn(0) == f.nodes[0] ? conn(1) : conn(0);
        }
        pface.push_back(nodes);
        pface_nodes.push_back(f.num_nodes);
        pface_bc.push_back(k);
      }
      continue;
    }
    auto it = _m.node_sets.find(b.set);
    if (it == _m.node_sets.end())
      throw InputError(key + ".node_set (line " + std::to_string(b.set_line) +
                       "): unknown node set '" + b.set + "'" + setSuggestion(b.set, _m.node_sets));
    if (b.type == ConditionType::Velocity)
    {
      const int k = int(_m.bc.velocity_value.size());
      _m.bc.velocity_value.push_back(b.value);
      _m.bc.velocity_function.push_back(fn);
      for (Index n : it->second)
        h_bc(n, b.component) = k;
    }
    else
    {
      const int k = int(_m.bc.force_value.size());
      _m.bc.force_value.push_back(b.vector);
      _m.bc.force_function.push_back(fn);
      for (Index n : it->second)
      {
        force_node.push_back(n);
        force_bc.push_back(k);
      }
    }
  }
  Kokkos::deep_copy(_m.nodes.bc, h_bc);
  _m.bc.force_node = toDevice(force_node, "force_node");
  _m.bc.force_bc = toDevice(force_bc, "force_bc");
  _m.bc.pressure_face_nodes = toDevice(pface_nodes, "pressure_face_nodes");
  _m.bc.pressure_bc = toDevice(pface_bc, "pressure_bc");
  _m.bc.pressure_face = ConnView("pressure_face", pface.size(), 4);
  auto h_pf = Kokkos::create_mirror_view(_m.bc.pressure_face);
  for (size_t k = 0; k < pface.size(); ++k)
    for (int a = 0; a < 4; ++a)
      h_pf(k, a) = pface[k][size_t(a)];
  Kokkos::deep_copy(_m.bc.pressure_face, h_pf);
  _m.bc.velocity_current = RealView("velocity_bc", _m.bc.velocity_value.size());
  if (!_m.bc.velocity_value.empty()) // the reactions of spcforc.csv
    _m.nodes.reaction = VectorView("reaction", size_t(_m.nodes.count));
  _m.bc.force_current = DeviceView<Real *[3]>("force_bc_value", _m.bc.force_value.size());
  _m.bc.pressure_current = RealView("pressure_bc_value", _m.bc.pressure_value.size());
}

void ModelSetup::setupPartRelease()
{
  // a node of several parts is held until the latest of their release times
  std::vector<Real> hold(size_t(_m.nodes.count), 0);
  bool any = false;
  for (const PartSpec &p : _m.deck.parts)
    any = any || p.release_time > 0;
  if (!any)
    return;
  auto h_conn = Kokkos::create_mirror_view_and_copy(HostSpace(), _m.elems.conn);
  auto h_part = Kokkos::create_mirror_view_and_copy(HostSpace(), _m.elems.part);
  for (Index e = 0; e < _m.elems.count; ++e)
  {
    const Real t = _m.deck.parts[size_t(_m.part_spec[size_t(h_part(e))])].release_time;
    for (int a = 0; a < kMaxElementNodes; ++a)
      if (h_conn(e, a) >= 0)
        hold[size_t(h_conn(e, a))] = std::max(hold[size_t(h_conn(e, a))], t);
  }
  _m.release = holdNodes(hold, _m.deck.dimension, _m.nodes, _m.bc);
  // every rank has a group for every release time of the deck, some maybe without nodes, so
  // that the ranks release in the same cycles and reduce what they released together
  for (const PartSpec &p : _m.deck.parts)
  {
    bool known = !(p.release_time > 0);
    for (const PartRelease::Group &g : _m.release.groups)
      known = known || g.time == p.release_time;
    if (known)
      continue;
    PartRelease::Group g;
    g.time = p.release_time;
    _m.release.groups.push_back(g);
  }
}

void ModelSetup::setupInitialState()
{
  // initial velocity per part; a node merged between parts takes the mass-weighted mean,
  // which keeps the total momentum of the deck
  const Index num_nodes = _m.mesh.numNodes();
  std::vector<std::array<Real, 3>> momentum(size_t(num_nodes), {0, 0, 0});
  std::vector<Real> mass(size_t(num_nodes), 0);
  auto h_emass = Kokkos::create_mirror_view_and_copy(HostSpace(), _m.elems.mass);
  auto h_conn = Kokkos::create_mirror_view_and_copy(HostSpace(), _m.elems.conn);
  auto h_part = Kokkos::create_mirror_view_and_copy(HostSpace(), _m.elems.part);
  for (Index e = 0; e < _m.elems.count; ++e)
  {
    const HostPart &part = _m.mesh.parts[size_t(h_part(e))];
    const auto &v0 = _m.deck.parts[size_t(_m.part_spec[size_t(h_part(e))])].initial_velocity;
    const int nn = nodesPerElement(part.type);
    for (int a = 0; a < nn; ++a)
    {
      const Index n = h_conn(e, a);
      const Real m = h_emass(e) / nn;
      mass[size_t(n)] += m;
      for (int i = 0; i < 3; ++i)
        momentum[size_t(n)][size_t(i)] += m * v0[size_t(i)];
    }
  }
  if (_m.dd)
  { // a node shared between ranks takes the mean over the elements of every rank, summed in
    // the serial order (device element, then corner), so every copy has the serial bits
    std::vector<std::pair<Index, int>> corners;
    const std::vector<Index> &cell = _m.dd->output_cell;
    const auto terms = cornerTerms(
        [&](Index e, int a) {
          return TermKey{cell[size_t(e)], a, 0};
        },
        {}, &corners);
    std::vector<Real> values, sums(4 * size_t(num_nodes));
    for (const auto &[e, a] : corners)
    {
      const HostPart &part = _m.mesh.parts[size_t(h_part(e))];
      const auto &v0 = _m.deck.parts[size_t(_m.part_spec[size_t(h_part(e))])].initial_velocity;
      const Real m = h_emass(e) / nodesPerElement(part.type);
      values.insert(values.end(), {m, m * v0[0], m * v0[1], m * v0[2]});
    }
    OrderedNodeSum(_m.comm, _m.dd->shared, terms).sumHost(values, 4, sums);
    for (Index n : _m.dd->shared.local)
    {
      mass[size_t(n)] = sums[4 * size_t(n)];
      for (int i = 0; i < 3; ++i)
        momentum[size_t(n)][size_t(i)] = sums[4 * size_t(n) + 1 + size_t(i)];
    }
  }
  auto h_v = Kokkos::create_mirror_view(_m.nodes.v);
  auto h_bc = Kokkos::create_mirror_view_and_copy(HostSpace(), _m.nodes.bc);
  updateVelocityValues(_m.bc, 0.0);
  auto h_vbc = Kokkos::create_mirror_view_and_copy(HostSpace(), _m.bc.velocity_current);
  const int dim = _m.deck.dimension;
  for (Index n = 0; n < num_nodes; ++n)
    for (int i = 0; i < 3; ++i)
      h_v(n, i) = i < dim ? momentum[size_t(n)][size_t(i)] / mass[size_t(n)] : 0;
  // the deck's initial_conditions, in order, over the parts' velocities: v = v0 + G (x - about)
  for (size_t c = 0; c < _m.deck.initial_velocities.size(); ++c)
  {
    const InitialVelocitySpec &iv = _m.deck.initial_velocities[c];
    const auto set = _m.node_sets.find(iv.node_set);
    if (set == _m.node_sets.end())
      throw InputError(_m.deck.path + ": initial_conditions[" + std::to_string(c) +
                       "].node_set (line " + std::to_string(iv.set_line) + "): unknown node set '" +
                       iv.node_set + "'" + setSuggestion(iv.node_set, _m.node_sets));
    for (Index n : set->second)
      for (int i = 0; i < dim; ++i)
      {
        Real v = iv.velocity[size_t(i)];
        for (int j = 0; j < dim; ++j)
          v += iv.gradient[size_t(i)][size_t(j)] *
               (_m.mesh.coords[size_t(n)][size_t(j)] - iv.about[size_t(j)]);
        h_v(n, i) = v;
      }
  }
  setReleaseVelocities(_m.release, h_v);
  for (Index n = 0; n < num_nodes; ++n)
    for (int i = 0; i < 3; ++i)
      if (h_bc(n, i) >= 0)
        h_v(n, i) = h_vbc(h_bc(n, i));
  Kokkos::deep_copy(_m.nodes.v, h_v);

  // initial specific internal energy (the detonation energy of an explosive)
  {
    auto h_energy = Kokkos::create_mirror_view(_m.elems.energy);
    auto h_mat = Kokkos::create_mirror_view_and_copy(HostSpace(), _m.elems.material);
    for (Index e = 0; e < _m.elems.count; ++e)
      h_energy(e) = initialSpecificEnergy(_m.materials_host[size_t(h_mat(e))]);
    Kokkos::deep_copy(_m.elems.energy, h_energy);
  }

  // material history (e.g. lighting times) from element centroids
  auto conn = _m.elems.conn;
  auto x = _m.nodes.x;
  auto mat_id = _m.elems.material;
  auto materials = _m.materials;
  auto hist = _m.elems.history;
  Kokkos::parallel_for(
      "scpdyn::setup::materialHistory", Kokkos::RangePolicy<ExecSpace>(0, _m.elems.count),
      KOKKOS_LAMBDA(const Index e) {
        Real c[3] = {0, 0, 0};
        int nn = 0;
        for (int a = 0; a < kMaxElementNodes; ++a)
          if (conn(e, a) >= 0)
          {
            ++nn;
            for (int i = 0; i < 3; ++i)
              c[i] += x(conn(e, a), i);
          }
        for (int i = 0; i < 3; ++i)
          c[i] /= nn;
        Real h[kHistorySize];
        initializeMaterialHistory(materials(mat_id(e)), c, h);
        for (int k = 0; k < kHistorySize; ++k)
          hist(e, k) = h[k];
      });

  _m.controls.geometry = _m.deck.geometry;
  _m.controls.hourglass = _m.deck.hourglass_type == HourglassForm::Stiffness
                              ? HourglassType::Stiffness
                              : HourglassType::Viscous;
  _m.controls.hourglass_coefficient = _m.deck.hourglass_coefficient;
  _m.controls.q_linear = _m.deck.bulk_viscosity_linear;
  _m.controls.q_quadratic = _m.deck.bulk_viscosity_quadratic;
  _m.controls.gather = orderedAssembly(_m.deck, _m.dd != nullptr);
  for (const MaterialParams &m : _m.materials_host)
    _m.controls.erosion = _m.controls.erosion || m.erosion.active;

  const Real dt_elem =
      initialElementTimeStep(_m.groups, _m.deck.geometry, _m.nodes, _m.elems, _m.materials);
  if (_m.dd)
  {
    // the lowest failing rank names its element (global id); every rank stops alike
    const bool bad = !(dt_elem > 0);
    int first = bad ? _m.rank : _m.num_ranks;
    MPI_Allreduce(MPI_IN_PLACE, &first, 1, MPI_INT, MPI_MIN, _m.comm);
    long element = bad ? long(globalElement(meshElementOfDevice(Index(-dt_elem) - 1))) : 0;
    if (first < _m.num_ranks)
    {
      MPI_Bcast(&element, 1, MPI_LONG, first, _m.comm);
      throw InputError(_m.deck.path + ": parts: element " + std::to_string(element) +
                       " is inverted or degenerate");
    }
  }
  if (!(dt_elem > 0)) // the mesh id, as the decomposed path names it
    throw InputError(_m.deck.path + ": parts: element " +
                     std::to_string(globalElement(meshElementOfDevice(Index(-dt_elem) - 1))) +
                     " is inverted or degenerate");
  _m.initial_element_step = dt_elem;
}

} // namespace scpdyn
