// Step 6b: the elements step 6 eroded (ElementKernel::finish flags them after their material
// update) are booked and announced (docs/theory.md 11.6).
#include "driver/Solver.hpp"

#include "contact/ContactSystem.hpp"
#include "core/HostCopy.hpp"
#include "parallel/Mpi.hpp"

#include <algorithm>
#include <iostream>
#include <utility>

namespace scpdyn
{

void Solver::stepErodeElements()
{
  ScopedStep t(_timers, "06b_erode_elements");
  auto eroded = _m.elems.eroded;
  Index local = 0;
  Kokkos::parallel_reduce(
      "erosionCount", Kokkos::RangePolicy<ExecSpace>(0, _m.elems.count),
      KOKKOS_LAMBDA(const Index e, Index &n) { n += eroded(e) == kErodingNow ? 1 : 0; }, local);
  const MPI_Comm comm = _m.dd ? _m.comm : MPI_COMM_NULL;
  long long total = local;
  if (comm != MPI_COMM_NULL)
    total = allReduceSum(static_cast<long long>(local), comm);
  if (total == 0)
    return;
  // this rank's new ones: (global id, internal + hourglass energy of their last state)
  std::vector<std::pair<Index, Real>> mine;
  if (local > 0)
  {
    auto h_eroded = Kokkos::create_mirror_view_and_copy(HostSpace(), eroded);
    auto mass = Kokkos::create_mirror_view_and_copy(HostSpace(), _m.elems.mass);
    auto energy = Kokkos::create_mirror_view_and_copy(HostSpace(), _m.elems.energy);
    auto hg = Kokkos::create_mirror_view_and_copy(HostSpace(), _m.elems.hourglass_energy);
    for (Index e = 0; e < _m.elems.count; ++e)
      if (h_eroded(e) == kErodingNow)
      {
        mine.emplace_back(globalElement(meshElementOfDevice(e)), mass(e) * energy(e) + hg(e));
        h_eroded(e) = 1;
      }
    Kokkos::deep_copy(eroded, h_eroded);
  }
  // every rank: all of them, by global id, so the sum and the list do not depend on the ranks
  std::vector<Index> ids;
  std::vector<Real> held;
  for (const auto &p : mine)
  {
    ids.push_back(p.first);
    held.push_back(p.second);
  }
  if (comm != MPI_COMM_NULL)
  {
    const int ranks = mpiSize(comm);
    const size_t ranks_n = static_cast<size_t>(ranks);
    std::vector<int> counts(ranks_n), offsets(ranks_n + 1, 0);
    const int n = int(ids.size());
    MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
    for (int r = 0; r < ranks; ++r)
      offsets[size_t(r) + 1] = offsets[size_t(r)] + counts[size_t(r)];
    std::vector<Index> all_ids(size_t(offsets.back()));
    std::vector<Real> all_held(size_t(offsets.back()));
    MPI_Allgatherv(ids.data(), n, MPI_INT, all_ids.data(), counts.data(), offsets.data(), MPI_INT,
                   comm);
    MPI_Allgatherv(held.data(), n, MPI_DOUBLE, all_held.data(), counts.data(), offsets.data(),
                   MPI_DOUBLE, comm);
    ids = std::move(all_ids);
    held = std::move(all_held);
  }
  std::vector<size_t> order(ids.size());
  for (size_t k = 0; k < order.size(); ++k)
    order[k] = k;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return ids[a] < ids[b]; });
  std::vector<Index> sorted(ids.size());
  for (size_t k = 0; k < order.size(); ++k)
  {
    sorted[k] = ids[order[k]];
    _eroded_energy += held[order[k]];
  }
  _eroded_elements += long(sorted.size());
  if (_m.contact)
    _m.contact->elementsEroded(sorted);
  if (_eroded_elements == globalElementCount())
  {
    _all_eroded = true;
    if (_m.rank == 0)
      std::cout << "every element is eroded at cycle " << _cycle << ", time " << _time
                << " s: the run ends\n";
  }
}

} // namespace scpdyn
