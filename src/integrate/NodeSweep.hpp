#pragma once
/// \file NodeSweep.hpp
/// \brief Step 12 inside step 6: the nodes that nothing after the element step touches are
/// integrated in the element sweep, right after their last element, while their x, v and
/// f_int are still in cache, which saves step 12 reading them again from memory
/// (the whole cycle 0.89-0.94 of a separate step 12: perf/results/log.md).
#include "element/ElementForces.hpp"
#include "element/Lanes.hpp"
#include "integrate/NodeIntegrator.hpp"

namespace scpdyn
{

#ifdef SCPDYN_ELEMENT_LANES
/// \brief NodeIntegrator::run<3, Loads, true> for free nodes (no velocity constraint, counted
/// in the sums): kElementLanes nodes at a time as three LanePacks of their interleaved
/// components (x y z x y z ...), the same arithmetic per component as integrate(), so x and v
/// get its bits; the sums are added lane-wise, then to `sums` in a fixed order.
template <bool Loads>
inline void runFreeNodes(const NodeIntegrator &k, const Index begin, const Index end,
                         NodeSums &sums)
{
  static_assert(std::is_same<VectorView::array_layout, Kokkos::LayoutRight>::value,
                "node n's components are at data() + 3 n");
  constexpr int W = kElementLanes;
  const Index packs = (end - begin) / W;
  LanePack kinetic = {}, kinetic_mid = {}, work = {}, momentum[3] = {};
  LanePack g[3];
  for (int p = 0; p < 3; ++p)
    for (int l = 0; l < W; ++l)
      g[p][l] = k.g[(p * W + l) % 3];
  for (Index q = 0; q < packs; ++q)
  {
    const Index n0 = begin + q * W;
    Real *x = &k.x(n0, 0), *v = &k.v(n0, 0), *fi = &k.f_int(n0, 0);
    Real *fe = Loads ? &k.f_ext(n0, 0) : nullptr, *imp = Loads ? &k.prev_impulse(n0, 0) : nullptr;
    Real dt_over_m[W], mass[W];
    for (int l = 0; l < W; ++l)
    {
      mass[l] = k.mass(n0 + l);
      dt_over_m[l] = k.dt / mass[l];
    }
    for (int p = 0; p < 3; ++p)
    {
      LanePack m, dm;
      for (int l = 0; l < W; ++l)
      {
        m[l] = mass[(p * W + l) / 3];
        dm[l] = dt_over_m[(p * W + l) / 3];
      }
      const LanePack v_old = loadPack(v + p * W);
      const LanePack f_e = Loads ? loadPack(fe + p * W) : LanePack{};
      const LanePack f = Loads ? loadPack(fi + p * W) + f_e : loadPack(fi + p * W);
      const LanePack v_new = v_old + f * dm;
      if (Loads)
      {
        const LanePack impulse = f_e * k.dt;
        work += 0.5 * v_old * (impulse + loadPack(imp + p * W));
        storePack(imp + p * W, impulse);
        storePack(fe + p * W, m * g[p]);
      }
      kinetic += 0.5 * m * v_new * v_new;
      kinetic_mid += 0.5 * m * v_old * v_new;
      momentum[p] += m * v_new;
      storePack(x + p * W, loadPack(x + p * W) + k.half_dt * (v_old + v_new));
      storePack(v + p * W, v_new);
      storePack(fi + p * W, LanePack{});
    }
  }
  for (int l = 0; l < W; ++l)
  {
    sums.external_work += work[l];
    sums.kinetic += kinetic[l];
    sums.kinetic_mid += kinetic_mid[l];
  }
  for (int p = 0; p < 3; ++p)
    for (int l = 0; l < W; ++l)
      sums.momentum[(p * W + l) % 3] += momentum[p][l];
  k.run<3, Loads, true>(begin + packs * W, end, sums);
}
#endif

/// \brief Step 12 for the nodes that nothing after step 6 touches, done inside step 6's sweep
/// as its after-block hook (element/ElementLaunch.hpp): after each block of kElementBlock
/// elements of a chunk, the nodes whose last
/// element (in the sweep's order) lies in that block are integrated while their x, v and f_int
/// are still in cache, and step 12 itself runs over the other ("late") nodes only. A node is
/// late if two chunks or two element groups touch it, if it has a velocity constraint, if a
/// contact surface, a face pressure or a nodal force acts on it, or if it is shared between
/// ranks or not owned. Built by makeNodeSweep() (element/ElementForces.hpp).
struct NodeSweep
{
  static constexpr Index kSweepBlock = 64;
  bool active = false;
  int chunks = 1;
  bool loads = false;
  Index early_nodes = 0;             ///< nodes step 6 integrates
  IndexView block_base;              ///< per (group, chunk), group-major: its first block
  IndexView block_runs;              ///< blocks + 1: each block's first run in `runs`
  DeviceView<Index *[2]> runs;       ///< runs of consecutive early nodes [begin, end)
  DeviceView<NodeSums *> block_sums; ///< per block: the sums of its nodes (this cycle)
  DeviceView<Index *[2]> late_runs;  ///< runs of at most 256 late nodes, ascending
  NodeIntegrator node;

