// The switch of sleepy CPs (docs/theory.md 11.4): tied while the elements behind their faces are
// intact, a slide line (with the slide lines' Coulomb friction) once the deck's failure measure
// of either element, or of both, reaches its threshold, or at a prescribed time. Irreversible:
// the flag is CP history and follows the face pair through later searches (3.3).
//
// The measures are face data: this rank's faces read their elements every cycle before step 9;
// a ghost face gets its owner's values in step 8, so every rank that computes a CP switches it
// in the same cycle.
#include "contact/ContactSystem.hpp"
#include "contact/ContactKernels.hpp"
#include "contact/JointConstraints.hpp"
#include "core/HostCopy.hpp"

namespace scpdyn
{
namespace
{

/// The failure measures of element e (FailureMeasure::PlasticStrain - 1, Damage - 1).
KOKKOS_INLINE_FUNCTION Real elementMeasure(const ElementFields &E, const IndexView &damage_slot,
                                           Index e, int column)
{
  if (column == 0)
    return E.plastic_strain(e);
  const Index slot = damage_slot(E.material(e));
  return slot >= 0 ? E.history(e, slot) : 0.0;
}

} // namespace

void ContactSystem::updateFailureMeasures(const ElementFields &elements)
{
  if (!_failure_from_elements)
    return;
  const ContactFaceData F = _faces;
  const IndexView slot = _damage_slot;
  Kokkos::parallel_for(
      "scpdyn::contact::faceFailure", Kokkos::RangePolicy<ExecSpace>(0, F.count),
      KOKKOS_LAMBDA(const Index f) {
        const Index e = F.element(f);
        if (e < 0)
          return; // a ghost face: its owner's values arrive in step 8
        for (int c = 0; c < 2; ++c)
          F.failure(f, c) = elementMeasure(elements, slot, e, c);
      });
}

std::vector<Real> ContactSystem::ownFaceFailure(const ElementFields &elements, int column) const
{
  RealView m("contact_own_failure", size_t(_own.count));
  auto element = _own.element;
  const IndexView slot = _damage_slot;
  Kokkos::parallel_for(
      "scpdyn::contact::ownFailure", Kokkos::RangePolicy<ExecSpace>(0, _own.count),
      KOKKOS_LAMBDA(const Index f) { m(f) = elementMeasure(elements, slot, element(f), column); });
  auto h = Kokkos::create_mirror_view_and_copy(HostSpace(), m);
  return std::vector<Real>(h.data(), h.data() + _own.count);
}

void ContactSystem::setGhostFailure(int column, const std::vector<Real> &measure)
{
  auto h = Kokkos::create_mirror_view_and_copy(HostSpace(), _faces.failure);
  eachGhostFace([&](Index f, size_t g) { h(f, column) = measure[g]; });
  Kokkos::deep_copy(_faces.failure, h);
}

void ContactSystem::releaseSleepy(Real time)
{
  const ContactFaceData F = _faces;
  const CommonPlaneData cp = _cp;
  Kokkos::parallel_for(
      "scpdyn::contact::sleepySwitch", Kokkos::RangePolicy<ExecSpace>(0, cp.count),
      KOKKOS_LAMBDA(const Index p) {
        const JointParams &P = cp.params(p);
        if (P.option != ContactOption::Sleepy || cp.state(p).failed)
          return;
        const int c = P.failure_measure == FailureMeasure::Damage ? 1 : 0;
        if (sleepyFails(P, F.failure(cp.face1(p), c), F.failure(cp.face2(p), c), time))
          cp.state(p).failed = 1;
      });
}

Index ContactSystem::failedCount() const
{
  const ContactFaceData F = _faces;
  const CommonPlaneData cp = _cp;
  Index n = 0;
  Kokkos::parallel_reduce(
      "scpdyn::contact::failedCount", Kokkos::RangePolicy<ExecSpace>(0, cp.count),
      KOKKOS_LAMBDA(const Index p, Index &count) {
        const bool failed = cp.params(p).option == ContactOption::Sleepy && cp.state(p).failed;
        count += failed && contact_kernels::ownsPlane(F, cp, p) ? 1 : 0;
      },
      n);
  return Index(globalSum(Real(n)));
}

} // namespace scpdyn
