// Step 9 of the cycle for every CP (scp-method.md Appendix A): half-step geometry (A-D), the
// option's force (E) and its distribution to the face nodes, the correction passes of the
// velocity-constraint options (10.8), the checks, the contact energy and the time-step limit (19).
#include "contact/ContactSystem.hpp"
#include "contact/JointConstraints.hpp"

#include <cmath>
#include <sstream>

namespace scpdyn
{
namespace
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
  return o == ContactOption::SlideLine || o == ContactOption::Sticky ||
         o == ContactOption::Sleepy;
}

/// (17)-(18): -w1 F on the nodes of face 1, +w2 F on face 2; with `dv`, also the velocity
/// change dt F w / M of every node component that is not prescribed.
KOKKOS_INLINE_FUNCTION void scatterForce(const ContactFaceData &F, const CommonPlaneData &cp,
                                         Index p, const Real Fv[3], const VectorView &fc,
                                         const VectorView &dv, const RealView &mass,
                                         const DeviceView<int * [3]> &bc, Real dt, int dim)
{
  for (int side = 0; side < 2; ++side)
  {
    const Index f = side == 0 ? cp.face1(p) : cp.face2(p);
    const Real sign = side == 0 ? -1.0 : 1.0;
    for (int a = 0; a < F.num_nodes(f); ++a)
    {
      const Index k = F.nodes(f, a);
      const Real w = sign * (side == 0 ? cp.w1(p, a) : cp.w2(p, a));
      for (int d = 0; d < dim; ++d)
      {
        Kokkos::atomic_add(&fc(k, d), w * Fv[d]);
        if (dv.extent(0) > 0 && bc(k, d) < 0)
          Kokkos::atomic_add(&dv(k, d), w * Fv[d] * dt / mass(k));
      }
    }
  }
}

} // namespace

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

void ContactSystem::jointForces(const NodeFields &nodes, Real dt)
{
  const ContactFaceData F = _faces;
  const CommonPlaneData cp = _cp;
  auto x = nodes.x, v = nodes.v, vstar = _vstar, fc = _fc;
  auto mass = nodes.mass;
  auto bc = nodes.bc;
  const VectorView no_dv;
  const int dim = _dim;
  const bool axisym = _axisym;
  const Real half_dt = 0.5 * dt;
  Kokkos::parallel_for(
      "scpdyn::contact::planeForces", Kokkos::RangePolicy<ExecSpace>(0, cp.count),
      KOKKOS_LAMBDA(const Index p) {
        const Index f1 = cp.face1(p), f2 = cp.face2(p);
        const JointParams &P = cp.params(p);
        CpState s = cp.state(p);
        Real x1[kMaxFaceNodes][3], x2[kMaxFaceNodes][3];
        const CpGeometry g = pairGeometry(F, f1, f2, x, v, half_dt, dim, axisym, x1, x2);
        // (10): v^n for the explicit option, v* for the options that use m*
        const VectorView &vel = P.option == ContactOption::Explicit ? v : vstar;
        Real V1[3], V2[3], Vrel[3];
        faceVelocity(F, f1, vel, V1);
        faceVelocity(F, f2, vel, V2);
        const Real *n = g.valid ? g.n : s.n_old;
        Real Vn = 0;
        for (int d = 0; d < 3; ++d)
        {
          Vrel[d] = V1[d] - V2[d];
          Vn += Vrel[d] * n[d];
          cp.normal(p, d) = n[d];
          cp.poc(p, d) = g.x_poc[d];
          cp.force(p, d) = 0;
        }
        cp.face_area1(p) = g.A1;
        cp.face_area2(p) = g.A2;
        cp.stored(p) = 0;
        if (!cpIsActive(g))
        { // (3.4) inactive: no force, only n_old and u move
          updateInactiveCp(s, n, Vn, dt);
          cp.state(p) = s;
          cp.area(p) = 0;
          cp.status(p) = CpInactive;
          for (int a = 0; a < kMaxFaceNodes; ++a)
            cp.w1(p, a) = cp.w2(p, a) = 0;
          return;
        }
        cp.area(p) = g.Ac;
        const Real mstar = reducedMass(g.f1, F.mass(f1), F.rigid(f1) != 0, g.f2, F.mass(f2),
                                       F.rigid(f2) != 0);
        cp.mstar(p) = mstar;
        Real w[kMaxFaceNodes];
        nodalWeights(x1, F.num_nodes(f1), g, 1, P.distribution, w);
        for (int a = 0; a < kMaxFaceNodes; ++a)
          cp.w1(p, a) = a < F.num_nodes(f1) ? w[a] : 0;
        nodalWeights(x2, F.num_nodes(f2), g, 2, P.distribution, w);
        for (int a = 0; a < kMaxFaceNodes; ++a)
          cp.w2(p, a) = a < F.num_nodes(f2) ? w[a] : 0;
        cp.status(p) = CpStick;
        if (isConstraint(P.option))
          return; // forces come from the correction passes
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
        const CpStepResult r =
            P.option == ContactOption::Explicit ? updateExplicit(P, s, k) : updateImplicit(P, s, k);
        Real Fv[3];
        for (int d = 0; d < 3; ++d)
        {
          Fv[d] = r.Fn * n[d] + r.Fs[d];
          cp.force(p, d) = Fv[d];
        }
        scatterForce(F, cp, p, Fv, fc, no_dv, mass, bc, dt, dim);
        cp.stored(p) = scpdyn::storedEnergy(P, s.Fn, s.Fs, s.umax, g.Ac);
        cp.status(p) = s.open ? CpOpen : r.slipped ? CpSlip : CpStick;
        cp.state(p) = s;
      });
}

