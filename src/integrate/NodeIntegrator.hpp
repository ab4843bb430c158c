#pragma once
/// \file NodeIntegrator.hpp
/// \brief Step 12 on one node (the leapfrog, its sums, and the next cycle's step 5), shared by
/// updateNodes() and by the node sweep inside step 6 (integrate/NodeSweep.hpp).
#include "core/Fields.hpp"
#include "integrate/MassDamping.hpp"

namespace scpdyn
{

/// \brief Sums over nodes of one update (reduced in one pass).
struct NodeSums
{
  Real kinetic = 0;       ///< 1/2 sum m |v^{n+1}|^2
  Real kinetic_mid = 0;   ///< 1/2 sum m v^n . v^{n+1} (the leapfrog's conserved kinetic part)
  Real external_work = 0; ///< work of f_ext and constraint reactions over the step, f.v^n dt
  Real damping_work = 0;  ///< work of the settling damping over the step (<= 0), booked alike
  Real momentum[3] = {0, 0, 0};

  KOKKOS_INLINE_FUNCTION NodeSums &operator+=(const NodeSums &o)
  {
    kinetic += o.kinetic;
    kinetic_mid += o.kinetic_mid;
    external_work += o.external_work;
    damping_work += o.damping_work;
    for (int i = 0; i < 3; ++i)
      momentum[i] += o.momentum[i];
    return *this;
  }
  KOKKOS_INLINE_FUNCTION void operator+=(const volatile NodeSums &o) volatile
  {
    kinetic += o.kinetic;
    kinetic_mid += o.kinetic_mid;
    external_work += o.external_work;
    damping_work += o.damping_work;
    for (int i = 0; i < 3; ++i)
      momentum[i] += o.momentum[i];
  }
};

/// \brief The views and step of step 12 (and of step 5 after it), for one node at a time.
///
/// Drift-kick-drift leapfrog (docs/theory.md 2.3): the element step used x^{n+1/2} =
/// x^n + dt/2 v^n; here v^{n+1} = v^n + dt F/M, velocity constraints imposed, and
/// x^{n+1} = x^n + dt/2 (v^n + v^{n+1}), F = (f_int + f_contact) + f_ext, without
/// f_contact unless Contact (a template choice, so the step without contact is compiled as
/// if f_contact did not exist: the same contractions, the same bits). Without Loads, f_ext is +0 (not read) and a node
/// component without a velocity constraint has impulse 0 and previous impulse 0, so its
/// external work term (+-0) is skipped: adding +-0 to the sum, which starts at +0, never
/// changes its bits. With Clear, the node's forces are then set for the next cycle: f_int = 0
/// and, with Loads, f_ext = m g. With Damp, the settling stage's mass damping (`damping`,
/// integrate/MassDamping.hpp) acts on the free components, its impulse kept in
/// `damping_impulse` and its work booked like the external work.
struct NodeIntegrator
{
  VectorView x, v, f_int, f_ext, prev_impulse;
  VectorView f_contact; ///< read with Contact only
  VectorView reaction;  ///< written on the constrained components by run<..., Record = true>
  RealView mass;
  DeviceView<int *[3]> bc;
  RealView vbc;    ///< BoundaryConditions::velocity_current
  IndexView owned; ///< empty: every node counts in the sums
  Real dt = 0, half_dt = 0;
  Real g[3] = {0, 0, 0};      ///< the next cycle's gravity (Clear)
  MassDamping damping;        ///< read with Damp only
  VectorView damping_impulse; ///< last step's damping impulse (Damp) [N s]

  /// The sums of a run of nodes, in local variables that no store to x, v or the impulse can
  /// alias: in a NodeSums in memory, every one of their 9 additions a node went through memory
  /// after each such store (a chain of store-to-load forwards, ~40 % of the step). One partial
  /// sum per component: a node's three terms of a sum do not wait for each other (in the node
  /// sweep of step 6 those chains of dependent adds set the pace).
  template <int Dim>
  struct Sums
  {
    Real external_work[Dim], kinetic[Dim], kinetic_mid[Dim], momentum[Dim], damping_work[Dim];