  /// The after-block hook: block b's number of the first block of a chunk.
  KOKKOS_INLINE_FUNCTION Index firstBlock(const int group_chunk) const
  {
    return block_base(group_chunk);
  }
  /// The after-block hook: step 12 on block b's early nodes, or, when an element of the chunk
  /// failed, none of them (the run stops after step 6 with the state it had).
  template <int Dim>
  KOKKOS_INLINE_FUNCTION void afterBlock(const Index b, const bool failed) const
  {
    if (failed)
      block_sums(b) = NodeSums();
    else
      integrateBlock<Dim>(b);
  }

  /// Step 12 (with step 5 after it) on the early nodes of block b, which has no later element.
  template <int Dim>
  KOKKOS_INLINE_FUNCTION void integrateBlock(const Index b) const
  {
    NodeSums s;
#ifdef SCPDYN_ELEMENT_LANES
    if constexpr (Dim == 3) // early nodes are free: no constraint, counted
    {
      for (Index r = block_runs(b); r < block_runs(b + 1); ++r)
        if (loads)
          runFreeNodes<true>(node, runs(r, 0), runs(r, 1), s);
        else
          runFreeNodes<false>(node, runs(r, 0), runs(r, 1), s);
      block_sums(b) = s;
      return;
    }
#endif
    for (Index r = block_runs(b); r < block_runs(b + 1); ++r)
      if (loads)
        node.run<Dim, true, true>(runs(r, 0), runs(r, 1), s);
      else
        node.run<Dim, false, true>(runs(r, 0), runs(r, 1), s);
    block_sums(b) = s;
  }
};

/// \brief The node sweep of step 6 (NodeSweep) for `chunks` chunks (1 with one thread; the
/// NodeCorners chunks with the corner gather). `late` (per node, nonzero) marks the nodes that
/// something after step 6 touches (LateNodes::mask()); a node with a velocity constraint, or
/// that two chunks or groups touch, is late too. The caller sets `loads` and the
/// NodeIntegrator each cycle.
NodeSweep makeNodeSweep(const ElementFields &elems, const std::vector<ElementGroup> &groups,
                        const NodeFields &nodes, int chunks, std::vector<char> late);

/// \brief Step 6 with step 12 of the early nodes in its sweep (computeElementForces() with the
/// sweep as after-block hook; an inactive sweep leaves step 12 to updateNodes()).
ElementStepResult computeElementForces(const std::vector<ElementGroup> &groups,
                                       const ElementControls &ctl, const NodeFields &nodes,
                                       const ElementFields &elems,
                                       const DeviceView<MaterialParams *> &materials,
                                       const NodeCorners &corners, const NodeSweep &sweep);

} // namespace scpdyn