void ContactSystem::constraintPasses(const NodeFields &nodes, Real dt)
{
  const ContactFaceData F = _faces;
  const CommonPlaneData cp = _cp;
  auto vstar = _vstar, fc = _fc, dv = _dv;
  auto mass = nodes.mass;
  auto bc = nodes.bc;
  auto used = _faces.nodes_used;
  const int dim = _dim;
  const Index nused = Index(used.extent(0));
  // the joint CPs' forces are part of what the constraints see
  Kokkos::parallel_for(
      "scpdyn::contact::vstarJoints", Kokkos::RangePolicy<ExecSpace>(0, nused),
      KOKKOS_LAMBDA(const Index i) {
        const Index k = used(i);
        for (int d = 0; d < dim; ++d)
          if (bc(k, d) < 0)
            vstar(k, d) += dt * fc(k, d) / mass(k);
      });
  // (10.8): Jacobi passes. Each pass computes every constraint CP's extra force from the v* left
  // by the previous one, so nodes shared by several CPs (corners, T-junctions) converge instead
  // of being over-corrected once.
  Real first = 0;
  for (int pass = 0; pass < _passes; ++pass)
  {
    Real largest = 0;
    Kokkos::parallel_reduce(
        "scpdyn::contact::constraintPass", Kokkos::RangePolicy<ExecSpace>(0, cp.count),
        KOKKOS_LAMBDA(const Index p, Real &dv_max) {
          const JointParams &P = cp.params(p);
          if (!isConstraint(P.option) || cp.status(p) == CpInactive)
            return;
          const Index f1 = cp.face1(p), f2 = cp.face2(p);
          Real V1[3], V2[3], dF[3];
          faceVelocity(F, f1, vstar, V1);
          faceVelocity(F, f2, vstar, V2);
          const Real ms = cp.mstar(p);
          if (P.option == ContactOption::Sticky)
            for (int d = 0; d < 3; ++d) // (25) with (24): F = m*(V1 - V2)/dt
              dF[d] = ms * (V1[d] - V2[d]) / dt;
          else
          { // (D14): stop the approach beyond the gap, no tension, no shear
            Real Vn = 0, Fn = 0;
            for (int d = 0; d < 3; ++d)
            {
              Vn += (V1[d] - V2[d]) * cp.normal(p, d);
              Fn += cp.force(p, d) * cp.normal(p, d);
            }
            const Real gap = cp.state(p).u < 0 ? -cp.state(p).u : 0.0;
            const Real Fn_new = ContactMath::max(0.0, Fn + ms * (Vn - gap / dt) / dt);
            for (int d = 0; d < 3; ++d)
              dF[d] = (Fn_new - Fn) * cp.normal(p, d);
          }
          Real mag = 0;
          for (int d = 0; d < 3; ++d)
          {
            cp.force(p, d) += dF[d];
            mag += dF[d] * dF[d];
          }
          scatterForce(F, cp, p, dF, fc, dv, mass, bc, dt, dim);
          const Real dvel = kmath::sqrt(mag) * dt / ms;
          dv_max = dvel > dv_max ? dvel : dv_max;
        },
        Kokkos::Max<Real>(largest));
    Kokkos::parallel_for(
        "scpdyn::contact::constraintApply", Kokkos::RangePolicy<ExecSpace>(0, nused),
        KOKKOS_LAMBDA(const Index i) {
          const Index k = used(i);
          for (int d = 0; d < 3; ++d)
          {
            vstar(k, d) += dv(k, d);
            dv(k, d) = 0;
          }
        });
    if (pass == 0)
      first = largest;
    if (!(largest > 1e-12 * first))
      break;
  }
  Kokkos::parallel_for(
      "scpdyn::contact::constraintFinish", Kokkos::RangePolicy<ExecSpace>(0, cp.count),
      KOKKOS_LAMBDA(const Index p) {
        const JointParams &P = cp.params(p);
        if (!isConstraint(P.option) || cp.status(p) == CpInactive)
          return;
        CpState s = cp.state(p);
        Real V1[3], V2[3], Vn = 0, Fn = 0;
        faceVelocity(F, cp.face1(p), vstar, V1);
        faceVelocity(F, cp.face2(p), vstar, V2);
        for (int d = 0; d < 3; ++d)
        {
          Vn += (V1[d] - V2[d]) * cp.normal(p, d);
          Fn += cp.force(p, d) * cp.normal(p, d);
        }
        s.u += dt * Vn; // the model's end-of-step closure rate
        s.umax = ContactMath::max(s.umax, s.u);
        s.Fn = Fn;
        for (int d = 0; d < 3; ++d)
        {
          s.Fs[d] = cp.force(p, d) - Fn * cp.normal(p, d);
          s.n_old[d] = cp.normal(p, d);
        }
        s.Ac_old = cp.area(p);
        cp.state(p) = s;
        if (P.option == ContactOption::SlideLine && !(Fn > 0))
          cp.status(p) = CpOpen;
      });
}

