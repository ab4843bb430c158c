#include "element/InternalForce.hpp"

#include "core/HostCopy.hpp"
#include "element/ElementKernel.hpp"

namespace scpdyn
{
namespace
{

// Kernel labels stay within std::string's 15-character small-string buffer: Kokkos turns
// each label into a std::string per launch, and a longer one is a heap allocation per cycle.

using element_kernel::ElementKernel;
using element_kernel::Scatter;

template <ElementType T, bool Axi>
Real launchGroup(const ElementGroup &g, const ElementControls &ctl, Scatter scatter,
                 const NodeFields &nodes, const ElementFields &el,
                 const DeviceView<MaterialParams *> &materials, const NodeCorners &corners,
                 const NodeSweep &sweep, const int group_index)
{
  const ElementKernel<T, Axi> k =
      element_kernel::makeElementKernel<T, Axi>(ctl, scatter, nodes, el, materials, corners);

  Real dt_min = 0;
  // one chunk a thread, its packs or elements in order; with the node sweep, after each block
  // of them, step 12 on the block's early nodes
  if (sweep.active || scatter == Scatter::Corners)
  {
    const ElementGroup grp = g;
    const int chunks = sweep.active ? sweep.chunks : corners.chunks;
    constexpr Index B = NodeSweep::kSweepBlock;
    Kokkos::parallel_reduce(
        "elementChunks", Kokkos::RangePolicy<ExecSpace>(0, chunks),
        KOKKOS_LAMBDA(const int c, Real &local_min) {
          const Index begin = chunkBegin(grp, chunks, c), end = chunkBegin(grp, chunks, c + 1);
          if (!sweep.active)
          {
            k.range(begin, end, local_min);
            return;
          }
          Index b = sweep.block_base(group_index * chunks + c);
          for (Index first = begin; first < end; first += B, ++b)
          {
            k.range(first, end - first < B ? end : first + B, local_min);
            if (local_min < 0) // a failed element: the run stops after this step
              sweep.block_sums(b) = NodeSums();
            else
              sweep.integrateBlock<ElementTraits<T>::dim>(b);
          }
        },
        Kokkos::Min<Real>(dt_min));
    return dt_min;
  }
#ifdef SCPDYN_ELEMENT_LANES
  if constexpr (T == ElementType::Hex8 && !Axi)
  {
    constexpr Index W = kElementLanes;
    const Index begin = g.begin, end = g.end;
    Kokkos::parallel_reduce(
        "hex8Forces", Kokkos::RangePolicy<ExecSpace>(0, (end - begin + W - 1) / W),
        KOKKOS_LAMBDA(const Index p, Real &local_min) {
          const Index first = begin + p * W;
          k.range(first, end - first < W ? end : first + W, local_min);
        },
        Kokkos::Min<Real>(dt_min));
    return dt_min;
  }
#endif
  Kokkos::parallel_reduce(
      "elementForces", Kokkos::RangePolicy<ExecSpace>(g.begin, g.end),
      KOKKOS_LAMBDA(const Index e, Real &local_min) { k.one(e, local_min); },
      Kokkos::Min<Real>(dt_min));
  return dt_min;
}

template <bool Axi>
Real launchAny(const ElementGroup &g, const ElementControls &ctl, Scatter s,
               const NodeFields &nodes, const ElementFields &el,
               const DeviceView<MaterialParams *> &materials, const NodeCorners &corners,
               const NodeSweep &sweep, const int gi)
{
  switch (g.type)
  {
  case ElementType::Line2:
    return launchGroup<ElementType::Line2, false>(g, ctl, s, nodes, el, materials, corners, sweep, gi);
  case ElementType::Quad4:
    return launchGroup<ElementType::Quad4, Axi>(g, ctl, s, nodes, el, materials, corners, sweep, gi);
  case ElementType::Hex8:
    return launchGroup<ElementType::Hex8, false>(g, ctl, s, nodes, el, materials, corners, sweep, gi);
  case ElementType::Tet4:
    return launchGroup<ElementType::Tet4, false>(g, ctl, s, nodes, el, materials, corners, sweep, gi);
  }
  return 0;
}

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
        const Real c = kmath::sqrt((m.bulk + 4.0 / 3.0 * m.shear) / m.density);
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

Real computeElementForces(const std::vector<ElementGroup> &groups, const ElementControls &ctl,
                          const NodeFields &nodes, const ElementFields &elems,
                          const DeviceView<MaterialParams *> &materials, const NodeCorners &corners,
                          const NodeSweep &sweep)
{
  const Scatter s = ctl.gather                       ? Scatter::Corners
                    : ExecSpace().concurrency() == 1 ? Scatter::Plain
                                                     : Scatter::Atomic;
  Real dt_min = Kokkos::reduction_identity<Real>::min();
  for (size_t gi = 0; gi < groups.size(); ++gi)
  {
    const ElementGroup &g = groups[gi];
    const Real d =
        ctl.geometry == Geometry2D::Axisymmetric
            ? launchAny<true>(g, ctl, s, nodes, elems, materials, corners, sweep, int(gi))
            : launchAny<false>(g, ctl, s, nodes, elems, materials, corners, sweep, int(gi));
    dt_min = d < dt_min ? d : dt_min;
  }
  return dt_min;
}

namespace
{

/// The chunk (group-major over all groups' chunks) of each node's elements: -1 if none, -2 once
/// two chunks touch it; and, in `last`, the last element (in the chunk's order) touching it.
template <class Conn>
std::vector<int> nodeChunks(const Conn &conn, const std::vector<ElementGroup> &groups,
                            Index num_nodes, int chunks, std::vector<Index> *last = nullptr)
{
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

} // namespace

NodeCorners makeNodeCorners(const ElementFields &elems, const std::vector<ElementGroup> &groups,
                            Index num_nodes, int chunks)
{
  auto conn = Kokkos::create_mirror_view_and_copy(HostSpace(), elems.conn);
  const std::vector<int> chunk_of = nodeChunks(conn, groups, num_nodes, chunks);
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

namespace
{

/// Adds node n to `runs` ([begin, end) pairs, flat): it extends the last run if that run is
/// one of those from `first_run` on, ends at n and is shorter than max_length; else a new run.
void addToRuns(std::vector<Index> &runs, size_t first_run, Index n, Index max_length)
{
  if (runs.size() / 2 > first_run && runs.back() == n && runs.back() - runs.end()[-2] < max_length)
    ++runs.back();
  else
    runs.insert(runs.end(), {n, n + 1});
}

DeviceView<Index * [2]> toDevicePairs(const std::vector<Index> &flat, const std::string &label)
{
  DeviceView<Index * [2]> v(label, flat.size() / 2);
  auto h = Kokkos::create_mirror_view(v);
  for (size_t i = 0; i < flat.size() / 2; ++i)
    for (int k = 0; k < 2; ++k)
      h(i, k) = flat[2 * i + size_t(k)];
  Kokkos::deep_copy(v, h);
  return v;
}

} // namespace

NodeSweep makeNodeSweep(const ElementFields &elems, const std::vector<ElementGroup> &groups,
                        const NodeFields &nodes, int chunks, std::vector<char> late)
{
  const Index num_nodes = nodes.count;
  auto bc = Kokkos::create_mirror_view_and_copy(HostSpace(), nodes.bc);
  for (Index n = 0; n < num_nodes; ++n) // step 12 imposes them, at values set in step 12
    for (int i = 0; i < 3; ++i)
      late[size_t(n)] = char(late[size_t(n)] | (bc(n, i) >= 0));
  auto conn = Kokkos::create_mirror_view_and_copy(HostSpace(), elems.conn);
  std::vector<Index> last;
  const std::vector<int> chunk_of = nodeChunks(conn, groups, num_nodes, chunks, &last);
  constexpr Index B = NodeSweep::kSweepBlock;
  // blocks of B elements from each chunk's start, group-major; the block of element e
  std::vector<Index> base, block_of(static_cast<size_t>(elems.count), -1);
  Index blocks = 0;
  for (const auto &g : groups)
    for (int c = 0; c < chunks; ++c)
    {
      base.push_back(blocks);
      const Index begin = chunkBegin(g, chunks, c), end = chunkBegin(g, chunks, c + 1);
      for (Index e = begin; e < end; ++e)
        block_of[size_t(e)] = blocks + (e - begin) / B;
      blocks += (end - begin + B - 1) / B;
    }
  // each block's early nodes in ascending runs; the late ones in runs of at most 256
  std::vector<std::vector<Index>> early(static_cast<size_t>(blocks));
  std::vector<Index> late_runs, runs, offsets{0};
  Index early_nodes = 0;
  for (Index n = 0; n < num_nodes; ++n)
    if (chunk_of[size_t(n)] >= 0 && !late[size_t(n)])
      early[size_t(block_of[size_t(last[size_t(n)])])].push_back(n);
    else
      addToRuns(late_runs, 0, n, 256);
  for (const auto &block_nodes : early)
  {
    for (const Index n : block_nodes)
      addToRuns(runs, size_t(offsets.back()), n, num_nodes);
    early_nodes += Index(block_nodes.size());
    offsets.push_back(Index(runs.size() / 2));
  }
  NodeSweep sweep;
  sweep.active = true;
  sweep.chunks = chunks;
  sweep.early_nodes = early_nodes;
  sweep.block_base = toDevice(base, "sweep_block_base");
  sweep.block_runs = toDevice(offsets, "sweep_block_runs");
  sweep.runs = toDevicePairs(runs, "sweep_runs");
  sweep.block_sums = DeviceView<NodeSums *>("sweep_block_sums", size_t(blocks));
  sweep.late_runs = toDevicePairs(late_runs, "late_runs");
  return sweep;
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
