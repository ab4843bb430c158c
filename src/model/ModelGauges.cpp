// Set-up of the gauges: each resolved to a node or element of the whole mesh and kept by the
// rank that holds it.
#include "model/ModelSetup.hpp"
#include "core/RealText.hpp"

#include "contact/ContactSystem.hpp"
#include "contact/JointGauge.hpp"
#include "mesh/MeshOps.hpp"
#include "parallel/Decomposition.hpp"
#include "parallel/Mpi.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace scpdyn
{

void ModelSetup::setupGauges()
{
  // gauges are resolved on the whole mesh (every rank alike), then kept by the rank that owns
  // the node or holds the element; the others keep id -1
  const HostMesh &mesh = _m.global_mesh ? *_m.global_mesh : _m.mesh;
  const MeshBox box = meshBox(mesh); // a gauge point must lie near it
  std::vector<Index> ids;
  std::vector<Index> codes;
  for (size_t g = 0; g < _m.deck.gauges.size(); ++g)
  {
    const GaugeSpec &spec = _m.deck.gauges[g];
    const std::string key = _m.deck.path + ": gauges[" + std::to_string(g) + "]";
    if (spec.kind == GaugeKind::Joint && !_m.contact)
      throw InputError(key + ".kind: a joint gauge needs a 'contact' section");
    const bool on_element = spec.kind == GaugeKind::Element;
    Index id = spec.id;
    if (spec.has_point)
    {
      // a point well outside every mesh is a typo (a unit, a sign), not a gauge
      const Real margin = 0.1 * box.diagonal();
      for (int i = 0; i < _m.deck.dimension; ++i)
        if (spec.point[size_t(i)] < box.lo[size_t(i)] - margin ||
            spec.point[size_t(i)] > box.hi[size_t(i)] + margin)
          throw InputError(key + ".point: coordinate " + std::to_string(i) + " = " +
                           formatReal(spec.point[size_t(i)]) + " m lies outside the meshes (" +
                           formatReal(box.lo[size_t(i)]) + " to " + formatReal(box.hi[size_t(i)]) +
                           " m, with a margin of 10 % of their diagonal)");
      // nearest node, or the element with the nearest centroid
      Real best = std::numeric_limits<Real>::max();
      const Index count = on_element ? mesh.numElements() : mesh.numNodes();
      Index e_first = 0;
      size_t part = 0;
      for (Index k = 0; k < count; ++k)
      {
        Real c[3] = {0, 0, 0};
        if (on_element)
        {
          while (k >= e_first + mesh.parts[part].numElements())
            e_first += mesh.parts[part++].numElements();
          const HostPart &p = mesh.parts[part];
          const int nn = nodesPerElement(p.type);
          for (int a = 0; a < nn; ++a)
            for (int i = 0; i < 3; ++i)
              c[i] +=
                  mesh.coords[size_t(p.connectivity[size_t((k - e_first) * nn + a)])][size_t(i)] /
                  nn;
        }
        else
          for (int i = 0; i < 3; ++i)
            c[i] = mesh.coords[size_t(k)][size_t(i)];
        Real d = 0;
        for (int i = 0; i < 3; ++i)
          d += (c[i] - spec.point[size_t(i)]) * (c[i] - spec.point[size_t(i)]);
        if (d < best)
        {
          best = d;
          id = k;
        }
      }
    }
    const Index limit = on_element ? mesh.numElements() : mesh.numNodes();
    if (id < 0 || id >= limit)
      throw InputError(key + ": " + (on_element ? "element " : "node ") + std::to_string(id) +
                       " does not exist (the mesh has " + std::to_string(limit) + ")");
    Index device_id = on_element ? _m.host_to_device_element[size_t(id)] : id;
    if (_m.dd)
    {
      const auto &map = on_element ? _m.dd->global_element : _m.dd->global_node;
      const auto it = std::lower_bound(map.begin(), map.end(), id);
      const Index local = it != map.end() && *it == id ? Index(it - map.begin()) : -1;
      device_id = local < 0                          ? -1
                  : on_element                       ? _m.host_to_device_element[size_t(local)]
                  : _m.dd->owned[size_t(local)] != 0 ? local
                                                     : -1;
    }
    const bool joint =
        spec.kind == GaugeKind::Joint; // the nearest node carries it with the material
    const auto &names = gaugeQuantities(spec.kind);
    for (const auto &q : spec.quantities)
    {
      const int code = int(std::find(names.begin(), names.end(), q) - names.begin());
      if (code == int(names.size()))
        throw InputError(key + ".quantities: unknown quantity '" + q + "' for a " +
                         deckName(spec.kind) + " gauge");
      // a joint gauge's slot is filled by jointGaugeValues(); the kernel leaves it at 0
      const Index slot_id = joint ? -1 : device_id;
      _m.gauges.push_back({spec.name + ":" + q, on_element, slot_id, code,
                           joint ? int(_m.joint_gauges.size()) : -1});
      ids.push_back(slot_id);
      codes.push_back(joint ? 0 : code + (on_element ? 100 : 0));
    }
    if (joint)
      _m.joint_gauges.push_back({device_id, spec.radius});
  }
  _m.gauge_id = IndexView("gauge_id", ids.size());
  _m.gauge_code = IndexView("gauge_code", codes.size());
  auto h_id = Kokkos::create_mirror_view(_m.gauge_id);
  auto h_code = Kokkos::create_mirror_view(_m.gauge_code);
  for (size_t k = 0; k < ids.size(); ++k)
  {
    h_id(k) = ids[k];
    h_code(k) = codes[k];
  }
  Kokkos::deep_copy(_m.gauge_id, h_id);
  Kokkos::deep_copy(_m.gauge_code, h_code);
}

} // namespace scpdyn