ContactFailure ContactSystem::finish(const NodeFields &nodes, Real dt, long cycle, Real time)
{
  ContactFailure failure;
  const CommonPlaneData cp = _cp;
  Index bad = cp.count;
  Kokkos::parallel_reduce(
      "scpdyn::contact::check", Kokkos::RangePolicy<ExecSpace>(0, cp.count),
      KOKKOS_LAMBDA(const Index p, Index &first) {
        const JointParams &P = cp.params(p);
        bool ok = true;
        for (int d = 0; d < 3; ++d)
        {
          const Real f = cp.force(p, d);
          ok = ok && f - f == 0; // false for NaN and infinity
        }
        if (!isConstraint(P.option) && cp.status(p) != CpInactive && !(cp.state(p).u <= P.a))
          ok = false; // closure past the aperture: diverging (or loaded beyond ~200 E0)
        if (!ok && p < first)
          first = p;
      },
      Kokkos::Min<Index>(bad));
  if (bad < cp.count)
  {
    auto state = Kokkos::create_mirror_view_and_copy(HostSpace(), Kokkos::subview(cp.state, bad));
    auto params = Kokkos::create_mirror_view_and_copy(HostSpace(), Kokkos::subview(cp.params, bad));
    auto force = Kokkos::create_mirror_view_and_copy(HostSpace(), cp.force);
    auto area = Kokkos::create_mirror_view_and_copy(HostSpace(), cp.area);
    const CpState &s = state();
    const JointParams &P = params();
    std::ostringstream os;
    os.precision(4);
    os << "contact diverged at cycle " << cycle << ", time " << time << " s (dt " << dt << " s): "
       << describe(bad);
    const bool finite = std::isfinite(force(bad, 0)) && std::isfinite(force(bad, 1)) &&
                        std::isfinite(force(bad, 2));
    if (!finite)
      os << " has a non-finite force";
    else
      os << ": closure u = " << s.u << " m passed the aperture a = " << P.a
         << " m (normal stress " << s.Fn / (area(bad) > 0 ? area(bad) : 1.0) << " Pa)";
    if (P.option == ContactOption::Explicit)
      os << "; the explicit contact is unstable at this time step"
         << (P.C_safe > 1e30 ? " with its limit switched off (C_safe: off): set C_safe (0.5) or "
                               "reduce time.courant"
                             : ": reduce C_safe or time.courant");
    else
      os << "; the joint is loaded beyond its law's range: check E0, a and Emax";
    failure.failed = true;
    failure.message = os.str();
    return failure;
  }

  // apply: contact forces are internal to the system (f_int); their work, booked on the
  // leapfrog's own terms 1/2 v^n.(F^{n+1/2} dt_n + F^{n-1/2} dt_{n-1}) like the external work,
  // is the contact energy, so the energy balance closes with contact = stored + dissipated
  auto used = _faces.nodes_used;
  auto v = nodes.v, f_int = nodes.f_int, fc = _fc, impulse = _impulse;
  const int dim = _dim;
  Real work = 0;
  Kokkos::parallel_reduce(
      "scpdyn::contact::apply", Kokkos::RangePolicy<ExecSpace>(0, Index(used.extent(0))),
      KOKKOS_LAMBDA(const Index i, Real &w) {
        const Index k = used(i);
        for (int d = 0; d < dim; ++d)
        {
          f_int(k, d) += fc(k, d);
          const Real I = fc(k, d) * dt;
          w -= 0.5 * v(k, d) * (I + impulse(k, d));
          impulse(k, d) = I;
        }
      },
      work);
  _work += work;
  Real stored = 0;
  auto st = cp.stored;
  Kokkos::parallel_reduce(
      "scpdyn::contact::stored", Kokkos::RangePolicy<ExecSpace>(0, cp.count),
      KOKKOS_LAMBDA(const Index p, Real &s) { s += st(p); }, stored);
  _stored = stored;
  return failure;
}

