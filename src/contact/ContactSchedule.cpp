// When the contact searches and how far it looks (docs/theory.md 3.1a).
#include "contact/ContactSystem.hpp"

namespace scpdyn
{

namespace
{

/// A gap of `search_gap: motion` is never below this fraction of the largest face, so a wall
/// at rest still pairs faces that round-off or a settling step brings within reach.
constexpr Real kMotionGapFloor = 0.01;
/// A search falls due once a contact node may have moved this share of the gap: two faces that
/// approach each other then close at most half of it, the other half left for speed that grows
/// within a step.
constexpr Real kTriggerShare = 0.25;
/// The gap is this many times the contact nodes' motion over one search interval (a node moves
/// at most 2 |v| dt between two half-step positions), so that for steady motion the trigger
/// falls due at the interval's end; at rest it never does.
constexpr Real kGapPerIntervalMotion = 1 / kTriggerShare;

} // namespace

bool ContactSystem::searchScheduled(long cycle) const
{
  return cycle == 0 || (_search_interval > 0 && cycle % _search_interval == 0);
}

bool ContactSystem::searchDue(long cycle) const
{
  if (_gap_from_motion && cycle == _planned_cycle)
    return _planned_due;
  return searchScheduled(cycle);
}

Real ContactSystem::searchGap(Real face_size) const
{
  if (_gap_from_motion)
    return std::max(_motion_gap, kMotionGapFloor * face_size);
  return _search_gap > 0 ? _search_gap : face_size;
}

void ContactSystem::planSearch(const NodeFields &nodes, Real dt, long cycle)
{
  if (!_gap_from_motion || cycle == _planned_cycle)
    return;
  // the nodes of this rank's own faces: decomposed, a ghost node's velocity is a step old and
  // a shared node on no contact face is in the node arrays too; over the ranks, the nodes of
  // every face, as in one rank
  const ContactFaceData F = _faces;
  auto v = nodes.v;
  Real v2 = 0;
  Kokkos::parallel_reduce(
      "scpdyn::contact::fastestNode", Kokkos::RangePolicy<ExecSpace>(0, F.count),
      KOKKOS_LAMBDA(const Index f, Real &m) {
        if (F.ghost(f))
          return;
        for (int k = 0; k < F.num_nodes(f); ++k)
        {
          const Index a = F.nodes(f, k);
          const Real s = v(a, 0) * v(a, 0) + v(a, 1) * v(a, 1) + v(a, 2) * v(a, 2);
          m = s > m ? s : m;
        }
      },
      Kokkos::Max<Real>(v2));
  Real speed = std::sqrt(v2);
  if (_comm.max) // every rank decides alike
    speed = _comm.max(speed);
  // x^{n+1/2} - x^{n-1/2} = dt (3 v^{n+1/2} - v^{n-1/2}) / 2 for a constant dt: at most 2 |v| dt
  const Real step = 2 * speed * dt;
  if (cycle > 0)
    _motion += step;
  // the bound after the next step, against the share of the gap the trigger allows. Nothing
  // else can bring a rejected pair within reach, so the interval's own searches would find
  // nothing new: only cycle 0, faces that erosion exposed (the same list on every rank) and
  // the motion bring a search
  const bool due = cycle == 0 || !_eroded_pending.empty() ||
                   _motion + step >= kTriggerShare * searchGap(_geom.h_max);
  if (due)
  {
    _motion = 0;
    _motion_gap = kGapPerIntervalMotion * step * Real(std::max(_search_interval, 1L) + 1);
  }
  _planned_cycle = cycle;
  _planned_due = due;
}

} // namespace scpdyn
