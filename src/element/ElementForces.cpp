// Step 6 of the cycle without an after-block hook, the corner gather, the row packs and the
// initial element time step.
#include "element/ElementForces.hpp"

#include "core/HostCopy.hpp"
#include "element/ElementLaunch.hpp"

namespace scpdyn
{
namespace
{

template <ElementType T, bool Axi>
Real initialGroup(const ElementGroup &g, const NodeFields &nodes, const ElementFields &el,
                  const DeviceView<MaterialParams *> &materials)
{
  constexpr int N = ElementTraits<T>::nodes;
  auto conn = el.conn;
  auto x_n = nodes.x;
  auto mat_id = el.material;
  auto e_volume = el.volume, e_c = el.sound_speed;
  Real dt_min = 0;
  Kokkos::parallel_reduce(
      "initialDt", Kokkos::RangePolicy<ExecSpace>(g.begin, g.end),
      KOKKOS_LAMBDA(const Index e, Real &local_min) {
        Real x[N][3], B[N][3];
        for (int a = 0; a < N; ++a)
          for (int i = 0; i < 3; ++i)
            x[a][i] = x_n(conn(e, a), i);
        const Real measure = elementGradients<T>(x, B);
        Real V = measure;
        if constexpr (Axi)
          V = quad4RadialVolume(x);
        const MaterialParams &m = materials(mat_id(e));
        const Real c = kmath::sqrt(pWaveModulus(m.bulk, m.shear) / m.density);
        e_c(e) = c;
        e_volume(e) = V;
        const Real h = characteristicLength<T>(x, measure);
        const Real dt = (V > 0 && measure > 0) ? h / c : -Real(e + 1);
        local_min = dt < local_min ? dt : local_min;
      },
      Kokkos::Min<Real>(dt_min));
  return dt_min;
}

} // namespace

ElementStepResult computeElementForces(const std::vector<ElementGroup> &groups,
                                       const ElementControls &ctl, const NodeFields &nodes,
                                       const ElementFields &elems,
                                       const DeviceView<MaterialParams *> &materials,
                                       const NodeCorners &corners)
{
  return computeElementForcesWith(groups, ctl, nodes, elems, materials, corners, NoAfterBlock());
}

std::vector<int> nodeChunks(const ElementFields &elems, const std::vector<ElementGroup> &groups,
                            Index num_nodes, int chunks, std::vector<Index> *last)
{
  auto conn = Kokkos::create_mirror_view_and_copy(HostSpace(), elems.conn);
  std::vector<int> chunk_of(static_cast<size_t>(num_nodes), -1);
  if (last)
    last->assign(static_cast<size_t>(num_nodes), -1);
  int chunk = 0;
  for (const auto &g : groups)
    for (int c = 0; c < chunks; ++c, ++chunk)
      for (Index e = chunkBegin(g, chunks, c); e < chunkBegin(g, chunks, c + 1); ++e)
        for (int a = 0; a < kMaxElementNodes && conn(e, a) >= 0; ++a)
        {
          int &owner = chunk_of[size_t(conn(e, a))];
          owner = owner == -1 || owner == chunk ? chunk : -2;
          if (last)
            (*last)[size_t(conn(e, a))] = e;
        }
  return chunk_of;
}

NodeCorners makeNodeCorners(const ElementFields &elems, const std::vector<ElementGroup> &groups,
                            Index num_nodes, int chunks, const std::vector<Index> &also_shared)
{
  auto conn = Kokkos::create_mirror_view_and_copy(HostSpace(), elems.conn);
  std::vector<int> chunk_of = nodeChunks(elems, groups, num_nodes, chunks);
  for (Index n : also_shared)
    chunk_of[size_t(n)] = -2;
  // a slot per shared corner, in ascending (element, corner) order, so a node's slots ascend
  // as its corners do
  std::vector<std::uint8_t> mask(static_cast<size_t>(elems.count), 0);
  std::vector<Index> base(static_cast<size_t>(elems.count));
  std::vector<std::vector<Index>> lists(static_cast<size_t>(num_nodes));
  Index slots = 0;
  for (Index e = 0; e < elems.count; ++e)
  {
    base[size_t(e)] = slots;
    for (int a = 0; a < kMaxElementNodes && conn(e, a) >= 0; ++a)
      if (chunk_of[size_t(conn(e, a))] == -2)
      {
        mask[size_t(e)] = std::uint8_t(mask[size_t(e)] | 1u << a);
        lists[size_t(conn(e, a))].push_back(slots++);
      }
  }
  std::vector<Index> shared, offsets{0}, flat;
  for (Index n = 0; n < num_nodes; ++n)
    if (!lists[size_t(n)].empty())
    {
      shared.push_back(n);
      flat.insert(flat.end(), lists[size_t(n)].begin(), lists[size_t(n)].end());
      offsets.push_back(Index(flat.size()));
    }
  NodeCorners nc;
  nc.chunks = chunks;
  nc.shared_nodes = toDevice(shared, "shared_nodes");
  nc.offsets = toDevice(offsets, "corner_offsets");
  nc.corners = toDevice(flat, "corners");
  nc.shared_corners = toDevice(mask, "shared_corners");
  nc.corner_base = toDevice(base, "corner_base");
  nc.corner_force = VectorView("corner_force", size_t(slots));
  return nc;
}

DeviceView<std::uint8_t *> markRowPacks(const ElementFields &elems,
                                        const std::vector<ElementGroup> &groups)
{
  DeviceView<std::uint8_t *> row_pack("row_pack", size_t(elems.count));
  auto h_row = Kokkos::create_mirror_view(row_pack); // zeros, as Views start
  auto conn = Kokkos::create_mirror_view_and_copy(HostSpace(), elems.conn);
  constexpr int W = kElementLanes;
  for (const auto &g : groups)
    if (g.type == ElementType::Hex8)
      for (Index e = g.begin; e + W <= g.end; ++e)
      {
        bool row = true;
        for (int r = 0; r < 4; ++r)
          row = row && conn(e, kHexRowPlus[r]) == conn(e, kHexRowMinus[r]) + 1;
        for (int l = 1; l < W && row; ++l)
          for (int a = 0; a < 8; ++a)
            row = row && conn(e + l, a) == conn(e, a) + l;
        h_row(e) = row ? 1 : 0;
      }
  Kokkos::deep_copy(row_pack, h_row);
  return row_pack;
}

void gatherCornerForces(const NodeFields &nodes, const NodeCorners &corners)
{
  auto shared = corners.shared_nodes;
  auto offsets = corners.offsets;
  auto list = corners.corners;
  auto cf = corners.corner_force;
  auto f = nodes.f_int;
  Kokkos::parallel_for(
      "gatherCorners", Kokkos::RangePolicy<ExecSpace>(0, Index(shared.extent(0))),
      KOKKOS_LAMBDA(const Index s_n) {
        const Index n = shared(s_n);
        Real s[3] = {0, 0, 0};
        for (Index k = offsets(s_n); k < offsets(s_n + 1); ++k)
          for (int i = 0; i < 3; ++i)
            s[i] += cf(list(k), i);
        for (int i = 0; i < 3; ++i)
          f(n, i) = s[i];
      });
}

Real initialElementTimeStep(const std::vector<ElementGroup> &groups, Geometry2D geometry,
                            const NodeFields &nodes, const ElementFields &elems,
                            const DeviceView<MaterialParams *> &materials)
{
  Real dt_min = Kokkos::reduction_identity<Real>::min();
  const bool axi = geometry == Geometry2D::Axisymmetric;
  for (const auto &g : groups)
  {
    Real d = 0;
    switch (g.type)
    {
    case ElementType::Line2:
      d = initialGroup<ElementType::Line2, false>(g, nodes, elems, materials);
      break;
    case ElementType::Quad4:
      d = axi ? initialGroup<ElementType::Quad4, true>(g, nodes, elems, materials)
              : initialGroup<ElementType::Quad4, false>(g, nodes, elems, materials);
      break;
    case ElementType::Hex8:
      d = initialGroup<ElementType::Hex8, false>(g, nodes, elems, materials);
      break;
    case ElementType::Tet4:
      d = initialGroup<ElementType::Tet4, false>(g, nodes, elems, materials);
      break;
    }
    dt_min = d < dt_min ? d : dt_min;
  }
  return dt_min;
}

} // namespace scpdyn
