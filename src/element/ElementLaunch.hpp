#pragma once
/// \file ElementLaunch.hpp
/// \brief The launches of step 6 for any after-block hook: computeElementForcesWith() runs the
/// element kernel (ElementKernel.hpp) over every group and, when the hook is active, calls it
/// after each block of kElementBlock elements of a thread's chunk. The element room knows
/// nothing of what the hook does; step 12 of the nodes that nothing after step 6 touches is one
/// such hook (integrate/NodeSweep.hpp). Included by the files that instantiate it (with
/// -ffp-contract=fast, so every instantiation contracts the kernel alike).
///
/// A hook is a device-copyable type with
/// - `active` (bool; a hook that is never active may make it `static constexpr`),
/// - `chunks` (int): how many chunks each group is cut into when active,
/// - `Index firstBlock(int group_chunk)`: the hook's number of the first block of chunk c of
///   group g, at group_chunk = g * chunks + c; a chunk's blocks are numbered consecutively,
/// - `template <int Dim> void afterBlock(Index block, bool failed)`: called once per block, in
///   order within a chunk, after the block's last element; `failed` when an element of the
///   chunk failed (the run stops after this step).
#include "element/ElementForces.hpp"
#include "element/ElementKernel.hpp"

namespace scpdyn
{

/// \brief The hook of a step 6 that does nothing after its blocks.
struct NoAfterBlock
{
  static constexpr bool active = false;
  int chunks = 1;
  KOKKOS_INLINE_FUNCTION Index firstBlock(int) const { return 0; }
  template <int Dim>
  KOKKOS_INLINE_FUNCTION void afterBlock(Index, bool) const
  {
  }
};

namespace element_launch
{

// Kernel labels stay within std::string's 15-character small-string buffer: Kokkos turns
// each label into a std::string per launch, and a longer one is a heap allocation per cycle.

using element_kernel::ElementKernel;
using element_kernel::Scatter;

/// Kernel k over group g; corner_chunks: NodeCorners::chunks.
template <ElementType T, bool Axi, bool Erosion, class AfterBlock>
Real launchKernel(const ElementGroup &g, const ElementKernel<T, Axi, Erosion> &k,
                  const int corner_chunks, const AfterBlock &after, const int group_index)
{
  Real dt_min = 0;
  // one chunk a thread, its packs or elements in order; with an active hook, after each block
  // of them, the hook
  if (after.active || k.scatter == Scatter::Corners)
  {
    const ElementGroup grp = g;
    const int chunks = after.active ? after.chunks : corner_chunks;
    constexpr Index B = kElementBlock;
    Kokkos::parallel_reduce(
        "elementChunks", Kokkos::RangePolicy<ExecSpace>(0, chunks),
        KOKKOS_LAMBDA(const int c, Real &local_min) {
          const Index begin = chunkBegin(grp, chunks, c), end = chunkBegin(grp, chunks, c + 1);
          if (!after.active)
          {
            k.range(begin, end, local_min);
            return;
          }
          Index b = after.firstBlock(group_index * chunks + c);
          for (Index first = begin; first < end; first += B, ++b)
          {
            k.range(first, end - first < B ? end : first + B, local_min);
            after.template afterBlock<ElementTraits<T>::dim>(b, local_min < 0);
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

/// Group g with the kernel of its elements' type, with or without erosion's tests as the deck
/// needs them (ElementKernel's Erosion).
template <ElementType T, bool Axi, class AfterBlock>
Real launchGroup(const ElementGroup &g, const ElementControls &ctl, Scatter scatter,
                 const NodeFields &nodes, const ElementFields &el,
                 const DeviceView<MaterialParams *> &materials, const NodeCorners &corners,
                 const AfterBlock &after, const int group_index)
{
  using element_kernel::makeElementKernel;
  if (ctl.erosion)
    return launchKernel(
        g, makeElementKernel<T, Axi, true>(ctl, scatter, nodes, el, materials, corners),
        corners.chunks, after, group_index);
  return launchKernel(g,
                      makeElementKernel<T, Axi, false>(ctl, scatter, nodes, el, materials, corners),
                      corners.chunks, after, group_index);
}

template <bool Axi, class AfterBlock>
Real launchAny(const ElementGroup &g, const ElementControls &ctl, Scatter s,
               const NodeFields &nodes, const ElementFields &el,
               const DeviceView<MaterialParams *> &materials, const NodeCorners &corners,
               const AfterBlock &after, const int gi)
{
  switch (g.type)
  {
  case ElementType::Line2:
    return launchGroup<ElementType::Line2, false>(g, ctl, s, nodes, el, materials, corners, after,
                                                  gi);
  case ElementType::Quad4:
    return launchGroup<ElementType::Quad4, Axi>(g, ctl, s, nodes, el, materials, corners, after,
                                                gi);
  case ElementType::Hex8:
    return launchGroup<ElementType::Hex8, false>(g, ctl, s, nodes, el, materials, corners, after,
                                                 gi);
  case ElementType::Tet4:
    return launchGroup<ElementType::Tet4, false>(g, ctl, s, nodes, el, materials, corners, after,
                                                 gi);
  }
  return 0;
}

/// The kernels' smallest h / c, or -(e + 1) for an inverted element e (NaN: not finite), as
/// the result the rest of the code reads.
inline ElementStepResult stepResult(const Real dt_min)
{
  ElementStepResult r;
  r.dt = dt_min;
  if (std::isnan(dt_min) || (!(dt_min > 0) && dt_min > -1))
    r.finite = false;
  else if (!(dt_min > 0))
    r.inverted = Index(-dt_min) - 1;
  return r;
}

} // namespace element_launch

/// \brief computeElementForces() with an after-block hook (see the file comment).
template <class AfterBlock>
ElementStepResult computeElementForcesWith(const std::vector<ElementGroup> &groups,
                                           const ElementControls &ctl, const NodeFields &nodes,
                                           const ElementFields &elems,
                                           const DeviceView<MaterialParams *> &materials,
                                           const NodeCorners &corners, const AfterBlock &after)
{
  using element_launch::Scatter;
  const Scatter s = ctl.gather                       ? Scatter::Corners
                    : ExecSpace().concurrency() == 1 ? Scatter::Plain
                                                     : Scatter::Atomic;
  Real dt_min = Kokkos::reduction_identity<Real>::min();
  for (size_t gi = 0; gi < groups.size(); ++gi)
  {
    const ElementGroup &g = groups[gi];
    const Real d = ctl.geometry == Geometry2D::Axisymmetric
                       ? element_launch::launchAny<true>(g, ctl, s, nodes, elems, materials,
                                                         corners, after, int(gi))
                       : element_launch::launchAny<false>(g, ctl, s, nodes, elems, materials,
                                                          corners, after, int(gi));
    dt_min = d < dt_min ? d : dt_min;
  }
  return element_launch::stepResult(dt_min);
}

} // namespace scpdyn
