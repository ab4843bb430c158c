#pragma once
/// \file ContactKernels.hpp
/// \brief Internal to the contact room: small device functions shared by the force kernels
/// (ContactForces.cpp) and the constraint solvers (ContactConstraints.cpp).
#include "contact/ContactData.hpp"
#include "contact/JointLaw.hpp"

namespace scpdyn
{
namespace contact_kernels
{

KOKKOS_INLINE_FUNCTION void faceVelocity(const ContactFaceData &F, Index f, const VectorView &v,
                                         Real V[3])
{
  const int nn = F.num_nodes(f);
  V[0] = V[1] = V[2] = 0;
  for (int a = 0; a < nn; ++a)
    for (int d = 0; d < 3; ++d)
      V[d] += v(F.nodes(f, a), d);
  for (int d = 0; d < 3; ++d)
    V[d] /= nn;
}

KOKKOS_INLINE_FUNCTION bool isConstraint(ContactOption o)
{
  return o == ContactOption::SlideLine || o == ContactOption::Sticky || o == ContactOption::Sleepy;
}

/// The option that stops impacts between faces at an angle takes the normal of an edge or
/// corner contact (docs/theory.md 4.2); the joint options and the ties keep the bisector (D1),
/// which is what a joint between near-parallel faces needs.
KOKKOS_INLINE_FUNCTION bool usesImpactNormal(ContactOption o)
{
  return o == ContactOption::SlideLine;
}

/// Velocity of face f weighted by row `row` of `w` (a View (row, face node)).
template <class Weights>
KOKKOS_INLINE_FUNCTION void faceVelocityWith(const ContactFaceData &F, Index f, const Weights &w,
                                             Index row, const VectorView &v, Real V[3])
{
  V[0] = V[1] = V[2] = 0;
  for (int a = 0; a < F.num_nodes(f); ++a)
    for (int d = 0; d < 3; ++d)
      V[d] += w(row, a) * v(F.nodes(f, a), d);
}

/// Velocity of face `side` (0: face 1, 1: face 2) of CP p: the nodal velocities weighted like
/// the CP force (17)-(18), so the power of the CP force is exactly -F.(V1 - V2).
KOKKOS_INLINE_FUNCTION void weightedVelocity(const ContactFaceData &F, const CommonPlaneData &cp,
                                             Index p, int side, const VectorView &v, Real V[3])
{
  if (side == 0)
    faceVelocityWith(F, cp.face1(p), cp.w1, p, v, V);
  else
    faceVelocityWith(F, cp.face2(p), cp.w2, p, v, V);
}

/// V1, V2 of CP p by the rule of its parameters.
KOKKOS_INLINE_FUNCTION void cpVelocities(const ContactFaceData &F, const CommonPlaneData &cp,
                                         Index p, VelocityRule rule, const VectorView &v,
                                         Real V1[3], Real V2[3])
{
  if (rule == VelocityRule::Weighted)
  {
    weightedVelocity(F, cp, p, 0, v, V1);
    weightedVelocity(F, cp, p, 1, v, V2);
  }
  else
  {
    faceVelocity(F, cp.face1(p), v, V1);
    faceVelocity(F, cp.face2(p), v, V2);
  }
}

/// \brief How the contact kernels add CP and tie-row shares into node arrays: atomic adds, or
/// plain adds when the execution space runs one thread (nodeAdder()).
///
/// The rule: one thread runs a RangePolicy in index order, one index after the other, so plain
/// adds form the same sums in the same order as the atomics, bit for bit (the element step's
/// rule for its scatter, element/ElementLaunch.hpp). With threads, or on a GPU, where two CPs of
/// one node run at once, the adds stay atomic. On one thread the atomics' locked
/// compare-exchange was a fifth of the CP update (perf/README.md). Guarded by
/// ContactScatter.* (tests/contact/test_contact_scatter.cpp).
struct NodeAdder
{
  bool plain = false;
  KOKKOS_INLINE_FUNCTION void operator()(Real *target, Real value) const
  {
    if (plain)
      *target += value;
    else
      Kokkos::atomic_add(target, value);
  }
};

/// The adder of this process's execution space: plain on one thread, atomic otherwise.
inline NodeAdder nodeAdder() { return NodeAdder{ExecSpace().concurrency() == 1}; }

/// The slot of face node `a` of side `side` (0: face 1, 1: face 2) of CP p in the CPs' nodal
/// shares (ContactSystem::_share_rows, the deterministic assembly of shareForce()).
KOKKOS_INLINE_FUNCTION Index shareSlot(Index p, int side, int a)
{
  return (2 * p + side) * kMaxFaceNodes + a;
}

/// Zero the slots of entries [begin, end) (CPs, or tie rows): an entry that returns before
/// writing its shares then gives its nodes nothing.
KOKKOS_INLINE_FUNCTION void clearShares(const VectorView &share, Index begin, Index end)
{
  for (Index q = shareSlot(begin, 0, 0); q < shareSlot(end, 0, 0); ++q)
    for (int d = 0; d < 3; ++d)
      share(q, d) = 0;
}

/// Calls visit(slot, node, w) for every node of CP p's own faces with its signed weight of the
/// CP force (17)-(18), -w1 on face 1 and +w2 on face 2, side by side and node by node (slot:
/// shareSlot()). A ghost face is skipped: its own rank computes the same CP and applies that
/// side (parallel rules of 2.2).
template <class Visit>
KOKKOS_INLINE_FUNCTION void forEachOwnNodeWeight(const ContactFaceData &F,
                                                 const CommonPlaneData &cp, Index p, Visit &&visit)
{
  for (int side = 0; side < 2; ++side)
  {
    const Index f = side == 0 ? cp.face1(p) : cp.face2(p);
    const Real sign = side == 0 ? -1.0 : 1.0;
    if (F.ghost(f))
      continue;
    for (int a = 0; a < F.num_nodes(f); ++a)
      visit(shareSlot(p, side, a), F.nodes(f, a), sign * (side == 0 ? cp.w1(p, a) : cp.w2(p, a)));
  }
}

/// (17)-(18): -w1 F on the nodes of face 1, +w2 F on face 2; with `dv`, also the velocity
/// change dt F w / M of every node component that is not prescribed. A ghost face gets nothing.
KOKKOS_INLINE_FUNCTION void scatterForce(const ContactFaceData &F, const CommonPlaneData &cp,
                                         Index p, const Real Fv[3], const VectorView &fc,
                                         const VectorView &dv, const RealView &mass,
                                         const DeviceView<int *[3]> &bc, Real dt, int dim,
                                         const NodeAdder &add)
{
  forEachOwnNodeWeight(F, cp, p, [&](Index, Index k, Real w) {
    for (int d = 0; d < dim; ++d)
    {
      add(&fc(k, d), w * Fv[d]);
      if (dv.extent(0) > 0 && bc(k, d) < 0)
        add(&dv(k, d), w * Fv[d] * dt / mass(k));
    }
  });
}

/// scatterForce() without the adds: the share w F of every node of CP p's own faces into its
/// slot of `share`, so that the nodes can sum them in a fixed order, whatever the thread count
/// (ContactSystem::assembleSlots()). The slots of ghost faces, of nodes past the face's count
/// and of components past dim keep the zeros the caller wrote.
KOKKOS_INLINE_FUNCTION void shareForce(const ContactFaceData &F, const CommonPlaneData &cp, Index p,
                                       const Real Fv[3], const VectorView &share, int dim)
{
  forEachOwnNodeWeight(F, cp, p, [&](Index slot, Index, Real w) {
    for (int d = 0; d < dim; ++d)
      share(slot, d) = w * Fv[d];
  });
}

/// True where this rank counts node k's contact work: everywhere but at the shared nodes that
/// another rank owns, when their forces are whole on every copy (`copy`:
/// ContactSystem::_copy_node, a device View or its host mirror; empty otherwise).
template <class CopyView>
KOKKOS_INLINE_FUNCTION bool countsNodeWork(const CopyView &copy, Index k)
{
  return size_t(k) >= copy.extent(0) || copy(k) == 0;
}

/// True on the one rank that counts CP p in sums over CPs (energies, dot products, outputs):
/// the rank of face 1 (the face with the smaller key); every CP in serial.
KOKKOS_INLINE_FUNCTION bool ownsPlane(const ContactFaceData &F, const CommonPlaneData &cp, Index p)
{
  return F.ghost(cp.face1(p)) == 0;
}

/// The explicit limit (19) of a CP between faces f1 and f2 of areas A1, A2 closing at Vn, with
/// history s, over the horizon dt_el [s]. A ghost face's element is on another rank, which
/// sent its density (step 8).
KOKKOS_INLINE_FUNCTION Real explicitCpTimeStep(const ContactFaceData &F, const JointParams &P,
                                               const CpState &s, Index f1, Index f2, Real A1,
                                               Real A2, Real Vn, const RealView &emass,
                                               const RealView &volume, Real dt_el)
{
  const Real mu =
      arealReducedMass(F.mass(f1), A1, F.rigid(f1) != 0, F.mass(f2), A2, F.rigid(f2) != 0);
  const Index e1 = F.element(f1), e2 = F.element(f2);
  const Real rho1 = e1 >= 0 ? emass(e1) / volume(e1) : F.density(f1);
  const Real rho2 = e2 >= 0 ? emass(e2) / volume(e2) : F.density(f2);
  return contactTimeStep(P, s, Vn, dt_el, mu, 0.5 * (rho1 + rho2));
}

} // namespace contact_kernels
} // namespace scpdyn
