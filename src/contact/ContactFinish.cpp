// The end of step 9 (docs/theory.md 6.7, 3.4): the divergence checks, then the contact forces and
// their work applied. A failure restores the CP histories and applies nothing, so the outputs
// written afterwards hold the last finite state.
#include "contact/ContactChecks.hpp"
#include "contact/ContactKernels.hpp"
#include "contact/JointConstraints.hpp"
#include "contact/ContactSystem.hpp"

#include <cmath>
#include <sstream>

namespace scpdyn
{
using namespace contact_kernels;

namespace
{

/// What a user can do about a diverged CP of option `P`.
std::string advice(const JointParams &P)
{
  if (P.option == ContactOption::SlideLine)
    return "; a slide line can only take energy out: its constraint solve did not hold (raise "
           "contact.constraint_passes)";
  if (P.option != ContactOption::Explicit)
    return "; the joint is loaded beyond its law's range: check E0, a and Emax";
  return std::string("; the explicit contact is unstable at this time step") +
         (P.C_safe > 1e30 ? " with its limit switched off (C_safe: off): set C_safe (0.5) or "
                            "reduce time.courant"
                          : ": reduce C_safe or time.courant");
}

} // namespace

ContactFailure ContactSystem::finish(const NodeFields &nodes, Real dt, long cycle, Real time)
{
  const CommonPlaneData cp = _cp;
  auto used = _faces.nodes_used;
  auto v = nodes.v, f_contact = nodes.f_contact, fc = _fc, impulse = _impulse;
  const int dim = _dim;
  const Index nused = Index(used.extent(0));

  // the cycle's contact work, booked on the leapfrog's own terms
  // 1/2 v^n.(F^{n+1/2} dt_n + F^{n-1/2} dt_{n-1}) like the external work, so the energy balance
  // closes with contact = stored + dissipated
  // decomposed with the shared nodes' forces whole on every copy: counted on their owner
  Real work = 0, stored = 0;
  auto copy = _copy_node;
  Kokkos::parallel_reduce(
      "scpdyn::contact::work", Kokkos::RangePolicy<ExecSpace>(0, nused),
      KOKKOS_LAMBDA(const Index i, Real &w) {
        const Index k = used(i);
        if (!contact_kernels::countsNodeWork(copy, k))
          return;
        for (int d = 0; d < dim; ++d)
          w -= 0.5 * v(k, d) * (fc(k, d) * dt + impulse(k, d));
      },
      work);
  auto st = cp.stored;
  const ContactFaceData F = _faces;
  // decomposed: a CP computed on two ranks counts on the rank of its face 1
  Kokkos::parallel_reduce(
      "scpdyn::contact::stored", Kokkos::RangePolicy<ExecSpace>(0, cp.count),
      KOKKOS_LAMBDA(const Index p, Real &s) {
        if (ownsPlane(F, cp, p))
          s += st(p);
      },
      stored);

  // per CP: non-finite force or history, a closure past kDivergedClosure apertures
  Index bad = cp.count;
  Kokkos::parallel_reduce(
      "scpdyn::contact::check", Kokkos::RangePolicy<ExecSpace>(0, cp.count),
      KOKKOS_LAMBDA(const Index p, Index &first) {
        const JointParams &P = cp.params(p);
        const Real F[3] = {cp.force(p, 0), cp.force(p, 1), cp.force(p, 2)};
        const int c =
            checkCp(P, cp.state(p), F, !isConstraint(P.option), cp.status(p) != CpInactive,
                    cp.area(p), cp.face_area1(p), cp.face_area2(p));
        if (c != CpCheckOk && p < first)
          first = p;
      },
      Kokkos::Min<Index>(bad));
  // energy test on the joint and slide-line CPs: their net work this cycle, booked per CP like the nodal
  // work above, 1/2 (V1 - V2)^n.(F^{n+1/2} dt_n + F^{n-1/2} dt_{n-1}) (the previous force from
  // the histories at the start of step 9; the weights of this cycle)
  if (_cp_work.extent(0) < size_t(cp.count))
  {
    _cp_work = RealView("cp_work", size_t(cp.count));
    _cp_carried = RealView("cp_carried", size_t(cp.count));
  }
  auto cp_work = _cp_work, cp_carried = _cp_carried;
  auto before = _state_before;
  const Real dt_prev = _dt_prev;
  Kokkos::parallel_for(
      "scpdyn::contact::jointWork", Kokkos::RangePolicy<ExecSpace>(0, cp.count),
      KOKKOS_LAMBDA(const Index p) {
        const JointParams &P = cp.params(p);
        cp_work(p) = 0;
        cp_carried(p) = 0;
        if (isTie(P, cp.state(p)))
          return; // a tie does no work: its booked work is round-off and lag of either sign
        Real V1[3], V2[3], w = 0, carried = 0;
        cpVelocities(F, cp, p, P.velocity, v, V1, V2);
        const CpState &o = before(p);
        // a sleepy CP that fails this cycle: its last impulse was a tie's, which does no work
        const Real booked = isTie(P, o) ? 0.0 : 1.0;
        for (int d = 0; d < 3; ++d)
        {
          const Real I_old = booked * (o.Fn * o.n_old[d] + o.Fs[d]) * dt_prev;
          w += 0.5 * (V1[d] - V2[d]) * (cp.force(p, d) * dt + I_old);
          carried += 0.25 * (V1[d] + V2[d]) * (cp.force(p, d) * dt + I_old);
        }
        cp_work(p) = w;
        cp_carried(p) = carried < 0 ? -carried : carried;
      });
  Real joint_work = 0, gross = 0;
  Kokkos::parallel_reduce(
      "scpdyn::contact::jointWorkSum", Kokkos::RangePolicy<ExecSpace>(0, cp.count),
      KOKKOS_LAMBDA(const Index p, Real &sum) {
        if (ownsPlane(F, cp, p) && !isConstraint(cp.params(p).option))
          sum += cp_work(p);
      },
      joint_work);
  Kokkos::parallel_reduce(
      "scpdyn::contact::jointWorkGross", Kokkos::RangePolicy<ExecSpace>(0, cp.count),
      KOKKOS_LAMBDA(const Index p, Real &sum) {
        if (ownsPlane(F, cp, p) && !isConstraint(cp.params(p).option))
          sum += cp_work(p) < 0 ? -cp_work(p) : cp_work(p);
      },
      gross);
  // slide lines: their net work; the work they carry from one body to the other, the scale of
  // the solve's round-off; and the kinetic energy of the contact nodes, the scale of the
  // leapfrog lag of either sign that persistent contact books (a quasi-static patch: 1e-20 J)
  Real slide_work = 0, slide_carried = 0, ke_contact = 0;
  if (slideLinesLive() || _has_sleepy)
  {
    Kokkos::parallel_reduce(
        "scpdyn::contact::slideWorkSum", Kokkos::RangePolicy<ExecSpace>(0, cp.count),
        KOKKOS_LAMBDA(const Index p, Real &sum) {
          if (ownsPlane(F, cp, p) && isSlide(cp.params(p), cp.state(p)))
            sum += cp_work(p);
        },
        slide_work);
    Kokkos::parallel_reduce(
        "scpdyn::contact::slideCarriedSum", Kokkos::RangePolicy<ExecSpace>(0, cp.count),
        KOKKOS_LAMBDA(const Index p, Real &sum) {
          if (ownsPlane(F, cp, p) && isSlide(cp.params(p), cp.state(p)))
            sum += cp_carried(p);
        },
        slide_carried);
    auto mass = nodes.mass;
    Kokkos::parallel_reduce(
        "scpdyn::contact::contactNodeEnergy", Kokkos::RangePolicy<ExecSpace>(0, nused),
        KOKKOS_LAMBDA(const Index i, Real &sum) {
          const Index k = used(i);
          for (int d = 0; d < dim; ++d)
            sum += 0.5 * mass(k) * v(k, d) * v(k, d);
        },
        ke_contact);
  }
  // the energy test is on the whole model (decomposed: the sums over the ranks)
  Real sums[7] = {joint_work, gross, stored, Real(cp.count), slide_work, ke_contact, slide_carried};
  if (_comm.sum)
    _comm.sum(sums, 7);
  const Real jw = _joint_work + sums[0];
  const Real jw_peak = std::max(_joint_work_peak, jw);
  const Real stored_peak = std::max(_stored_peak, sums[2]);
  const Real jw_gross = _joint_work_gross + sums[1];
  const Real sw = _slide_work + sums[4];
  const Real sw_peak = std::max(_slide_work_peak, sw);
  const Real sw_carried = _slide_carried + sums[6];
  const bool slide_created =
      (slideLinesLive() || _has_sleepy) &&
      contactCreatedEnergy(sw, sw_peak + kSlideLag * sums[5] + kSlideRoundOff * sw_carried, 0, 0);
  const bool created = bad >= cp.count && sums[3] > 0 &&
                       (contactCreatedEnergy(jw, jw_peak, stored_peak, jw_gross) || slide_created);
  if (created)
  { // name the CP that gave the mesh the most energy this cycle
    Kokkos::MinLoc<Real, Index>::value_type least;
    Kokkos::parallel_reduce(
        "scpdyn::contact::release", Kokkos::RangePolicy<ExecSpace>(0, cp.count),
        KOKKOS_LAMBDA(const Index p, Kokkos::MinLoc<Real, Index>::value_type &m) {
          if (cp_work(p) < m.val || (cp_work(p) == m.val && p < m.loc))
            m.val = cp_work(p), m.loc = p;
        },
        Kokkos::MinLoc<Real, Index>(least));
    bad = least.loc >= 0 && least.loc < cp.count ? least.loc : 0;
  }

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
    os << "contact diverged at cycle " << cycle << ", time " << time << " s (dt " << dt << " s): ";
    bool finite = std::isfinite(s.u) && std::isfinite(s.Fn);
    for (int d = 0; d < 3; ++d)
      finite = finite && std::isfinite(force(bad, d)) && std::isfinite(s.Fs[d]);
    if (created && slide_created)
      os << "the slide lines gave the mesh " << -sw << " J net (more than the most they ever "
         << "took in, " << sw_peak << " J): energy created, most of it this cycle at "
         << describe(bad);
    else if (created)
      os << "the joints gave the mesh " << -jw << " J net (more than the most they ever took in, "
         << jw_peak << " J, or held, " << stored_peak << " J): energy created, most of it "
         << "this cycle at " << describe(bad);
    else if (!finite)
      os << describe(bad) << " has a non-finite force or closure";
    else
      os << describe(bad) << ": closure u - u_z = " << s.u - s.u_z << " m passed "
         << kDivergedClosure << " apertures (a = " << P.a << " m; normal stress "
         << s.Fn / area(bad) << " Pa)";
    ContactFailure failure;
    failure.failed = true;
    failure.message = os.str() + advice(P);
    Kokkos::deep_copy(cp.state, _state_before);
    return failure;
  }

  Kokkos::parallel_for(
      "scpdyn::contact::apply", Kokkos::RangePolicy<ExecSpace>(0, nused),
      KOKKOS_LAMBDA(const Index i) {
        const Index k = used(i);
        for (int d = 0; d < dim; ++d)
        {
          f_contact(k, d) = fc(k, d);
          impulse(k, d) = fc(k, d) * dt;
        }
      });
  _work += work;
  _stored = stored;
  _joint_work = jw;
  _joint_work_peak = jw_peak;
  _joint_work_gross = jw_gross;
  _slide_work = sw;
  _slide_work_peak = sw_peak;
  _slide_carried = sw_carried;
  _stored_peak = stored_peak;
  _dt_prev = dt;
  return ContactFailure();
}

} // namespace scpdyn
