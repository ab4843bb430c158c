// The velocity-constraint options of step 9 (docs/theory.md 10.5, 10.8, 11.1, 11.2): all sticky
// and slide-line CPs are solved together, every cycle, as one linear system for their forces
// (preconditioned conjugate gradients), with an active set for the slide lines' "no tension".
//
// Why not one pass of independent CP forces (10.8): a node at a brick corner or T-junction
// belongs to several CPs, and each CP's m* assumes it owns the node, so one pass over-corrects
// (measured: the staggered wall of verification T6d gains energy and blows up). Jacobi passes
// with node masses shared among the CPs are stable but converge slowly at T-junctions and
// along long interfaces (the face-average ties of a straight interface form a chain whose
// operator has eigenvalues 1 + cos(k pi/(N+1))), so a tolerance needs a Krylov solver.
#include "contact/ContactKernels.hpp"
#include "contact/ContactSystem.hpp"
#include "contact/JointConstraints.hpp"

namespace scpdyn
{
using namespace contact_kernels;

namespace
{

enum TieMode : int
{
  TieNone = 0,  ///< not constrained this cycle
  TieFull = 1,  ///< sticky: V1 = V2 at the end of the step (25)
  TieNormal = 2 ///< slide line in compression: (V1 - V2).n = gap/dt (D14)
};

/// dt sum w^2/M over the nodes of CP p, per component d whose velocity is free (the diagonal
/// of the tie operator); for a normal tie, the same along n.
KOKKOS_INLINE_FUNCTION void tieDiagonal(const ContactFaceData &F, const CommonPlaneData &cp,
                                        Index p, const RealView &mass,
                                        const DeviceView<int *[3]> &bc, Real dt, int dim, Real D[3],
                                        Real &Dn)
{
  D[0] = D[1] = D[2] = Dn = 0;
  for (int side = 0; side < 2; ++side)
  {
    const Index f = side == 0 ? cp.face1(p) : cp.face2(p);
    for (int a = 0; a < F.num_nodes(f); ++a)
    {
      const Index k = F.nodes(f, a);
      const Real w = side == 0 ? cp.w1(p, a) : cp.w2(p, a);
      for (int d = 0; d < dim; ++d)
        if (bc(k, d) < 0)
        {
          D[d] += dt * w * w / mass(k);
          Dn += dt * w * w * cp.normal(p, d) * cp.normal(p, d) / mass(k);
        }
    }
  }
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

} // namespace

void ContactSystem::tieScatter(const NodeFields &nodes, Real dt, const VectorView &force)
{
  const ContactFaceData F = _faces;
  const CommonPlaneData cp = _cp;
  auto dv = _dv;
  auto mass = nodes.mass;
  auto bc = nodes.bc;
  auto used = _faces.nodes_used;
  auto mode = _tie_mode;
  const int dim = _dim;
  Kokkos::parallel_for(
      "scpdyn::contact::tieZero", Kokkos::RangePolicy<ExecSpace>(0, Index(used.extent(0))),
      KOKKOS_LAMBDA(const Index i) {
        for (int d = 0; d < 3; ++d)
          dv(used(i), d) = 0;
      });
  Kokkos::parallel_for(
      "scpdyn::contact::tieScatter", Kokkos::RangePolicy<ExecSpace>(0, cp.count),
      KOKKOS_LAMBDA(const Index p) {
        if (mode(p) == TieNone)
          return;
        for (int side = 0; side < 2; ++side)
        {
          const Index f = side == 0 ? cp.face1(p) : cp.face2(p);
          const Real sign = side == 0 ? -1.0 : 1.0;
          if (F.ghost(f))
            continue; // its own rank adds this side
          for (int a = 0; a < F.num_nodes(f); ++a)
          {
            const Index k = F.nodes(f, a);
            const Real w = sign * (side == 0 ? cp.w1(p, a) : cp.w2(p, a));
            for (int d = 0; d < dim; ++d)
              if (bc(k, d) < 0)
                Kokkos::atomic_add(&dv(k, d), w * force(p, d) * dt / mass(k));
          }
        }
      });
  if (_comm.sum_nodes) // every copy of a node sees the increments of every rank's CPs
    _comm.sum_nodes(dv);
}

int ContactSystem::tieSolve(const NodeFields &nodes, Real dt)
{
  const ContactFaceData F = _faces;
  const CommonPlaneData cp = _cp;
  auto X = _cg_x, R = _cg_r, Pv = _cg_p, Z = _cg_z, AP = _cg_ap, B = _cg_b;
  auto dv = _dv;
  auto mass = nodes.mass;
  auto bc = nodes.bc;
  auto mode = _tie_mode;
  const int dim = _dim;
  Real rz = 0;
  Kokkos::parallel_reduce(
      "scpdyn::contact::tieSetup", Kokkos::RangePolicy<ExecSpace>(0, cp.count),
      KOKKOS_LAMBDA(const Index p, Real &sum) {
        Real r[3] = {B(p, 0), B(p, 1), B(p, 2)}, z[3], D[3], Dn;
        project(cp, p, mode(p), dim, r);
        tieDiagonal(F, cp, p, mass, bc, dt, dim, D, Dn);
        precondition(cp, p, mode(p), D, Dn, r, z);
        const bool counted = ownsPlane(F, cp, p); // a cross-rank CP counts once
        for (int d = 0; d < 3; ++d)
        {
          X(p, d) = 0;
          R(p, d) = r[d];
          Z(p, d) = z[d];
          Pv(p, d) = z[d];
          if (counted)
            sum += r[d] * z[d];
        }
      },
      rz);
  rz = globalSum(rz);
  const Real rz0 = rz;
  int it = 0;
  for (; it < _passes && rz > 1e-20 * rz0 && rz > 0; ++it)
  {
    tieScatter(nodes, dt, Pv);
    Real pap = 0;
    Kokkos::parallel_reduce(
        "scpdyn::contact::tieApply", Kokkos::RangePolicy<ExecSpace>(0, cp.count),
        KOKKOS_LAMBDA(const Index p, Real &sum) {
          Real V1[3], V2[3], ap[3];
          weightedVelocity(F, cp, p, 0, dv, V1);
          weightedVelocity(F, cp, p, 1, dv, V2);
          for (int d = 0; d < 3; ++d)
            ap[d] = V2[d] - V1[d]; // (A p)_c: the relative velocity the forces p remove
          project(cp, p, mode(p), dim, ap);
          const bool counted = ownsPlane(F, cp, p);
          for (int d = 0; d < 3; ++d)
          {
            AP(p, d) = ap[d];
            if (counted)
              sum += Pv(p, d) * ap[d];
          }
        },
        pap);
    pap = globalSum(pap);
    if (!(pap > 0))
      break;
    const Real alpha = rz / pap;
    Real rz_new = 0;
    Kokkos::parallel_reduce(
        "scpdyn::contact::tieUpdate", Kokkos::RangePolicy<ExecSpace>(0, cp.count),
        KOKKOS_LAMBDA(const Index p, Real &sum) {
          Real r[3], z[3], D[3], Dn;
          for (int d = 0; d < 3; ++d)
          {
            X(p, d) += alpha * Pv(p, d);
            r[d] = R(p, d) - alpha * AP(p, d);
            R(p, d) = r[d];
          }
          tieDiagonal(F, cp, p, mass, bc, dt, dim, D, Dn);
          precondition(cp, p, mode(p), D, Dn, r, z);
          const bool counted = ownsPlane(F, cp, p);
          for (int d = 0; d < 3; ++d)
          {
            Z(p, d) = z[d];
            if (counted)
              sum += r[d] * z[d];
          }
        },
        rz_new);
    rz_new = globalSum(rz_new);
    const Real beta = rz_new / rz;
    rz = rz_new;
    Kokkos::parallel_for(
        "scpdyn::contact::tieDirection", Kokkos::RangePolicy<ExecSpace>(0, cp.count),
        KOKKOS_LAMBDA(const Index p) {
          for (int d = 0; d < 3; ++d)
            Pv(p, d) = Z(p, d) + beta * Pv(p, d);
        });
  }
  return it;
}

void ContactSystem::constraintPasses(const NodeFields &nodes, Real dt)
{
  const ContactFaceData F = _faces;
  const CommonPlaneData cp = _cp;
  const size_t n = size_t(cp.count);
  if (_cg_x.extent(0) != n)
  {
    _cg_x = VectorView("cg_x", n);
    _cg_r = VectorView("cg_r", n);
    _cg_p = VectorView("cg_p", n);
    _cg_z = VectorView("cg_z", n);
    _cg_ap = VectorView("cg_ap", n);
    _cg_b = VectorView("cg_b", n);
    _tie_mode = IndexView("tie_mode", n);
  }
  auto vstar = _vstar, fc = _fc, dv = _dv;
  auto mass = nodes.mass;
  auto bc = nodes.bc;
  auto used = _faces.nodes_used;
  auto X = _cg_x, B = _cg_b;
  auto mode = _tie_mode;
  const int dim = _dim;
  const Index nused = Index(used.extent(0));
  // the joint CPs' forces are part of what the constraints see; decomposed: their totals over
  // the ranks (fc holds this rank's faces only), summed in a copy so step 10b still sums parts
  VectorView joint = fc;
  if (_comm.sum_nodes)
  {
    Kokkos::deep_copy(dv, fc);
    _comm.sum_nodes(dv);
    joint = dv;
  }
  Kokkos::parallel_for(
      "scpdyn::contact::vstarJoints", Kokkos::RangePolicy<ExecSpace>(0, nused),
      KOKKOS_LAMBDA(const Index i) {
        const Index k = used(i);
        for (int d = 0; d < dim; ++d)
          if (bc(k, d) < 0)
            vstar(k, d) += dt * joint(k, d) / mass(k);
      });
  // targets b: the relative velocity to remove (sticky), or the normal approach beyond the gap
  // (slide line); slide lines start active where they approach
  Kokkos::parallel_for(
      "scpdyn::contact::tieTargets", Kokkos::RangePolicy<ExecSpace>(0, cp.count),
      KOKKOS_LAMBDA(const Index p) {
        const ContactOption o = cp.params(p).option;
        Real V1[3], V2[3], Vn = 0;
        weightedVelocity(F, cp, p, 0, vstar, V1);
        weightedVelocity(F, cp, p, 1, vstar, V2);
        for (int d = 0; d < 3; ++d)
          Vn += (V1[d] - V2[d]) * cp.normal(p, d);
        const Real gap = cp.state(p).u < 0 ? -cp.state(p).u : 0.0;
        const Real excess = Vn - gap / dt;
        const bool active = cp.status(p) != CpInactive;
        mode(p) = !active                                       ? TieNone
                  : o == ContactOption::Sticky                  ? TieFull
                  : o == ContactOption::SlideLine && excess > 0 ? TieNormal
                                                                : TieNone;
        for (int d = 0; d < 3; ++d)
          B(p, d) = o == ContactOption::Sticky ? V1[d] - V2[d] : excess * cp.normal(p, d);
      });
  // Active set for "no tension" (D14): solve, free the slide lines that pull, add those that
  // still approach beyond their gap, repeat until nothing changes.
  for (int outer = 0; outer < 20; ++outer)
  {
    tieSolve(nodes, dt);
    if (!_has_slide)
      break;
    tieScatter(nodes, dt, X);
    Index changed = 0;
    Kokkos::parallel_reduce(
        "scpdyn::contact::tieActiveSet", Kokkos::RangePolicy<ExecSpace>(0, cp.count),
        KOKKOS_LAMBDA(const Index p, Index &count) {
          if (cp.params(p).option != ContactOption::SlideLine || cp.status(p) == CpInactive)
            return;
          Real V1[3], V2[3], Fn = 0, dVn = 0, bn = 0;
          weightedVelocity(F, cp, p, 0, dv, V1);
          weightedVelocity(F, cp, p, 1, dv, V2);
          for (int d = 0; d < 3; ++d)
          {
            Fn += X(p, d) * cp.normal(p, d);
            dVn += (V1[d] - V2[d]) * cp.normal(p, d);
            bn += B(p, d) * cp.normal(p, d);
          }
          // tolerance: round-off of the removed approach velocity
          const Real tol = 1e-9 * (contact_math::abs(bn) + contact_math::abs(dVn)) + 1e-300;
          if (mode(p) == TieNormal && Fn < 0)
          {
            mode(p) = TieNone;
            ++count;
          }
          else if (mode(p) == TieNone && bn + dVn > tol)
          {
            mode(p) = TieNormal;
            ++count;
          }
        },
        changed);
    if (globalSum(Real(changed)) == 0)
      break;
  }
  // apply the forces: contact force, v*, CP totals
  tieScatter(nodes, dt, X);
  const VectorView no_dv;
  Kokkos::parallel_for(
      "scpdyn::contact::tieApplyNodes", Kokkos::RangePolicy<ExecSpace>(0, nused),
      KOKKOS_LAMBDA(const Index i) {
        const Index k = used(i);
        for (int d = 0; d < 3; ++d)
          vstar(k, d) += dv(k, d);
      });
  Kokkos::parallel_for(
      "scpdyn::contact::constraintFinish", Kokkos::RangePolicy<ExecSpace>(0, cp.count),
      KOKKOS_LAMBDA(const Index p) {
        const JointParams &P = cp.params(p);
        if (!isConstraint(P.option) || cp.status(p) == CpInactive)
          return;
        Real f[3], Fn = 0;
        for (int d = 0; d < 3; ++d)
        {
          f[d] = mode(p) == TieNone ? 0.0 : X(p, d);
          cp.force(p, d) = f[d];
          Fn += f[d] * cp.normal(p, d);
        }
        scatterForce(F, cp, p, f, fc, no_dv, mass, bc, dt, dim);
        CpState s = cp.state(p);
        Real V1[3], V2[3], Vn = 0;
        weightedVelocity(F, cp, p, 0, vstar, V1);
        weightedVelocity(F, cp, p, 1, vstar, V2);
        for (int d = 0; d < 3; ++d)
          Vn += (V1[d] - V2[d]) * cp.normal(p, d);
        s.u += dt * Vn; // the end-of-step closure rate
        s.umax = contact_math::max(s.umax, s.u);
        s.Fn = Fn;
        for (int d = 0; d < 3; ++d)
        {
          s.Fs[d] = f[d] - Fn * cp.normal(p, d);
          s.n_old[d] = cp.normal(p, d);
        }
        s.Ac_old = cp.area(p);
        cp.state(p) = s;
        if (mode(p) == TieNone)
          cp.status(p) = CpOpen;
      });
}

} // namespace scpdyn