ContactFailure ContactSystem::computeForces(const NodeFields &nodes, const BoundaryConditions &bc,
                                            Real dt, long cycle, Real time)
{
  if (_faces.count == 0)
    return ContactFailure();
  if (searchDue(cycle))
  {
    if (_binned_cycle != cycle)
      sortIntoBins(nodes, dt, cycle);
    detect(nodes, dt);
  }
  computeVstar(nodes, bc, dt);
  if (_cp.count > 0)
  {
    jointForces(nodes, dt);
    if (_has_constraints)
      constraintPasses(nodes, dt);
  }
  return finish(nodes, dt, cycle, time);
}

Real ContactSystem::stableTimeStep(const NodeFields &nodes, const ElementFields &elements,
                                   Real dt_element) const
{
  if (!_has_explicit || _cp.count == 0)
    return 1e300;
  const ContactFaceData F = _faces;
  const CommonPlaneData cp = _cp;
  auto v = nodes.v;
  auto emass = elements.mass, volume = elements.volume;
  Real dt_min = 1e300;
  Kokkos::parallel_reduce(
      "scpdyn::contact::timeStep", Kokkos::RangePolicy<ExecSpace>(0, cp.count),
      KOKKOS_LAMBDA(const Index p, Real &m) {
        const JointParams &P = cp.params(p);
        if (P.option != ContactOption::Explicit || cp.status(p) == CpInactive)
          return;
        const Index f1 = cp.face1(p), f2 = cp.face2(p);
        Real V1[3], V2[3], Vn = 0;
        faceVelocity(F, f1, v, V1);
        faceVelocity(F, f2, v, V2);
        for (int d = 0; d < 3; ++d)
          Vn += (V1[d] - V2[d]) * cp.normal(p, d);
        const Real mu = arealReducedMass(F.mass(f1), cp.face_area1(p), F.rigid(f1) != 0,
                                         F.mass(f2), cp.face_area2(p), F.rigid(f2) != 0);
        const Index e1 = F.element(f1), e2 = F.element(f2);
        const Real rho = 0.5 * (emass(e1) / volume(e1) + emass(e2) / volume(e2));
        const Real dt_c = contactTimeStep(P, cp.state(p), Vn, dt_element, mu, rho);
        m = dt_c < m ? dt_c : m;
      },
      Kokkos::Min<Real>(dt_min));
  return dt_min;
}

} // namespace scpdyn