    KOKKOS_INLINE_FUNCTION Sums()
    {
      for (int i = 0; i < Dim; ++i)
        external_work[i] = kinetic[i] = kinetic_mid[i] = momentum[i] = damping_work[i] = 0;
    }
    /// s plus these partial sums, component 0 first
    KOKKOS_INLINE_FUNCTION void addTo(NodeSums &s) const
    {
      for (int i = 0; i < Dim; ++i)
      {
        s.external_work += external_work[i];
        s.damping_work += damping_work[i];
        s.kinetic += kinetic[i];
        s.kinetic_mid += kinetic_mid[i];
        s.momentum[i] += momentum[i];
      }
    }
  };

  /// Step 5 on node n: f_int = 0, and with loads f_ext = m g (without, f_ext keeps its zero).
  KOKKOS_INLINE_FUNCTION void resetForces(const Index n, const bool loads) const
  {
    for (int i = 0; i < 3; ++i)
      f_int(n, i) = 0;
    if (!loads)
      return;
    const Real m = mass(n);
    for (int i = 0; i < 3; ++i)
      f_ext(n, i) = m * g[i];
  }

  /// Step 12 on node n, its terms added to s (then step 5 on it, with Clear).
  /// Record: write the reactions (an instantiation of its own, so that runs without velocity
  /// constraints keep the code, and the contracted bits, of the others).
  template <int Dim, bool Loads, bool Clear, bool Contact = false, bool Record = false,
            bool Damp = false>
  KOKKOS_INLINE_FUNCTION void integrate(const Index n, Sums<Dim> &s) const
  {
    const Real m = mass(n);
    const Real dt_over_m = dt / m; // one division a node, not one a component
    const bool counted = owned.extent(0) == 0 || owned(n);
    for (int i = 0; i < Dim; ++i)
    {
      const Real v_old = v(n, i);
      const Real fe = Loads ? f_ext(n, i) : Real(0);
      const Real f = (Contact ? f_int(n, i) + f_contact(n, i) : f_int(n, i)) + fe;
      Real v_new = Damp ? damping.velocity(v_old, f * dt_over_m) : v_old + f * dt_over_m;
      Real work_force = fe;
      const int k = bc(n, i);
      if (Damp) // a constrained component is not damped: its constraint sets v^{n+1}
      {
        const Real d = k >= 0 ? Real(0) : damping.impulse(m, v_old, v_new);
        if (counted)
          s.damping_work[i] += 0.5 * v_old * (d + damping_impulse(n, i));
        damping_impulse(n, i) = d;
      }
      if (k >= 0)
      {
        v_new = vbc(k);
        // the constraint's reaction does the work that the velocity change needs
        const Real r = m * (v_new - v_old) / dt - f;
        work_force += r;
        if (Record)
          reaction(n, i) = r;
      }
      // Work on the leapfrog's own terms: 1/2 m v^n.v^{n+1} changes from n-1/2 to n+1/2
      // by 1/2 v^n.(F^{n+1/2} dt_n + F^{n-1/2} dt_{n-1}); booking external work the same
      // way (the element energy does, by its trapezoidal stress) closes the balance to
      // O(dt^2).
      if (Loads || k >= 0)
      {
        const Real impulse = work_force * dt;
        if (counted)
          s.external_work[i] += 0.5 * v_old * (impulse + prev_impulse(n, i));
        prev_impulse(n, i) = impulse;
      }
      if (counted)
      {
        s.kinetic[i] += 0.5 * m * v_new * v_new;
        s.kinetic_mid[i] += 0.5 * m * v_old * v_new;
        s.momentum[i] += m * v_new;
      }
      x(n, i) += half_dt * (v_old + v_new);
      v(n, i) = v_new;
    }
    if (Clear)
      resetForces(n, Loads);
  }

  /// Nodes begin .. end - 1 in order, their terms added to `sums`.
  template <int Dim, bool Loads, bool Clear, bool Contact = false, bool Record = false,
            bool Damp = false>
  KOKKOS_INLINE_FUNCTION void run(const Index begin, const Index end, NodeSums &sums) const
  {
    Sums<Dim> s;
    for (Index n = begin; n < end; ++n)
      integrate<Dim, Loads, Clear, Contact, Record, Damp>(n, s);
    s.addTo(sums);
  }
};

} // namespace scpdyn

namespace Kokkos
{
template <>
struct reduction_identity<scpdyn::NodeSums>
{
  KOKKOS_FORCEINLINE_FUNCTION static scpdyn::NodeSums sum() { return scpdyn::NodeSums(); }
};
} // namespace Kokkos
