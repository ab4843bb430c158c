// Step 12 inside step 6: the sweep's blocks and runs of early nodes, and step 6 with the sweep
// as its after-block hook.
#include "integrate/NodeSweep.hpp"

#include "core/HostCopy.hpp"
#include "element/ElementLaunch.hpp"

namespace scpdyn
{

ElementStepResult computeElementForces(const std::vector<ElementGroup> &groups,
                                       const ElementControls &ctl, const NodeFields &nodes,
                                       const ElementFields &elems,
                                       const DeviceView<MaterialParams *> &materials,
                                       const NodeCorners &corners, const NodeSweep &sweep)
{
  return computeElementForcesWith(groups, ctl, nodes, elems, materials, corners, sweep);
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

DeviceView<Index *[2]> toDevicePairs(const std::vector<Index> &flat, const std::string &label) {
  DeviceView<Index *[2]> v(label, flat.size() / 2);
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
  std::vector<Index> last;
  const std::vector<int> chunk_of = nodeChunks(elems, groups, num_nodes, chunks, &last);
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

} // namespace scpdyn
