#pragma once
/// \file TieRows.hpp
/// \brief Internal to the contact room: the rows of the velocity-constraint system of step 9
/// (docs/theory.md 10.8, 11.1, 11.2), shared by its two solvers: conjugate gradients for the
/// ties alone (ContactConstraints.cpp) and the bound-constrained solve once slide lines take
/// part (ContactBoundSolve.cpp). Row c belongs to CP c / Q, Q = ContactSystem::_tie_points.
#include "contact/ContactKernels.hpp"

namespace scpdyn
{
namespace tie_rows
{
using contact_kernels::faceVelocityWith;

enum TieMode : int
{
  TieNone = 0,  ///< not constrained this cycle
  TieFull = 1,  ///< sticky: V1 = V2 at the end of the step (25)
  TieNormal = 2 ///< slide line in compression: (V1 - V2).n = gap/dt (D14)
};

/// dt sum w^2/M over the nodes of tie row c (of CP p), per component d whose velocity is free
/// (the diagonal of the tie operator); for a normal tie, the same along n.
KOKKOS_INLINE_FUNCTION void tieDiagonal(const ContactFaceData &F, const CommonPlaneData &cp,
                                        const TieWeights &tw, Index c, Index p,
                                        const RealView &mass, const DeviceView<int *[3]> &bc,
                                        Real dt, int dim, Real D[3], Real &Dn)
{
  D[0] = D[1] = D[2] = Dn = 0;
  for (int side = 0; side < 2; ++side)
  {
    const Index f = side == 0 ? cp.face1(p) : cp.face2(p);
    for (int a = 0; a < F.num_nodes(f); ++a)
    {
      const Index k = F.nodes(f, a);
      const Real w = side == 0 ? tw.w1(c, a) : tw.w2(c, a);
      for (int d = 0; d < dim; ++d)
        if (bc(k, d) < 0)
        {
          D[d] += dt * w * w / mass(k);
          Dn += dt * w * w * cp.normal(p, d) * cp.normal(p, d) / mass(k);
        }
    }
  }
}

/// Velocity of face `side` (0: face 1, 1: face 2) at tie row c of CP p.
KOKKOS_INLINE_FUNCTION void rowVelocity(const ContactFaceData &F, const CommonPlaneData &cp,
                                        const TieWeights &tw, Index c, Index p, int side,
                                        const VectorView &v, Real V[3])
{
  if (side == 0)
    faceVelocityWith(F, cp.face1(p), tw.w1, c, v, V);
  else
    faceVelocityWith(F, cp.face2(p), tw.w2, c, v, V);
}

/// Calls visit(slot, node, w) for every node of tie row c's own faces (CP p) with its signed
/// weight, -w1 on face 1 and +w2 on face 2, side by side and node by node (slot:
/// shareSlot(c, side, a)). A ghost face is skipped: its own rank adds that side.
template <class Visit>
KOKKOS_INLINE_FUNCTION void forEachOwnRowWeight(const ContactFaceData &F, const CommonPlaneData &cp,
                                                const TieWeights &tw, Index c, Index p,
                                                Visit &&visit)
{
  for (int side = 0; side < 2; ++side)
  {
    const Index f = side == 0 ? cp.face1(p) : cp.face2(p);
    if (F.ghost(f))
      continue;
    const Real sign = side == 0 ? -1.0 : 1.0;
    for (int a = 0; a < F.num_nodes(f); ++a)
      visit(contact_kernels::shareSlot(c, side, a), F.nodes(f, a),
            sign * (side == 0 ? tw.w1(c, a) : tw.w2(c, a)));
  }
}

/// The force Fv of tie row c of CP p on its own faces' nodes: -w1 Fv on face 1, +w2 Fv on
/// face 2, into `out` as a force (dt_over_mass = false) or a velocity change dt Fv w / M of the
/// free components (true).
KOKKOS_INLINE_FUNCTION void rowScatter(const ContactFaceData &F, const CommonPlaneData &cp,
                                       const TieWeights &tw, Index c, Index p, const Real Fv[3],
                                       const VectorView &out, bool dt_over_mass,
                                       const RealView &mass, const DeviceView<int *[3]> &bc,
                                       Real dt, int dim, const contact_kernels::NodeAdder &add)
{
  forEachOwnRowWeight(F, cp, tw, c, p, [&](Index, Index k, Real w) {
    for (int d = 0; d < dim; ++d)
      if (!dt_over_mass)
        add(&out(k, d), w * Fv[d]);
      else if (bc(k, d) < 0)
        add(&out(k, d), w * Fv[d] * dt / mass(k));
  });
}

/// rowScatter() without the adds: the share of every node of tie row c's own faces into its
/// slot of `share`, every component written (zero where rowScatter adds nothing), so that the
/// nodes can sum the rows in order (ContactSystem::assembleSlots). The slots of ghost faces and
/// of nodes past a face's count are in no node's list.
KOKKOS_INLINE_FUNCTION void rowShare(const ContactFaceData &F, const CommonPlaneData &cp,
                                     const TieWeights &tw, Index c, Index p, const Real Fv[3],
                                     const VectorView &share, bool dt_over_mass,
                                     const RealView &mass, const DeviceView<int *[3]> &bc, Real dt,
                                     int dim)
{
  forEachOwnRowWeight(F, cp, tw, c, p, [&](Index slot, Index k, Real w) {
    for (int d = 0; d < 3; ++d)
      share(slot, d) = d >= dim        ? 0.0
                       : !dt_over_mass ? w * Fv[d]
                       : bc(k, d) < 0  ? w * Fv[d] * dt / mass(k)
                                       : 0.0;
  });
}

/// Keep the constrained part of a CP vector: all of it (full tie), its normal part (normal
/// tie) or nothing.
KOKKOS_INLINE_FUNCTION void project(const CommonPlaneData &cp, Index p, int mode, int dim,
                                    Real v[3])
{
  if (mode == TieNormal)
  {
    Real vn = 0;
    for (int d = 0; d < 3; ++d)
      vn += v[d] * cp.normal(p, d);
    for (int d = 0; d < 3; ++d)
      v[d] = vn * cp.normal(p, d);
  }
  for (int d = 0; d < 3; ++d)
    if (mode == TieNone || d >= dim)
      v[d] = 0;
}

/// The preconditioned residual z = diag^-1 r of one CP.
KOKKOS_INLINE_FUNCTION void precondition(const CommonPlaneData &cp, Index p, int mode,
                                         const Real D[3], Real Dn, const Real r[3], Real z[3])
{
  for (int d = 0; d < 3; ++d)
    z[d] = mode == TieFull               ? (D[d] > 0 ? r[d] / D[d] : 0.0)
           : mode == TieNormal && Dn > 0 ? r[d] / Dn
                                         : 0.0;
  (void)cp;
  (void)p;
}

} // namespace tie_rows
} // namespace scpdyn
