// The joint CPs' forces summed at the nodes in a fixed order (ContactSystem::_gather_forces):
// with threads the atomic adds of scatterForce() meet in any order and round differently from
// run to run; here every node adds its CPs' shares in ascending CP order, the order one thread
// adds them in, so a contact deck gives the same bits at any thread count (numerics.scatter
// gather, docs/input.md).
#include "contact/ContactSystem.hpp"
#include "contact/ContactKernels.hpp"

#include <vector>

namespace scpdyn
{

void ContactSystem::buildShareRows()
{
  using contact_kernels::shareSlot;
  auto face1 = Kokkos::create_mirror_view_and_copy(HostSpace(), _cp.face1);
  auto face2 = Kokkos::create_mirror_view_and_copy(HostSpace(), _cp.face2);
  auto nodes = Kokkos::create_mirror_view_and_copy(HostSpace(), _faces.nodes);
  auto num = Kokkos::create_mirror_view_and_copy(HostSpace(), _faces.num_nodes);
  auto ghost = Kokkos::create_mirror_view_and_copy(HostSpace(), _faces.ghost);
  auto used = Kokkos::create_mirror_view_and_copy(HostSpace(), _faces.nodes_used);
  std::vector<Index> row_of(_vstar.extent(0), -1);
  for (size_t i = 0; i < used.extent(0); ++i)
    row_of[size_t(used(i))] = Index(i);
  // every own face node's slot, CP by CP: appending in that order keeps each row ascending
  auto eachSlot = [&](auto &&visit) {
    for (Index p = 0; p < _cp.count; ++p)
      for (int side = 0; side < 2; ++side)
      {
        const Index f = side == 0 ? face1(p) : face2(p);
        if (ghost(f))
          continue;
        for (int a = 0; a < num(f); ++a)
          visit(row_of[size_t(nodes(f, a))], shareSlot(p, side, a));
      }
  };
  std::vector<Index> offsets(used.extent(0) + 1, 0);
  eachSlot([&](Index row, Index) { ++offsets[size_t(row) + 1]; });
  for (size_t i = 0; i < used.extent(0); ++i)
    offsets[i + 1] += offsets[i];
  std::vector<Index> slots(size_t(offsets.back())), fill(offsets.begin(), offsets.end() - 1);
  eachSlot([&](Index row, Index slot) { slots[size_t(fill[size_t(row)]++)] = slot; });
  _share_offsets = IndexView("contact_share_offsets", offsets.size());
  _share_slots = IndexView("contact_share_slots", slots.size());
  Kokkos::deep_copy(_share_offsets,
                    Kokkos::View<const Index *, HostSpace, Kokkos::MemoryTraits<Kokkos::Unmanaged>>(
                        offsets.data(), offsets.size()));
  Kokkos::deep_copy(_share_slots,
                    Kokkos::View<const Index *, HostSpace, Kokkos::MemoryTraits<Kokkos::Unmanaged>>(
                        slots.data(), slots.size()));
  if (_node_share.extent(0) < size_t(2 * kMaxFaceNodes) * size_t(_cp.count))
    _node_share = VectorView("contact_share", size_t(2 * kMaxFaceNodes) * size_t(_cp.count));
  _share_generation = _cp_generation;
}

void ContactSystem::assembleShares()
{
  auto used = _faces.nodes_used;
  auto offsets = _share_offsets, slots = _share_slots;
  auto share = _node_share, fc = _fc;
  Kokkos::parallel_for(
      "scpdyn::contact::assembleShares", Kokkos::RangePolicy<ExecSpace>(0, Index(used.extent(0))),
      KOKKOS_LAMBDA(const Index i) {
        const Index k = used(i);
        for (Index q = offsets(i); q < offsets(i + 1); ++q)
          for (int d = 0; d < 3; ++d)
            fc(k, d) += share(slots(q), d);
      });
}

} // namespace scpdyn
