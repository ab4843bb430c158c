// The velocity-constraint options of step 9 (docs/theory.md 10.5, 10.8, 11.1, 11.2): all sticky
// and slide-line CPs are solved together, every cycle, as one system for their forces: the ties
// alone by preconditioned conjugate gradients (here), with slide lines as a bound-constrained
// problem for their "no tension" (ContactBoundSolve.cpp).
//
// Why not one pass of independent CP forces (10.8): a node at a brick corner or T-junction
// belongs to several CPs, and each CP's m* assumes it owns the node, so one pass over-corrects
// (measured: the staggered wall of verification T6d gains energy and blows up). Jacobi passes
// with node masses shared among the CPs are stable but converge slowly at T-junctions and
// along long interfaces (the face-average ties of a straight interface form a chain whose
// operator has eigenvalues 1 + cos(k pi/(N+1))), so a tolerance needs a Krylov solver.
//
// The unknowns are per tie row: a sticky CP in 2D ties V1 = V2 at the two Gauss points of its
// overlap (cp_geometry::tieWeights2D), each with the shape-function weights of both faces there
// (docs/theory.md 11.2); a slide line, and a 3D or 1D sticky CP, acts at its POC (row 0 of its
// CP, the others idle). Row c belongs to CP c / Q, Q = ContactSystem::_tie_points.
#include "contact/ContactSystem.hpp"
#include "contact/JointConstraints.hpp"
#include "contact/TieRows.hpp"

