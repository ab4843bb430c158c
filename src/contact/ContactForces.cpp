// Step 9 of the cycle for every CP (docs/theory.md Appendix A): half-step geometry (A-D), the
// option's force (E) and its distribution to the face nodes, the correction passes of the
// velocity-constraint options (10.8) and the time-step limit (19). The checks and the contact
// energy are in ContactFinish.cpp.
#include "contact/ContactSystem.hpp"
#include "contact/ContactKernels.hpp"
#include "contact/JointConstraints.hpp"

#include <cmath>
#include <sstream>

namespace scpdyn
{
using namespace contact_kernels;

void ContactSystem::computeVstar(const NodeFields &nodes, const BoundaryConditions &bcs, Real dt)
{
  auto used = _faces.nodes_used;
  auto v = nodes.v, f_int = nodes.f_int, f_ext = nodes.f_ext, vstar = _vstar, fc = _fc, dv = _dv;
  auto mass = nodes.mass;
  auto bc = nodes.bc;
  auto vbc = bcs.velocity_current;
  const int dim = _dim;
  // (10.6) v* = v + dt F/M with every force assembled before step 9 (internal, hourglass,
  // body); prescribed components take their prescribed value (10.1)
  Kokkos::parallel_for(
      "scpdyn::contact::vstar", Kokkos::RangePolicy<ExecSpace>(0, Index(used.extent(0))),
      KOKKOS_LAMBDA(const Index i) {
        const Index k = used(i);
        for (int d = 0; d < 3; ++d)
        {
          fc(k, d) = 0;
          dv(k, d) = 0;
          if (d >= dim)
            vstar(k, d) = 0;
          else if (bc(k, d) >= 0)
            vstar(k, d) = vbc(bc(k, d));
          else
            vstar(k, d) = v(k, d) + dt * (f_int(k, d) + f_ext(k, d)) / mass(k);
        }
      });
}

void ContactSystem::velocitiesSet()
{
  auto state = _cp.state;
  Kokkos::parallel_for(
      "scpdyn::contact::velocitiesSet", Kokkos::RangePolicy<ExecSpace>(0, _cp.count),
      KOKKOS_LAMBDA(const Index p) { state(p).dt_model = 0; });
}

void ContactSystem::jointForces(const NodeFields &nodes, Real dt)
{
  const ContactFaceData F = _faces;
  const CommonPlaneData cp = _cp;
  auto x = nodes.x, v = nodes.v, vstar = _vstar, fc = _fc;
  auto mass = nodes.mass;
  auto bc = nodes.bc;
  const VectorView no_dv;
  const int dim = _dim, Q = _tie_points;
  const bool axisym = _axisym;
  const Real half_dt = 0.5 * dt;
  const TieWeights tie = _tie;
  const NodeAdder add = nodeAdder();
  const NodeSlotRows *rows = slotRows(1, _share_rows);
  const bool gather = rows != nullptr;
  const VectorView share = gather ? rows->share : VectorView();
  Kokkos::parallel_for(
      "scpdyn::contact::planeForces", Kokkos::RangePolicy<ExecSpace>(0, cp.count),
      KOKKOS_LAMBDA(const Index p) {
        if (gather) // a CP that returns before its force gives its nodes nothing
          clearShares(share, p, p + 1);
        const Index f1 = cp.face1(p), f2 = cp.face2(p);
        const JointParams &P = cp.params(p);
        CpState s = cp.state(p);
        Real x1[kMaxFaceNodes][3], x2[kMaxFaceNodes][3];
        const CpGeometry g =
            pairGeometry(F, f1, f2, x, v, half_dt, dim, axisym, x1, x2, usesImpactNormal(P.option));
        // (10): v^n for the explicit option, v* for the options that use m*
        const VectorView &vel = P.option == ContactOption::Explicit ? v : vstar;
        const Real *n = g.valid ? g.n : s.n_old;
        for (int d = 0; d < 3; ++d)
        {
          cp.normal(p, d) = n[d];
          cp.poc(p, d) = g.x_poc[d];
          cp.force(p, d) = 0;
        }
        cp.face_area1(p) = g.A1;
        cp.face_area2(p) = g.A2;
        cp.stored(p) = 0;
        Real V1[3], V2[3], Vrel[3], Vn = 0;
        if (!cpIsActive(g))
        { // (3.4) inactive: no force, only n_old and u move
          faceVelocity(F, f1, vel, V1);
          faceVelocity(F, f2, vel, V2);
          for (int d = 0; d < 3; ++d)
            Vn += (V1[d] - V2[d]) * n[d];
          updateInactiveCp(s, n, Vn, dt);
          cp.state(p) = s;
          cp.area(p) = 0;
          cp.status(p) = CpInactive;
          for (int a = 0; a < kMaxFaceNodes; ++a)
            cp.w1(p, a) = cp.w2(p, a) = 0;
          return;
        }
        cp.area(p) = g.Ac;
        const Real mstar =
            reducedMass(g.f1, F.mass(f1), F.rigid(f1) != 0, g.f2, F.mass(f2), F.rigid(f2) != 0);
        cp.mstar(p) = mstar;
        // A velocity constraint ties faces that touch to round-off, where node penetrations
        // are noise: its force (and its face velocities) always use the shape functions at
        // the POC (8.2); otherwise the weights flip between nodes and drive the relative
        // zigzag mode of the two faces, which the face-average constraint cannot see.
        const DistributionRule rule =
            isConstraint(P.option) ? DistributionRule::Poc : P.distribution;
        // blend length of the penetration weights (8.1, CommonPlaneGeometry.hpp): the relative
        // displacement the last force gives the reduced mass in one step from rest
        const Real F_old = kmath::sqrt(s.Fn * s.Fn + contact_math::dot(s.Fs, s.Fs));
        const Real blend = 0.5 * dt * dt * F_old / mstar;
        Real w[kMaxFaceNodes];
        nodalWeights(x1, F.num_nodes(f1), g, 1, rule, w, blend);
        for (int a = 0; a < kMaxFaceNodes; ++a)
          cp.w1(p, a) = a < F.num_nodes(f1) ? w[a] : 0;
        nodalWeights(x2, F.num_nodes(f2), g, 2, rule, w, blend);
        for (int a = 0; a < kMaxFaceNodes; ++a)
          cp.w2(p, a) = a < F.num_nodes(f2) ? w[a] : 0;
        cp.status(p) = CpStick;
        if (isConstraint(P.option))
        { // forces come from the correction passes, at the tie points (2D sticky) or the POC
          Real tw1[2][kMaxFaceNodes] = {}, tw2[2][kMaxFaceNodes] = {};
          const bool two_points = isTie(P, s) && dim == 2;
          if (two_points)
            tieWeights2D(x1, x2, g, tw1, tw2);
          for (int q = 0; q < Q; ++q)
            for (int a = 0; a < kMaxFaceNodes; ++a)
            {
              tie.w1(p * Q + q, a) = two_points ? tw1[q][a] : q == 0 ? cp.w1(p, a) : 0.0;
              tie.w2(p * Q + q, a) = two_points ? tw2[q][a] : q == 0 ? cp.w2(p, a) : 0.0;
            }
          return;
        }
        cpVelocities(F, cp, p, P.velocity, vel, V1, V2);
        for (int d = 0; d < 3; ++d)
        {
          Vrel[d] = V1[d] - V2[d];
          Vn += Vrel[d] * n[d];
        }
        CpKinematics k;
        for (int d = 0; d < 3; ++d)
        {
          k.n[d] = n[d];
          k.Vs[d] = Vrel[d];
          k.Fint_s[d] = 0; // velocity-correction variant (10.6)
        }
        k.Vn = Vn;
        k.Ac = g.Ac;
        k.dt = dt;
        k.mstar = mstar;
        k.Fint_n = 0;
        if (P.option == ContactOption::Implicit && s.dt_model > 0)
        { // The model masses predicted last step's end velocity; the mesh moved otherwise, and
          // the difference is closure and shear the joint has not seen. Feed it into this
          // step's increments (B of (20) and the shear increment), where the inertia of the
          // model damps it: without it u and Fs drift from the real kinematics wherever the CP
          // forces vary from face to face (a block on an incline creeps and rocks into its base).
          Real Va1[3], Va2[3];
          cpVelocities(F, cp, p, P.velocity, v, Va1, Va2);
          Real vn = 0;
          for (int d = 0; d < 3; ++d)
          {
            const Real corr = (Va1[d] - Va2[d] - s.V_model[d]) * s.dt_model / dt;
            k.Vs[d] += corr;
            vn += corr * n[d];
          }
          k.Vn += vn;
        }
        const CpStepResult r =
            P.option == ContactOption::Explicit ? updateExplicit(P, s, k) : updateImplicit(P, s, k);
        if (P.option == ContactOption::Implicit)
        { // the model's end-of-step relative velocity (10.2): V' = V* - dt F'/m*
          for (int d = 0; d < 3; ++d)
            s.V_model[d] = Vrel[d] - dt * (r.Fn * n[d] + r.Fs[d]) / mstar;
          s.dt_model = dt;
        }
        Real Fv[3];
        for (int d = 0; d < 3; ++d)
        {
          Fv[d] = r.Fn * n[d] + r.Fs[d];
          cp.force(p, d) = Fv[d];
        }
        if (gather)
          shareForce(F, cp, p, Fv, share, dim);
        else
          scatterForce(F, cp, p, Fv, fc, no_dv, mass, bc, dt, dim, add);
        cp.stored(p) = scpdyn::storedEnergy(P, s.Fn, s.Fs, s.umax, g.Ac);
        cp.status(p) = s.open ? CpOpen : r.slipped ? CpSlip : CpStick;
        cp.state(p) = s;
      });
  if (gather)
    assembleSlots(*rows, fc, false);
}

ContactFailure ContactSystem::computeForces(const NodeFields &nodes, const BoundaryConditions &bc,
                                            Real dt, long cycle, Real time)
{
  // decomposed: every rank takes every collective step, with or without faces and CPs
  const bool decomposed = bool(_comm.sum);
  if (_faces.count == 0 && !decomposed)
    return ContactFailure();
  if (searchDue(cycle))
  {
    if (_binned_cycle != cycle)
      sortIntoBins(nodes, dt, cycle);
    detect(nodes, dt);
    ++_searches;
  }
  computeVstar(nodes, bc, dt);
  if (_state_before.extent(0) != _cp.state.extent(0))
    _state_before = DeviceView<CpState *>("cp_state_before", _cp.state.extent(0));
  Kokkos::deep_copy(_state_before, _cp.state);
  if (_has_sleepy) // after the copy: the energy check books a CP failing now as a tie before
    releaseSleepy(time);
  if (_cp.count > 0 || decomposed)
  {
    if (constraintsLive())
      allocateTieRows();
    jointForces(nodes, dt);
    if (_has_explicit)
      recordApproach(nodes);
    if (constraintsLive())
      constraintPasses(nodes, dt);
  }
  return finish(nodes, dt, cycle, time);
}

void ContactSystem::recordApproach(const NodeFields &nodes)
{
  if (_approach.extent(0) < size_t(_cp.count))
    _approach = RealView("cp_approach", size_t(_cp.count));
  const ContactFaceData F = _faces;
  const CommonPlaneData cp = _cp;
  auto v = nodes.v;
  auto approach = _approach;
  Kokkos::parallel_for(
      "scpdyn::contact::approach", Kokkos::RangePolicy<ExecSpace>(0, cp.count),
      KOKKOS_LAMBDA(const Index p) {
        Real V1[3], V2[3], Vn = 0;
        cpVelocities(F, cp, p, cp.params(p).velocity, v, V1, V2);
        for (int d = 0; d < 3; ++d)
          Vn += (V1[d] - V2[d]) * cp.normal(p, d);
        approach(p) = Vn;
      });
}

Real ContactSystem::stableTimeStep(const NodeFields &nodes, const ElementFields &elements,
                                   Real dt_element) const
{
  (void)nodes;
  if (!_has_explicit || _cp.count == 0)
    return 1e300;
  const ContactFaceData F = _faces;
  const CommonPlaneData cp = _cp;
  auto approach = _approach;
  auto emass = elements.mass, volume = elements.volume;
  Real dt_min = 1e300;
  Kokkos::parallel_reduce(
      "scpdyn::contact::timeStep", Kokkos::RangePolicy<ExecSpace>(0, cp.count),
      KOKKOS_LAMBDA(const Index p, Real &m) {
        const JointParams &P = cp.params(p);
        if (P.option != ContactOption::Explicit || cp.status(p) == CpInactive)
          return;
        const Index f1 = cp.face1(p), f2 = cp.face2(p);
        const Real dt_c =
            explicitCpTimeStep(F, P, cp.state(p), f1, f2, cp.face_area1(p), cp.face_area2(p),
                               approach(p), emass, volume, dt_element);
        m = dt_c < m ? dt_c : m;
      },
      Kokkos::Min<Real>(dt_min));
  return dt_min;
}

} // namespace scpdyn
