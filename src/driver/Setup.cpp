// Set-up of the solver (steps 1 and 2 of the paper): meshes from the deck, sets, device
// fields, boundary conditions, gauges and the initial state.
#include "driver/Solver.hpp"
#include "core/HostCopy.hpp"

#include "bc/TimeFunctions.hpp"
#include "contact/ContactSystem.hpp"
#include "driver/Decomposition.hpp"
#include "element/ElementKinematics.hpp"
#include "material/MaterialLibrary.hpp"
#include "material/MaterialUpdate.hpp"
#include "mesh/GmshReader.hpp"
#include "mesh/MeshGenerators.hpp"
#include "mesh/MeshOps.hpp"
#include "parallel/Mpi.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace scpdyn
{

namespace
{
/// `scatter: gather` with one thread: plain adds in element order give the corner gather's sums
/// bit for bit (every node's corners are gathered in ascending element order from zero), so
/// the corner array and the gather pass are skipped.
bool cornerGather(const Deck &deck)
{
  return deck.scatter == ScatterMode::Gather && ExecSpace().concurrency() > 1;
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

Solver::Solver(const Deck &deck, MPI_Comm comm) : _deck(deck), _comm(comm)
{
  _rank = mpiRank(comm);
  _num_ranks = mpiSize(comm);
  for (const auto &m : _deck.materials)
    _materials_host.push_back(makeMaterialParams(m));
  _bc.functions = _deck.functions;
  setupMesh();
  if (_num_ranks > 1)
    decompose();
  setupFields();
  if (_dd)
    finishDecomposition();
  setupSets();
  setupBoundaryConditions();
  _external_loads = hasExternalLoads(_bc, _deck.gravity.data());
  setupContact();
  setupNodeSweep();
  setupGauges();
  setupInitialState();
  _global_mesh.reset(); // from here on a rank holds its own piece only
  if (_dd)
    _dd->halo_bytes_setup = _dd->halo->bytesSent();
}

Solver::~Solver() = default;

void Solver::setupMesh()
{
  std::vector<int> merge_parts;
  for (size_t s = 0; s < _deck.parts.size(); ++s)
  {
    const PartSpec &spec = _deck.parts[s];
    const std::string key = "parts[" + std::to_string(s) + "].mesh";
    const size_t first_part = _mesh.parts.size();
    try
    {
      const MeshSpec &m = spec.mesh;
      if (m.type == MeshType::Block)
        appendBlock(_mesh, spec.name, m.element, m.elements, m.origin, m.size);
      else if (m.type == MeshType::BrickWall)
        appendBrickWall(_mesh, spec.name, m.element, m.elements, m.origin,
                        m.brick_size, m.count, m.stagger);
      else
      {
        HostMesh g = readGmsh41(m.file);
        if (_mesh.dim != 0 && g.dim != _mesh.dim)
          throw std::runtime_error("mesh dimension " + std::to_string(g.dim) +
                                   " differs from the other parts");
        appendMesh(_mesh, std::move(g), spec.name + ".");
      }
    }
    catch (const InputError &)
    {
      throw;
    }
    catch (const std::exception &e)
    {
      throw InputError(_deck.path + ": " + key + ": " + e.what());
    }
    const int mat = materialIndex(_deck, spec.material);
    for (size_t p = first_part; p < _mesh.parts.size(); ++p)
    {
      _mesh.parts[p].material = mat;
      if (spec.merge_nodes)
        merge_parts.push_back(int(p));
    }
    _part_spec.resize(_mesh.parts.size(), int(s));
  }
  if (_mesh.dim != _deck.dimension)
    throw InputError(_deck.path + ": dimension: the deck says " + std::to_string(_deck.dimension) +
                     " but the meshes are " + std::to_string(_mesh.dim) + "-dimensional");
  try
  {
    if (merge_parts.size() > 1)
    {
      Real lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
      for (const auto &c : _mesh.coords)
        for (int i = 0; i < 3; ++i)
        {
          lo[i] = std::min(lo[i], c[size_t(i)]);
          hi[i] = std::max(hi[i], c[size_t(i)]);
        }
      const Real diag = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                  (hi[2] - lo[2]) * (hi[2] - lo[2]));
      mergeCoincidentNodes(_mesh, merge_parts, 1e-9 * diag);
    }
    checkElements(_mesh);
  }
  catch (const std::exception &e)
  {
    throw InputError(_deck.path + ": parts: " + e.what());
  }
  _external_faces = extractExternalFaces(_mesh);
}

void Solver::setupFields()
{
  const Index num_nodes = _mesh.numNodes();
  const Index num_elems = _mesh.numElements();
  const bool axi = _deck.dimension == 2 && _deck.geometry == Geometry2D::Axisymmetric;

  // device element order: grouped by type (stable in part order), so every launch is one type
  std::vector<std::pair<ElementType, Index>> order; // type, host element id
  std::vector<int> elem_part;
  std::vector<Index> elem_first(_mesh.parts.size() + 1, 0);
  for (size_t p = 0; p < _mesh.parts.size(); ++p)
    elem_first[p + 1] = elem_first[p] + _mesh.parts[p].numElements();
  for (size_t p = 0; p < _mesh.parts.size(); ++p)
    for (Index e = 0; e < _mesh.parts[p].numElements(); ++e)
      order.push_back({_mesh.parts[p].type, elem_first[p] + e});
  std::stable_sort(order.begin(), order.end(),
                   [](const auto &a, const auto &b) { return int(a.first) < int(b.first); });
  _host_to_device_element.assign(size_t(num_elems), -1);
  for (size_t k = 0; k < order.size(); ++k)
    _host_to_device_element[size_t(order[k].second)] = Index(k);
  for (size_t k = 0; k < order.size(); ++k)
    if (_groups.empty() || _groups.back().type != order[k].first)
      _groups.push_back({order[k].first, Index(k), Index(k + 1)});
    else
      _groups.back().end = Index(k + 1);

  _nodes.count = num_nodes;
  _nodes.x0 = VectorView("x0", size_t(num_nodes));
  _nodes.x = VectorView("x", size_t(num_nodes));
  _nodes.v = VectorView("v", size_t(num_nodes));
  _nodes.f_int = VectorView("f_int", size_t(num_nodes));
  _nodes.f_ext = VectorView("f_ext", size_t(num_nodes));
  if (!_deck.contact.surfaces.empty())
    _nodes.f_contact = VectorView("f_contact", size_t(num_nodes));
  _nodes.external_impulse = VectorView("external_impulse", size_t(num_nodes));
  _nodes.mass = RealView("node_mass", size_t(num_nodes));
  _nodes.bc = DeviceView<int * [3]>("node_bc", size_t(num_nodes));

  _elems.count = num_elems;
  const size_t ne = size_t(num_elems);
  _elems.conn = ConnView("conn", ne, kMaxElementNodes);
  _elems.part = IndexView("part", ne);
  _elems.material = IndexView("material", ne);
  _elems.mass = RealView("element_mass", ne);
  _elems.volume = RealView("volume", ne);
  _elems.stress = SymTensorView("stress", ne);
  _elems.energy = RealView("energy", ne);
  _elems.plastic_strain = RealView("plastic_strain", ne);
  _elems.q = RealView("q", ne);
  _elems.sound_speed = RealView("sound_speed", ne);
  _elems.hourglass_energy = RealView("hourglass_energy", ne);
  _elems.history = HistoryView("history", ne);
  _elems.hourglass = HourglassView("hourglass", ne);

  auto h_x0 = Kokkos::create_mirror_view(_nodes.x0);
  auto h_mass = Kokkos::create_mirror_view(_nodes.mass);
  auto h_conn = Kokkos::create_mirror_view(_elems.conn);
  auto h_part = Kokkos::create_mirror_view(_elems.part);
  auto h_mat = Kokkos::create_mirror_view(_elems.material);
  auto h_emass = Kokkos::create_mirror_view(_elems.mass);
  auto h_bc = Kokkos::create_mirror_view(_nodes.bc);
  for (Index n = 0; n < num_nodes; ++n)
  {
    for (int i = 0; i < 3; ++i)
    {
      h_x0(n, i) = _mesh.coords[size_t(n)][size_t(i)];
      h_bc(n, i) = -1;
    }
    h_mass(n) = 0;
  }
  for (size_t p = 0; p < _mesh.parts.size(); ++p)
  {
    const HostPart &part = _mesh.parts[p];
    const int nn = nodesPerElement(part.type);
    const MaterialParams &mat = _materials_host[size_t(part.material)];
    for (Index e = 0; e < part.numElements(); ++e)
    {
      const Index d = _host_to_device_element[size_t(elem_first[p] + e)];
      Real x[kMaxElementNodes][3];
      for (int a = 0; a < kMaxElementNodes; ++a)
        h_conn(d, a) = -1;
      for (int a = 0; a < nn; ++a)
      {
        const Index n = part.connectivity[size_t(e * nn + a)];
        h_conn(d, a) = n;
        for (int i = 0; i < 3; ++i)
          x[a][i] = _mesh.coords[size_t(n)][size_t(i)];
      }
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
      throw InputError(_deck.path + ": parts: node " + std::to_string(n) +
                       " belongs to no element (zero mass)");
  Kokkos::deep_copy(_nodes.x0, h_x0);
  Kokkos::deep_copy(_nodes.x, h_x0);
  Kokkos::deep_copy(_nodes.mass, h_mass);
  if (_dd) // step 2 [A]: every copy of a shared node holds the total mass
    _dd->halo->sum(_nodes.mass);
  Kokkos::deep_copy(_nodes.bc, h_bc);
  Kokkos::deep_copy(_elems.conn, h_conn);
  Kokkos::deep_copy(_elems.part, h_part);
  Kokkos::deep_copy(_elems.material, h_mat);
  Kokkos::deep_copy(_elems.mass, h_emass);

  _materials = DeviceView<MaterialParams *>("materials", _materials_host.size());
  auto h_materials = Kokkos::create_mirror_view(_materials);
  for (size_t i = 0; i < _materials_host.size(); ++i)
    h_materials(i) = _materials_host[i];
  Kokkos::deep_copy(_materials, h_materials);

  _elems.row_pack = markRowPacks(_elems, _groups);
  if (cornerGather(_deck))
    _corners = makeNodeCorners(_elems, _groups, num_nodes, ExecSpace().concurrency());
}

/// Step 12 inside step 6 for the nodes nothing after it touches (NodeSweep), when the element
/// step runs chunks in a known order: one thread, or the corner gather's chunks.
void Solver::setupNodeSweep()
{
#if defined(KOKKOS_ENABLE_CUDA) || defined(KOKKOS_ENABLE_HIP) || defined(KOKKOS_ENABLE_SYCL)
  const bool ordered = false; // no chunks on a device
#else
  const bool ordered = ExecSpace().concurrency() == 1 || cornerGather(_deck);
#endif
  if (_deck.node_update != NodeUpdateMode::Fused || !ordered)
    return;
  // every room that acts on nodes between steps 6 and 12 declares them (LateNodes.hpp)
  LateNodes late(_nodes.count);
  declareLateNodes(_bc, late);
  if (_contact)
    _contact->declareLateNodes(late);
  if (_dd) // step 7 sums the shared nodes; a node this rank does not own is counted elsewhere
  {
    late.declare("shared-node exchange", _dd->shared_nodes);
    std::vector<char> not_owned(_dd->owned.size());
    for (size_t n = 0; n < not_owned.size(); ++n)
      not_owned[n] = char(!_dd->owned[n]);
    late.declareFlagged("nodes of other ranks", not_owned);
  }
  _sweep = makeNodeSweep(_elems, _groups, _nodes, cornerGather(_deck) ? _corners.chunks : 1,
                         late.mask());
  _sweep_nodes = _dd ? long(allReduceSum((long long)_sweep.early_nodes, _comm)) : _sweep.early_nodes;
}

void Solver::setupSets()
{
  _node_sets = _mesh.node_sets;
  _face_sets = _mesh.face_sets;
  auto partsMatching = [&](const std::string &pattern, const std::string &key) {
    std::vector<int> parts;
    for (size_t p = 0; p < _mesh.parts.size(); ++p)
      if (partMatches(_mesh.parts[p].name, pattern))
        parts.push_back(int(p));
    if (parts.empty())
      throw InputError(_deck.path + ": " + key + ": no part named '" + pattern + "'");
    return parts;
  };
  const Real tol = 1e-9;
  for (size_t i = 0; i < _deck.node_sets.size(); ++i)
  {
    const SetSpec &s = _deck.node_sets[i];
    const std::string key = "node_sets[" + std::to_string(i) + "]";
    std::vector<Index> nodes =
        s.has_box ? nodesInBox(_mesh, s.box_min, s.box_max, tol)
                  : nodesOfParts(_mesh, partsMatching(s.part, key + ".part"));
    if (!s.has_box)
      unifyNodeSet(nodes);
    checkSetNotEmpty(nodes.size(),
                     _deck.path + ": " + key + ": node set '" + s.name + "' selects no node");
    _node_sets[s.name] = nodes;
  }
  for (size_t i = 0; i < _deck.face_sets.size(); ++i)
  {
    const SetSpec &s = _deck.face_sets[i];
    const std::string key = "face_sets[" + std::to_string(i) + "]";
    std::vector<HostFace> faces =
        s.has_box ? facesInBox(_external_faces, _mesh, s.box_min, s.box_max, tol)
                  : facesOfParts(_external_faces, partsMatching(s.part, key + ".part"));
    checkSetNotEmpty(faces.size(),
                     _deck.path + ": " + key + ": face set '" + s.name + "' selects no face");
    _face_sets[s.name] = faces;
  }
}

void Solver::setupBoundaryConditions()
{
  std::vector<Index> force_node, force_bc;
  std::vector<std::array<Index, 4>> pface;
  std::vector<Index> pface_nodes, pface_bc;
  auto h_bc = Kokkos::create_mirror_view(_nodes.bc);
  Kokkos::deep_copy(h_bc, _nodes.bc);
  for (size_t i = 0; i < _deck.boundary_conditions.size(); ++i)
  {
    const BoundaryConditionSpec &b = _deck.boundary_conditions[i];
    const std::string key = _deck.path + ": boundary_conditions[" + std::to_string(i) + "]";
    const int fn = findFunction(_deck.functions, b.function, key + ".function");
    if (b.type == ConditionType::Pressure)
    {
      auto it = _face_sets.find(b.set);
      if (it == _face_sets.end())
        throw InputError(key + ".face_set: unknown face set '" + b.set + "'");
      const int k = int(_bc.pressure_value.size());
      _bc.pressure_value.push_back(b.value);
      _bc.pressure_function.push_back(fn);
      for (const HostFace &f : it->second)
      {
        std::array<Index, 4> nodes = {f.nodes[0], f.nodes[1], f.nodes[2], f.nodes[3]};
        if (f.num_nodes == 1)
        {
          // 1D: the element's other node fixes the outward direction
          const Index d = _host_to_device_element[size_t(f.element)];
          auto conn = Kokkos::create_mirror_view_and_copy(HostSpace(), Kokkos::subview(_elems.conn, d, Kokkos::ALL));
          nodes[1] = conn(0) == f.nodes[0] ? conn(1) : conn(0);
        }
        pface.push_back(nodes);
        pface_nodes.push_back(f.num_nodes);
        pface_bc.push_back(k);
      }
      continue;
    }
    auto it = _node_sets.find(b.set);
    if (it == _node_sets.end())
      throw InputError(key + ".node_set: unknown node set '" + b.set + "'");
    if (b.type == ConditionType::Velocity)
    {
      const int k = int(_bc.velocity_value.size());
      _bc.velocity_value.push_back(b.value);
      _bc.velocity_function.push_back(fn);
      for (Index n : it->second)
        h_bc(n, b.component) = k;
    }
    else
    {
      const int k = int(_bc.force_value.size());
      _bc.force_value.push_back(b.vector);
      _bc.force_function.push_back(fn);
      for (Index n : it->second)
      {
        force_node.push_back(n);
        force_bc.push_back(k);
      }
    }
  }
  Kokkos::deep_copy(_nodes.bc, h_bc);
  _bc.force_node = toDevice(force_node, "force_node");
  _bc.force_bc = toDevice(force_bc, "force_bc");
  _bc.pressure_face_nodes = toDevice(pface_nodes, "pressure_face_nodes");
  _bc.pressure_bc = toDevice(pface_bc, "pressure_bc");
  _bc.pressure_face = ConnView("pressure_face", pface.size(), 4);
  auto h_pf = Kokkos::create_mirror_view(_bc.pressure_face);
  for (size_t k = 0; k < pface.size(); ++k)
    for (int a = 0; a < 4; ++a)
      h_pf(k, a) = pface[k][size_t(a)];
  Kokkos::deep_copy(_bc.pressure_face, h_pf);
  _bc.velocity_current = RealView("velocity_bc", _bc.velocity_value.size());
  _bc.force_current = DeviceView<Real * [3]>("force_bc_value", _bc.force_value.size());
  _bc.pressure_current = RealView("pressure_bc_value", _bc.pressure_value.size());
}

void Solver::setupInitialState()
{
  // initial velocity per part; a node merged between parts takes the mass-weighted mean,
  // which keeps the total momentum of the deck
  const Index num_nodes = _mesh.numNodes();
  std::vector<std::array<Real, 3>> momentum(size_t(num_nodes), {0, 0, 0});
  std::vector<Real> mass(size_t(num_nodes), 0);
  auto h_emass = Kokkos::create_mirror_view_and_copy(HostSpace(), _elems.mass);
  auto h_conn = Kokkos::create_mirror_view_and_copy(HostSpace(), _elems.conn);
  auto h_part = Kokkos::create_mirror_view_and_copy(HostSpace(), _elems.part);
  for (Index e = 0; e < _elems.count; ++e)
  {
    const HostPart &part = _mesh.parts[size_t(h_part(e))];
    const auto &v0 = _deck.parts[size_t(_part_spec[size_t(h_part(e))])].initial_velocity;
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
  if (_dd)
  { // a node shared between ranks takes the mean over the elements of every rank
    VectorView p("initial_momentum", size_t(num_nodes));
    RealView m("initial_mass", size_t(num_nodes));
    auto h_p = Kokkos::create_mirror_view(p);
    auto h_m = Kokkos::create_mirror_view(m);
    for (Index n = 0; n < num_nodes; ++n)
    {
      h_m(n) = mass[size_t(n)];
      for (int i = 0; i < 3; ++i)
        h_p(n, i) = momentum[size_t(n)][size_t(i)];
    }
    Kokkos::deep_copy(p, h_p);
    Kokkos::deep_copy(m, h_m);
    _dd->halo->sum(p);
    _dd->halo->sum(m);
    Kokkos::deep_copy(h_p, p);
    Kokkos::deep_copy(h_m, m);
    for (Index n = 0; n < num_nodes; ++n)
    {
      mass[size_t(n)] = h_m(n);
      for (int i = 0; i < 3; ++i)
        momentum[size_t(n)][size_t(i)] = h_p(n, i);
    }
  }
  auto h_v = Kokkos::create_mirror_view(_nodes.v);
  auto h_bc = Kokkos::create_mirror_view_and_copy(HostSpace(), _nodes.bc);
  updateVelocityValues(_bc, 0.0);
  auto h_vbc = Kokkos::create_mirror_view_and_copy(HostSpace(), _bc.velocity_current);
  for (Index n = 0; n < num_nodes; ++n)
    for (int i = 0; i < 3; ++i)
    {
      h_v(n, i) = i < _deck.dimension ? momentum[size_t(n)][size_t(i)] / mass[size_t(n)] : 0;
      if (h_bc(n, i) >= 0)
        h_v(n, i) = h_vbc(h_bc(n, i));
    }
  Kokkos::deep_copy(_nodes.v, h_v);

  // initial specific internal energy (the detonation energy of an explosive)
  {
    auto h_energy = Kokkos::create_mirror_view(_elems.energy);
    auto h_mat = Kokkos::create_mirror_view_and_copy(HostSpace(), _elems.material);
    for (Index e = 0; e < _elems.count; ++e)
      h_energy(e) = initialSpecificEnergy(_materials_host[size_t(h_mat(e))]);
    Kokkos::deep_copy(_elems.energy, h_energy);
  }

  // material history (e.g. lighting times) from element centroids
  auto conn = _elems.conn;
  auto x = _nodes.x;
  auto mat_id = _elems.material;
  auto materials = _materials;
  auto hist = _elems.history;
  Kokkos::parallel_for(
      "scpdyn::setup::materialHistory", Kokkos::RangePolicy<ExecSpace>(0, _elems.count),
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

  _controls.geometry = _deck.geometry;
  _controls.hourglass =
      _deck.hourglass_type == HourglassForm::Stiffness ? HourglassType::Stiffness : HourglassType::Viscous;
  _controls.hourglass_coefficient = _deck.hourglass_coefficient;
  _controls.q_linear = _deck.bulk_viscosity_linear;
  _controls.q_quadratic = _deck.bulk_viscosity_quadratic;
  _controls.gather = cornerGather(_deck);

  const Real dt_elem = initialElementTimeStep(_groups, _deck.geometry, _nodes, _elems, _materials);
  if (_dd)
  {
    // the lowest failing rank names its element (global id); every rank stops alike
    const bool bad = !(dt_elem > 0);
    int first = bad ? _rank : _num_ranks;
    MPI_Allreduce(MPI_IN_PLACE, &first, 1, MPI_INT, MPI_MIN, _comm);
    long element = bad ? long(globalElement(meshElementOfDevice(Index(-dt_elem) - 1))) : 0;
    if (first < _num_ranks)
    {
      MPI_Bcast(&element, 1, MPI_LONG, first, _comm);
      throw InputError(_deck.path + ": parts: element " + std::to_string(element) +
                       " is inverted or degenerate");
    }
  }
  if (!(dt_elem > 0))
    throw InputError(_deck.path + ": parts: element " + std::to_string(Index(-dt_elem) - 1) +
                     " is inverted or degenerate");
  NodeSums s = nodeSums(_nodes, _dd ? _dd->owned_device : IndexView());
  TimeStepLimits first;
  first.element = dt_elem;
  _dt_next = nextTimeStep(first, timeStepControls(), s, _dd ? _comm : MPI_COMM_NULL);
  _last_sums = s;
  _kinetic_mid = s.kinetic;
  _initial_energy = 0;
  _initial_energy = s.kinetic + energies().internal;
  _energy_scale = std::abs(_initial_energy);
}

} // namespace scpdyn
