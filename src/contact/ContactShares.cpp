// The contact forces summed at the nodes in a fixed order (ContactSystem::_gather_forces):
// with threads the atomic adds of scatterForce() and rowScatter() meet in any order and round
// differently from run to run; here every CP (the joints) or tie row (the velocity
// constraints) writes its nodes' shares into its slots, and every node adds its slots in
// ascending CP or row order, the order one thread adds them in, so a contact deck gives the
// same bits at any thread count (numerics.scatter gather, docs/input.md).
#include "contact/ContactSystem.hpp"
#include "contact/ContactKernels.hpp"

#include <algorithm>
#include <vector>

namespace scpdyn
{

void ContactSystem::buildSlotRows(int per_cp, NodeSlotRows &rows)
{
  using contact_kernels::shareSlot;
  auto face1 = Kokkos::create_mirror_view_and_copy(HostSpace(), _cp.face1);
  auto face2 = Kokkos::create_mirror_view_and_copy(HostSpace(), _cp.face2);
  auto key1 = Kokkos::create_mirror_view_and_copy(HostSpace(), _cp.key1);
  auto key2 = Kokkos::create_mirror_view_and_copy(HostSpace(), _cp.key2);
  auto nodes = Kokkos::create_mirror_view_and_copy(HostSpace(), _faces.nodes);
  auto num = Kokkos::create_mirror_view_and_copy(HostSpace(), _faces.num_nodes);
  auto ghost = Kokkos::create_mirror_view_and_copy(HostSpace(), _faces.ghost);
  auto used = Kokkos::create_mirror_view_and_copy(HostSpace(), _faces.nodes_used);
  std::vector<Index> row_of(_vstar.extent(0), -1);
  for (size_t i = 0; i < used.extent(0); ++i)
    row_of[size_t(used(i))] = Index(i);
  // decomposed: a node other ranks hold sums over the ranks, its terms keyed by the serial
  // order of the slots (CP by face keys, then entry, then side)
  const bool across = bool(_comm.ordered_plan);
  const std::vector<Index> &shared_index = _comm.shared_index;
  std::vector<std::vector<NodeTerm>> terms;
  Index num_shared = 0;
  for (Index s : shared_index)
    num_shared = s >= 0 ? std::max(num_shared, s + 1) : num_shared;
  if (across)
    terms.resize(size_t(num_shared));
  auto sharedOf = [&](Index k) {
    return across && size_t(k) < shared_index.size() ? shared_index[size_t(k)] : Index(-1);
  };
  // every own face node's slot, entry by entry (CP, or tie row c = p per_cp + q): appending in
  // that order keeps each node's list ascending
  auto eachSlot = [&](auto &&visit) {
    for (Index p = 0; p < _cp.count; ++p)
      for (Index c = p * per_cp; c < (p + 1) * per_cp; ++c)
        for (int side = 0; side < 2; ++side)
        {
          const Index f = side == 0 ? face1(p) : face2(p);
          if (ghost(f))
            continue;
          for (int a = 0; a < num(f); ++a)
            visit(nodes(f, a), shareSlot(c, side, a), p, c - p * per_cp, side);
        }
  };
  std::vector<Index> offsets(used.extent(0) + 1, 0);
  eachSlot([&](Index k, Index, Index, Index, int) {
    if (sharedOf(k) < 0)
      ++offsets[size_t(row_of[size_t(k)]) + 1];
  });
  for (size_t i = 0; i < used.extent(0); ++i)
    offsets[i + 1] += offsets[i];
  std::vector<Index> slots(size_t(offsets.back())), fill(offsets.begin(), offsets.end() - 1);
  eachSlot([&](Index k, Index slot, Index p, Index q, int side) {
    const Index s = sharedOf(k);
    if (s < 0)
      slots[size_t(fill[size_t(row_of[size_t(k)])]++)] = slot;
    else
      terms[size_t(s)].push_back(
          {TermKey{std::int64_t(key1(p)), std::int64_t(key2(p)), std::int64_t(2 * q + side)},
           slot});
  });
  rows.offsets = IndexView("contact_slot_offsets", offsets.size());
  rows.slots = IndexView("contact_slots", slots.size());
  Kokkos::deep_copy(rows.offsets,
                    Kokkos::View<const Index *, HostSpace, Kokkos::MemoryTraits<Kokkos::Unmanaged>>(
                        offsets.data(), offsets.size()));
  Kokkos::deep_copy(rows.slots,
                    Kokkos::View<const Index *, HostSpace, Kokkos::MemoryTraits<Kokkos::Unmanaged>>(
                        slots.data(), slots.size()));
  const size_t n = size_t(2 * kMaxFaceNodes) * size_t(_cp.count) * size_t(per_cp);
  if (rows.share.extent(0) < n)
    rows.share = VectorView("contact_share", n);
  rows.across = across ? _comm.ordered_plan(terms) : nullptr;
  rows.generation = _cp_generation;
}

void ContactSystem::assembleSlots(const NodeSlotRows &rows, const VectorView &out, bool from_zero)
{
  auto used = _faces.nodes_used;
  auto offsets = rows.offsets, slots = rows.slots;
  auto share = rows.share;
  Kokkos::parallel_for(
      "scpdyn::contact::assembleSlots", Kokkos::RangePolicy<ExecSpace>(0, Index(used.extent(0))),
      KOKKOS_LAMBDA(const Index i) {
        const Index k = used(i);
        for (int d = 0; d < 3; ++d)
        {
          Real s = from_zero ? 0.0 : out(k, d);
          for (Index q = offsets(i); q < offsets(i + 1); ++q)
            s += share(slots(q), d);
          out(k, d) = s;
        }
      });
  if (rows.across) // the shared nodes (empty ranges above, so `out` still holds their start)
    rows.across->sum(share, out, from_zero);
}

void ContactSystem::sumOverRanks(const NodeSlotRows *rows, const VectorView &f) const
{
  if (rows && rows->across)
    _comm.gather_ghosts(f);
  else if (_comm.sum_nodes)
    _comm.sum_nodes(f);
}

const ContactSystem::NodeSlotRows *ContactSystem::slotRows(int per_cp, NodeSlotRows &rows)
{
  if (!_gather_forces)
    return nullptr;
  if (rows.generation != _cp_generation)
    buildSlotRows(per_cp, rows);
  return &rows;
}

} // namespace scpdyn