namespace scpdyn
{
using namespace contact_kernels;
using namespace tie_rows;

void ContactSystem::tieScatter(const NodeFields &nodes, Real dt, const VectorView &force)
{
  const ContactFaceData F = _faces;
  const CommonPlaneData cp = _cp;
  const TieWeights tw = _tie;
  auto dv = _dv;
  auto mass = nodes.mass;
  auto bc = nodes.bc;
  auto used = _faces.nodes_used;
  auto mode = _tie_mode;
  const int dim = _dim, Q = _tie_points;
  const NodeAdder add = nodeAdder();
  if (const NodeSlotRows *slots = slotRows(_tie_points, _tie_rows))
  { // in a fixed order (ContactShares.cpp)
    auto share = slots->share;
    Kokkos::parallel_for(
        "scpdyn::contact::tieShares", Kokkos::RangePolicy<ExecSpace>(0, cp.count * Q),
        KOKKOS_LAMBDA(const Index c) {
          const bool none = mode(c) == TieNone;
          const Real f[3] = {none ? 0.0 : force(c, 0), none ? 0.0 : force(c, 1),
                             none ? 0.0 : force(c, 2)};
          rowShare(F, cp, tw, c, c / Q, f, share, true, mass, bc, dt, dim);
        });
    assembleSlots(*slots, dv, true);
    sumOverRanks(slots, dv);
    return;
  }
  Kokkos::parallel_for(
      "scpdyn::contact::tieZero", Kokkos::RangePolicy<ExecSpace>(0, Index(used.extent(0))),
      KOKKOS_LAMBDA(const Index i) {
        for (int d = 0; d < 3; ++d)
          dv(used(i), d) = 0;
      });
  Kokkos::parallel_for(
      "scpdyn::contact::tieScatter", Kokkos::RangePolicy<ExecSpace>(0, cp.count * Q),
      KOKKOS_LAMBDA(const Index c) {
        if (mode(c) == TieNone)
          return;
        const Real f[3] = {force(c, 0), force(c, 1), force(c, 2)};
        rowScatter(F, cp, tw, c, c / Q, f, dv, true, mass, bc, dt, dim, add);
      });
  sumOverRanks(nullptr, dv); // every copy of a node sees the increments of every rank's CPs
}

int ContactSystem::tieSolve(const NodeFields &nodes, Real dt)
{
  const ContactFaceData F = _faces;
  const CommonPlaneData cp = _cp;
  const TieWeights tw = _tie;
  auto X = _cg_x, R = _cg_r, Pv = _cg_p, Z = _cg_z, AP = _cg_ap, B = _cg_b;
  auto dv = _dv;
  auto mass = nodes.mass;
  auto bc = nodes.bc;
  auto mode = _tie_mode;
  const int dim = _dim, Q = _tie_points;
  const Index rows = cp.count * Q;
  auto W = _cg_w;
  auto diag = _cg_diag;
  // every sum of the solve is exact (ExactSum.hpp) over the rows, each row's own terms added
  // first in component order: its bits do not depend on the threads or the ranks that add
  // the rows (one exact add a row, a third of the cost of one a term: perf/results/log.md)
  ExactSums<2> setup; // r.z, and the same norm of the face velocities themselves
  Kokkos::parallel_reduce(
      "scpdyn::contact::tieSetup", Kokkos::RangePolicy<ExecSpace>(0, rows),
      KOKKOS_LAMBDA(const Index c, ExactSums<2> &acc) {
        const Index p = c / Q;
        Real r[3] = {B(c, 0), B(c, 1), B(c, 2)}, z[3], D[3], Dn, zv[3];
        Real wv[3] = {W(c, 0), W(c, 1), W(c, 2)};
        project(cp, p, mode(c), dim, r);
        tieDiagonal(F, cp, tw, c, p, mass, bc, dt, dim, D, Dn);
        for (int d = 0; d < 3; ++d)
          diag(c, d) = D[d];
        diag(c, 3) = Dn;
        precondition(cp, p, mode(c), D, Dn, r, z);
        project(cp, p, mode(c), dim, wv);
        precondition(cp, p, mode(c), D, Dn, wv, zv);
        const bool counted = ownsPlane(F, cp, p); // a cross-rank CP counts once
        Real rz_row = 0, wz_row = 0;
        for (int d = 0; d < 3; ++d)
        {
          X(c, d) = 0;
          R(c, d) = r[d];
          Z(c, d) = z[d];
          Pv(c, d) = z[d];
          rz_row += r[d] * z[d];
          wz_row += wv[d] * zv[d];
        }
        if (counted)
          acc.add(0, rz_row), acc.add(1, wz_row);
      },
      ExactSumsReducer<2>(setup));
  Real sums[2];
  exactTotals(setup, sums);
  Real rz = sums[0];
  // Stop at 1e-10 of the initial residual, or where the relative velocity left is round-off of
  // the face velocities (1e-13 of them): below that the targets are noise, and on a redundant
  // system (a node pair tied by two CPs) CG would chase that noise out of the operator's range.
  const Real rz_stop = contact_math::max(1e-20 * rz, 1e-26 * sums[1]);
  int it = 0;
  for (; it < _passes && rz > rz_stop && rz > 0; ++it)
  {
    tieScatter(nodes, dt, Pv);
    ExactSums<1> pap_sum;
    Kokkos::parallel_reduce(
        "scpdyn::contact::tieApply", Kokkos::RangePolicy<ExecSpace>(0, rows),
        KOKKOS_LAMBDA(const Index c, ExactSums<1> &acc) {
          const Index p = c / Q;
          Real V1[3], V2[3], ap[3];
          rowVelocity(F, cp, tw, c, p, 0, dv, V1);
          rowVelocity(F, cp, tw, c, p, 1, dv, V2);
          for (int d = 0; d < 3; ++d)
            ap[d] = V2[d] - V1[d]; // (A p)_c: the relative velocity the forces p remove
          project(cp, p, mode(c), dim, ap);
          Real pap_row = 0;
          for (int d = 0; d < 3; ++d)
          {
            AP(c, d) = ap[d];
            pap_row += Pv(c, d) * ap[d];
          }
          if (ownsPlane(F, cp, p))
            acc.add(0, pap_row);
        },
        ExactSumsReducer<1>(pap_sum));
    Real pap;
    exactTotals(pap_sum, &pap);
    if (!(pap > 0))
      break;
    const Real alpha = rz / pap;
    ExactSums<1> rz_sum;
    Kokkos::parallel_reduce(
        "scpdyn::contact::tieUpdate", Kokkos::RangePolicy<ExecSpace>(0, rows),
        KOKKOS_LAMBDA(const Index c, ExactSums<1> &acc) {
          const Index p = c / Q;
          Real r[3], z[3];
          for (int d = 0; d < 3; ++d)
          {
            X(c, d) += alpha * Pv(c, d);
            r[d] = R(c, d) - alpha * AP(c, d);
            R(c, d) = r[d];
          }
          const Real D[3] = {diag(c, 0), diag(c, 1), diag(c, 2)};
          precondition(cp, p, mode(c), D, diag(c, 3), r, z);
          Real rz_row = 0;
          for (int d = 0; d < 3; ++d)
          {
            Z(c, d) = z[d];
            rz_row += r[d] * z[d];
          }
          if (ownsPlane(F, cp, p))
            acc.add(0, rz_row);
        },
        ExactSumsReducer<1>(rz_sum));
    Real rz_new;
    exactTotals(rz_sum, &rz_new);
    const Real beta = rz_new / rz;
    rz = rz_new;
    Kokkos::parallel_for(
        "scpdyn::contact::tieDirection", Kokkos::RangePolicy<ExecSpace>(0, rows),
        KOKKOS_LAMBDA(const Index c) {
          for (int d = 0; d < 3; ++d)
            Pv(c, d) = Z(c, d) + beta * Pv(c, d);
        });
  }
  return it;
}

void ContactSystem::allocateTieRows()
{
  const size_t n = size_t(_cp.count) * size_t(_tie_points);
  if (_cg_x.extent(0) == n)
    return;
  _cg_x = VectorView("cg_x", n);
  _cg_r = VectorView("cg_r", n);
  _cg_p = VectorView("cg_p", n);
  _cg_z = VectorView("cg_z", n);
  _cg_ap = VectorView("cg_ap", n);
  _cg_b = VectorView("cg_b", n);
  _cg_w = VectorView("cg_w", n);
  _cg_s = VectorView("cg_s", n);
  _cg_t = VectorView("cg_t", n);
  _cg_best = VectorView("cg_best", n);
  _cg_diag = DeviceView<Real *[4]>("cg_diag", n);
  _tie_mode = IndexView("tie_mode", n);
  _tie.w1 = DeviceView<Real *[kMaxFaceNodes]>("tie_w1", n);
  _tie.w2 = DeviceView<Real *[kMaxFaceNodes]>("tie_w2", n);
}

void ContactSystem::constraintPasses(const NodeFields &nodes, Real dt)
{
  const ContactFaceData F = _faces;
  const CommonPlaneData cp = _cp;
  const TieWeights tw = _tie;
  auto vstar = _vstar, fc = _fc, dv = _dv;
  auto mass = nodes.mass;
  auto bc = nodes.bc;
  auto used = _faces.nodes_used;
  auto X = _cg_x, B = _cg_b, W = _cg_w;
  auto mode = _tie_mode;
  const int dim = _dim, Q = _tie_points;
  const Index nused = Index(used.extent(0)), rows = cp.count * Q;
  const NodeAdder add = nodeAdder();
  const NodeSlotRows *slots = slotRows(_tie_points, _tie_rows);
  const bool gather = slots != nullptr;
  const VectorView share = gather ? slots->share : VectorView();
  // the joint CPs' forces are part of what the constraints see; decomposed: their totals over
  // the ranks (fc holds this rank's faces only, or the shared nodes' totals already when they
  // sum in order), made whole in a copy so step 9b still sums parts
  VectorView joint = fc;
  if (_comm.sum_nodes)
  {
    Kokkos::deep_copy(dv, fc);
    sumOverRanks(_gather_forces ? &_share_rows : nullptr, dv);
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
  // targets b: the relative velocity to remove at each tie point (sticky), or the normal
  // approach beyond the gap at the POC (slide line; one that separates gets no force from the
  // bound-constrained solve)
  Kokkos::parallel_for(
      "scpdyn::contact::tieTargets", Kokkos::RangePolicy<ExecSpace>(0, rows),
      KOKKOS_LAMBDA(const Index c) {
        const Index p = c / Q;
        Real V1[3], V2[3], Vn = 0;
        rowVelocity(F, cp, tw, c, p, 0, vstar, V1);
        rowVelocity(F, cp, tw, c, p, 1, vstar, V2);
        for (int d = 0; d < 3; ++d)
          Vn += (V1[d] - V2[d]) * cp.normal(p, d);
        const Real gap = cp.state(p).u < 0 ? -cp.state(p).u : 0.0;
        const Real excess = Vn - gap / dt;
        const bool active = cp.status(p) != CpInactive;
        const bool sticky_row = isTie(cp.params(p), cp.state(p));
        const bool slide_row = isSlide(cp.params(p), cp.state(p)) && c % Q == 0; // at the POC
        mode(c) = !active ? TieNone : sticky_row ? TieFull : slide_row ? TieNormal : TieNone;
        for (int d = 0; d < 3; ++d) // the scale of the solve's round-off stop (tieSolve)
          W(c, d) = contact_math::abs(V1[d]) + contact_math::abs(V2[d]);
        for (int d = 0; d < 3; ++d)
          B(c, d) = sticky_row ? V1[d] - V2[d] : slide_row ? excess * cp.normal(p, d) : 0.0;
      });
  // ties alone: one linear system; with slide lines, their "no tension" makes it a
  // bound-constrained one (ContactBoundSolve.cpp)
  const bool sliding = slideLinesLive() || (_has_sleepy && failedCount() > 0); // collective
  if (sliding)
    boundSolve(nodes, dt);
  else
  {
    _tie_iterations += tieSolve(nodes, dt);
    ++_tie_solves;
  }
  if (_has_friction && sliding) // the slide lines' Coulomb friction, on their normal forces
    slideFriction(nodes, dt);
  // apply the forces: contact force, v*, CP totals
  tieScatter(nodes, dt, X);
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
        if (gather) // a row without force gives its nodes nothing
          clearShares(share, p * Q, (p + 1) * Q);
        if (!isConstraint(P.option) || cp.status(p) == CpInactive)
          return;
        Real f[3] = {0, 0, 0}, Fn = 0;
        bool tied = false;
        for (Index c = p * Q; c < (p + 1) * Q; ++c)
        {
          if (mode(c) == TieNone)
            continue;
          tied = true;
          const Real fr[3] = {X(c, 0), X(c, 1), X(c, 2)};
          if (gather)
            rowShare(F, cp, tw, c, p, fr, share, false, mass, bc, dt, dim);
          else
            rowScatter(F, cp, tw, c, p, fr, fc, false, mass, bc, dt, dim, add);
          for (int d = 0; d < 3; ++d)
            f[d] += fr[d];
        }
        for (int d = 0; d < 3; ++d)
        {
          cp.force(p, d) = f[d];
          Fn += f[d] * cp.normal(p, d);
        }
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
        if (!tied)
          cp.status(p) = CpOpen;
      });
  if (gather)
    assembleSlots(*slots, fc, false);
}

} // namespace scpdyn
