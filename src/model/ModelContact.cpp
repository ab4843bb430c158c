// Set-up of the contact system (docs/theory.md 3): its faces and parameters; in a decomposed run
// also the communication of its ghost faces (docs/theory.md 2.2, steps 4 and 8).
#include "model/ModelSetup.hpp"

#include "contact/ContactSystem.hpp"
#include "material/MaterialLibrary.hpp"
#include "parallel/Decomposition.hpp"
#include "parallel/GhostFaces.hpp"
#include "parallel/Mpi.hpp"

#include <algorithm>

namespace scpdyn
{

void ModelSetup::setupContact()
{
  if (_m.deck.contact.surfaces.empty())
    return;
  ContactMeshInput in;
  in.deck = &_m.deck;
  in.mesh = &_m.mesh;
  in.external_faces = &_m.external_faces;
  if (!_m.interior_faces.empty())
    in.interior_faces = &_m.interior_faces;
  in.face_sets = &_m.face_sets;
  in.host_to_device_element = &_m.host_to_device_element;
  in.nodes = _m.nodes;
  in.elems = _m.elems;
  for (const MaterialParams &m : _m.materials_host)
  {
    const std::vector<std::string> names = historyNames(m);
    const auto at = std::find(names.begin(), names.end(), "damage");
    in.damage_slot.push_back(at == names.end() ? -1 : int(at - names.begin()));
  }
  if (_m.dd)
  {
    in.global_element = &_m.dd->global_element;
    MPI_Comm comm = _m.comm;
    in.global_count = [comm](long long n) { return allReduceSum(n, comm); };
  }
  _m.contact = std::make_shared<ContactSystem>(in);
  if (_m.dd)
    setupContactGhosts();
}

void ModelSetup::setupContactGhosts()
{
  const Index n = _m.nodes.count;
  auto h_mass = Kokkos::create_mirror_view_and_copy(HostSpace(), _m.nodes.mass);
  auto h_bc = Kokkos::create_mirror_view_and_copy(HostSpace(), _m.nodes.bc);
  std::vector<Real> mass(static_cast<size_t>(n));
  std::vector<std::array<int, 3>> bc(static_cast<size_t>(n));
  for (Index k = 0; k < n; ++k)
  {
    mass[size_t(k)] = h_mass(k);
    bc[size_t(k)] = {h_bc(k, 0), h_bc(k, 1), h_bc(k, 2)};
  }
  _m.dd->ghosts = std::make_unique<GhostFaces>(_m.comm, _m.dd->global_node, mass, bc);
  _m.dd->own_faces = _m.contact->ownFaces();
  auto shared = Kokkos::create_mirror_view_and_copy(HostSpace(), _m.dd->shared_nodes);
  _m.dd->shared_host.assign(shared.data(), shared.data() + shared.extent(0));
  ContactComm cc;
  DomainDecomposition *dd = _m.dd.get();
  cc.sum_nodes = [dd](const VectorView &f) {
    dd->halo->sum(f);
    dd->ghosts->gather(&f, 1);
  };
  MPI_Comm comm = _m.comm;
  if (orderedAssembly(_m.deck, true))
  {
    cc.shared_index = dd->shared_index;
    cc.owned = dd->owned;
    cc.ordered_plan = [dd, comm](const std::vector<std::vector<NodeTerm>> &terms) {
      return std::make_shared<OrderedNodeSum>(comm, dd->shared, terms, &dd->ordered_bytes);
    };
    cc.gather_ghosts = [dd](const VectorView &f) { dd->ghosts->gather(&f, 1); };
  }
  cc.sum = [comm](Real *v, int count) { allReduceSum(v, count, comm); };
  cc.max = [comm](Real v) { return allReduceMax(v, comm); };
  cc.sum_exact = [comm](std::int64_t *v, int count) {
    MPI_Allreduce(MPI_IN_PLACE, v, count, MPI_INT64_T, MPI_SUM, comm);
  };
  _m.contact->setComm(cc);
}

} // namespace scpdyn
