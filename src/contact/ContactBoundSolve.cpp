// Step 9 with slide lines (docs/theory.md 10.8, 11.1): the forces X of the sticky and slide-line
// tie rows minimise f(X) = 1/2 X.A X - b.X with X.n >= 0 on every slide-line row. Its minimum is
// the discrete contact problem: no approach beyond the gap where a slide line pushes, no slide
// line that pulls. f(X) dt is the change of kinetic energy the forces make (b the approach of
// v*), so any X with f(X) <= f(0) = 0 takes energy out and never puts it in.
//
// Solver: MPRGP, modified proportioning with reduced gradient projections (Dostal and Schoeberl,
// Comput. Optim. Appl. 30, 2005; Dostal, Optimal Quadratic Programming Algorithms, Springer
// 2009). Conjugate gradients on the rows that carry force (the free set); a gradient-projection
// (expansion) step where a CG step would make a slide line pull, which binds or frees many rows
// at once; a proportioning step where the gradient wants bound rows to push. Every step
// decreases f, so a solve stopped by its iteration cap still never creates energy, and it
// converges for a semi-definite A: redundant rows (two CPs on one node pair, where corners sit
// on the other side's nodes) do not stall it. The active set it replaces (free the rows that
// pull, re-solve, repeat) cycled there and applied an X that gave the mesh energy.
//
// The unknowns are scaled by the diagonal, y = D^(1/2) X (the Jacobi preconditioner of the tie
// solve), which keeps the bounds as they are; the step of the projection, abar = 1.9 / ||A||,
// uses the bound ||A||_2 <= ||B||_1 ||B||_inf of A = B B^T, B = S J M^(-1/2) dt^(1/2).
#include "contact/ContactSystem.hpp"
#include "contact/TieRows.hpp"

#include <cmath>
#include <limits>

namespace scpdyn
{
using namespace contact_kernels;
using namespace tie_rows;

namespace
{

/// The growth of the projected gradient over its best that stops the solve (divergence guard in
/// boundSolve): CG's residual is not monotone, but on a consistent system it does not climb
/// three orders above its lowest value.
constexpr Real kDivergedGrowth = 1e3;

KOKKOS_INLINE_FUNCTION Real along(const CommonPlaneData &cp, Index p, const Real v[3])
{
  return v[0] * cp.normal(p, 0) + v[1] * cp.normal(p, 1) + v[2] * cp.normal(p, 2);
}

/// The parts of the gradient g of row c at x (scaled): phi, the free gradient (rows with force);
/// beta, the chopped gradient (bound slide-line rows the gradient would push); phit, the reduced
/// free gradient (phi cut to the step that reaches the bound, x.n / abar).
KOKKOS_INLINE_FUNCTION void gradientParts(const CommonPlaneData &cp, Index p, int mode,
                                          const Real x[3], const Real g[3], Real abar, Real phi[3],
                                          Real beta[3], Real phit[3])
{
  for (int d = 0; d < 3; ++d)
    phi[d] = beta[d] = phit[d] = 0;
  if (mode == TieFull)
    for (int d = 0; d < 3; ++d)
      phi[d] = phit[d] = g[d];
  else if (mode == TieNormal)
  {
    const Real lam = along(cp, p, x), gn = along(cp, p, g);
    const Real gt = lam > 0 ? (gn > 0 ? contact_math::min(lam / abar, gn) : gn) : 0.0;
    for (int d = 0; d < 3; ++d)
    {
      phi[d] = lam > 0 ? gn * cp.normal(p, d) : 0.0;
      beta[d] = lam > 0 ? 0.0 : contact_math::min(gn, 0.0) * cp.normal(p, d);
      phit[d] = gt * cp.normal(p, d);
    }
  }
}

} // namespace

void ContactSystem::tieApply(const NodeFields &nodes, Real dt, const VectorView &in,
                             const VectorView &out)
{
  const ContactFaceData F = _faces;
  const CommonPlaneData cp = _cp;
  const TieWeights tw = _tie;
  auto S = _cg_s, T = _cg_t, dv = _dv;
  auto mode = _tie_mode;
  const int dim = _dim, Q = _tie_points;
  const Index rows = cp.count * Q;
  Kokkos::parallel_for(
      "scpdyn::contact::boundScale", Kokkos::RangePolicy<ExecSpace>(0, rows),
      KOKKOS_LAMBDA(const Index c) {
        for (int d = 0; d < 3; ++d)
          T(c, d) = S(c, d) * in(c, d);
      });
  tieScatter(nodes, dt, T);
  Kokkos::parallel_for(
      "scpdyn::contact::boundApply", Kokkos::RangePolicy<ExecSpace>(0, rows),
      KOKKOS_LAMBDA(const Index c) {
        const Index p = c / Q;
        Real V1[3], V2[3], ap[3];
        rowVelocity(F, cp, tw, c, p, 0, dv, V1);
        rowVelocity(F, cp, tw, c, p, 1, dv, V2);
        for (int d = 0; d < 3; ++d)
          ap[d] = V2[d] - V1[d];
        project(cp, p, mode(c), dim, ap);
        for (int d = 0; d < 3; ++d)
          out(c, d) = S(c, d) * ap[d];
      });
}

Real ContactSystem::tieOperatorBound(const NodeFields &nodes, Real dt)
{
  // ||B||_inf: the largest row sum of |B|; ||B||_1: the largest column (node component) sum
  const ContactFaceData F = _faces;
  const CommonPlaneData cp = _cp;
  const TieWeights tw = _tie;
  auto S = _cg_s, dv = _dv;
  auto mass = nodes.mass;
  auto bc = nodes.bc;
  auto used = _faces.nodes_used;
  auto mode = _tie_mode;
  const int dim = _dim, Q = _tie_points;
  const Index rows = cp.count * Q;
  const NodeAdder add = nodeAdder();
  const NodeSlotRows *slots =
      slotRows(_tie_points, _tie_rows); // the column sums in a fixed order, or atomic
  const bool gather = slots != nullptr;
  const VectorView share = gather ? slots->share : VectorView();
  Kokkos::parallel_for(
      "scpdyn::contact::boundZero", Kokkos::RangePolicy<ExecSpace>(0, Index(used.extent(0))),
      KOKKOS_LAMBDA(const Index i) {
        for (int d = 0; d < 3; ++d)
          dv(used(i), d) = 0;
      });
  Real row_max = 0;
  Kokkos::parallel_reduce(
      "scpdyn::contact::boundRows", Kokkos::RangePolicy<ExecSpace>(0, rows),
      KOKKOS_LAMBDA(const Index c, Real &m) {
        const Index p = c / Q;
        if (gather)
          clearShares(share, c, c + 1);
        if (mode(c) == TieNone)
          return;
        Real sum[3] = {0, 0, 0}; // per component (full rows), or along n (normal rows): sum[0]
        for (int side = 0; side < 2; ++side)
        {
          const Index f = side == 0 ? cp.face1(p) : cp.face2(p);
          for (int a = 0; a < F.num_nodes(f); ++a)
          {
            const Index k = F.nodes(f, a);
            const Real w = contact_math::abs(side == 0 ? tw.w1(c, a) : tw.w2(c, a));
            const Real b = w * kmath::sqrt(dt / mass(k));
            for (int d = 0; d < dim; ++d)
              if (bc(k, d) < 0)
              {
                const Real e = mode(c) == TieFull
                                   ? S(c, d) * b
                                   : S(c, d) * b * contact_math::abs(cp.normal(p, d));
                sum[mode(c) == TieFull ? d : 0] += e;
                if (F.ghost(f))
                  continue;
                if (gather)
                  share(shareSlot(c, side, a), d) = e;
                else
                  add(&dv(k, d), e);
              }
          }
        }
        for (int d = 0; d < 3; ++d)
          m = contact_math::max(m, sum[d]);
      },
      Kokkos::Max<Real>(row_max));
  if (gather)
    assembleSlots(*slots, dv, true);
  sumOverRanks(slots, dv); // a node's column spans the rows of every rank
  Real col_max = 0;
  Kokkos::parallel_reduce(
      "scpdyn::contact::boundColumns", Kokkos::RangePolicy<ExecSpace>(0, Index(used.extent(0))),
      KOKKOS_LAMBDA(const Index i, Real &m) {
        for (int d = 0; d < 3; ++d)
          m = contact_math::max(m, dv(used(i), d));
      },
      Kokkos::Max<Real>(col_max));
  if (_comm.max)
  {
    row_max = _comm.max(row_max);
    col_max = _comm.max(col_max);
  }
  return row_max * col_max;
}

int ContactSystem::boundSolve(const NodeFields &nodes, Real dt)
{
  const ContactFaceData F = _faces;
  const CommonPlaneData cp = _cp;
  const TieWeights tw = _tie;
  auto X = _cg_x, G = _cg_r, Pv = _cg_p, AP = _cg_ap, Bh = _cg_z, B = _cg_b, W = _cg_w;
  auto S = _cg_s;
  auto mass = nodes.mass;
  auto bc = nodes.bc;
  auto mode = _tie_mode;
  const int dim = _dim, Q = _tie_points;
  const Index rows = cp.count * Q;
  const auto range = Kokkos::RangePolicy<ExecSpace>(0, rows);

  // scale, targets b^ = S b, start at X = 0 (feasible): g = -b^
  // scale: of the round-off stop; cold: |projected gradient|^2 at X = 0, of the relative stop
  // every sum of the solve is exact (ExactSum.hpp): its bits do not depend on the threads or
  // the ranks that add its terms
  ExactSums<2> setup;
  Kokkos::parallel_reduce(
      "scpdyn::contact::boundSetup", range,
      KOKKOS_LAMBDA(const Index c, ExactSums<2> &acc) {
        const Index p = c / Q;
        Real D[3], Dn, b[3] = {B(c, 0), B(c, 1), B(c, 2)}, wv[3] = {W(c, 0), W(c, 1), W(c, 2)};
        tieDiagonal(F, cp, tw, c, p, mass, bc, dt, dim, D, Dn);
        project(cp, p, mode(c), dim, b);
        project(cp, p, mode(c), dim, wv);
        const bool counted = ownsPlane(F, cp, p); // a cross-rank CP counts once
        for (int d = 0; d < 3; ++d)
        {
          const Real s = mode(c) == TieFull     ? (D[d] > 0 ? 1 / kmath::sqrt(D[d]) : 0.0)
                         : mode(c) == TieNormal ? (Dn > 0 ? 1 / kmath::sqrt(Dn) : 0.0)
                                                : 0.0;
          S(c, d) = d < dim ? s : 0.0;
          Bh(c, d) = S(c, d) * b[d];
          // warm start: a slide line's last normal force, shared by its rows (y = X / S)
          const Real share = cp.state(p).Fn / Q;
          X(c, d) = mode(c) == TieNormal && share > 0 && S(c, d) > 0
                        ? share * cp.normal(p, d) / S(c, d)
                        : 0.0;
          if (counted)
            acc.add(0, S(c, d) * wv[d] * S(c, d) * wv[d]);
        }
        const Real bn = S(c, 0) * along(cp, p, b);
        if (counted)
          acc.add(1, mode(c) == TieFull
                         ? S(c, 0) * b[0] * S(c, 0) * b[0] + S(c, 1) * b[1] * S(c, 1) * b[1] +
                               S(c, 2) * b[2] * S(c, 2) * b[2]
                     : mode(c) == TieNormal
                         ? contact_math::max(bn, 0.0) * contact_math::max(bn, 0.0)
                         : 0.0);
      },
      ExactSumsReducer<2>(setup));
  Real s2[2];
  exactTotals(setup, s2);
  const Real scale = s2[0], cold = s2[1];
  // g = A y - b^ at the warm start; f(y) = 1/2 y.(g - b^) must not exceed f(0) = 0 (the start
  // would then give the mesh energy): else start from 0
  tieApply(nodes, dt, X, AP);
  ExactSums<1> start;
  Kokkos::parallel_reduce(
      "scpdyn::contact::boundStart", range,
      KOKKOS_LAMBDA(const Index c, ExactSums<1> &acc) {
        for (int d = 0; d < 3; ++d)
          G(c, d) = AP(c, d) - Bh(c, d);
        if (ownsPlane(F, cp, c / Q))
          for (int d = 0; d < 3; ++d)
            acc.add(0, 0.5 * X(c, d) * (G(c, d) - Bh(c, d)));
      },
      ExactSumsReducer<1>(start));
  Real f0;
  exactTotals(start, &f0);
  if (!(f0 <= 0))
    Kokkos::parallel_for(
        "scpdyn::contact::boundCold", range, KOKKOS_LAMBDA(const Index c) {
          for (int d = 0; d < 3; ++d)
          {
            X(c, d) = 0;
            G(c, d) = -Bh(c, d);
          }
        });
  const Real norm_A = tieOperatorBound(nodes, dt);
  if (!(norm_A > 0))
    return 0; // no row can move a node
  const Real abar = 1.9 / norm_A;

  // P = phi(X); the norms of phi, beta and phit.phi at the current X
  auto freeDirection = [&]() {
    Kokkos::parallel_for(
        "scpdyn::contact::boundFree", range, KOKKOS_LAMBDA(const Index c) {
          const Index p = c / Q;
          const Real x[3] = {X(c, 0), X(c, 1), X(c, 2)}, g[3] = {G(c, 0), G(c, 1), G(c, 2)};
          Real phi[3], beta[3], phit[3];
          gradientParts(cp, p, mode(c), x, g, abar, phi, beta, phit);
          for (int d = 0; d < 3; ++d)
            Pv(c, d) = phi[d];
        });
  };
  auto norms = [&](Real n[3]) {
    ExactSums<3> acc3;
    Kokkos::parallel_reduce(
        "scpdyn::contact::boundNorms", range,
        KOKKOS_LAMBDA(const Index c, ExactSums<3> &acc) {
          const Index p = c / Q;
          if (!ownsPlane(F, cp, p))
            return;
          const Real x[3] = {X(c, 0), X(c, 1), X(c, 2)}, g[3] = {G(c, 0), G(c, 1), G(c, 2)};
          Real phi[3], beta[3], phit[3];
          gradientParts(cp, p, mode(c), x, g, abar, phi, beta, phit);
          for (int d = 0; d < 3; ++d)
          {
            acc.add(0, phi[d] * phi[d]);
            acc.add(1, beta[d] * beta[d]);
            acc.add(2, phit[d] * phi[d]);
          }
        },
        ExactSumsReducer<3>(acc3));
    exactTotals(acc3, n);
  };
  // pAp and g.p of direction P (AP = A P already)
  auto curvature = [&](Real &pap, Real &gp) {
    ExactSums<2> acc2;
    Kokkos::parallel_reduce(
        "scpdyn::contact::boundCurvature", range,
        KOKKOS_LAMBDA(const Index c, ExactSums<2> &acc) {
          if (!ownsPlane(F, cp, c / Q))
            return;
          for (int d = 0; d < 3; ++d)
          {
            acc.add(0, Pv(c, d) * AP(c, d));
            acc.add(1, G(c, d) * Pv(c, d));
          }
        },
        ExactSumsReducer<2>(acc2));
    Real s[2];
    exactTotals(acc2, s);
    pap = s[0];
    gp = s[1];
  };
  auto step = [&](Real alpha) {
    Kokkos::parallel_for(
        "scpdyn::contact::boundStep", range, KOKKOS_LAMBDA(const Index c) {
          for (int d = 0; d < 3; ++d)
          {
            X(c, d) -= alpha * Pv(c, d);
            G(c, d) -= alpha * AP(c, d);
          }
        });
  };

  freeDirection();
  Real n[3];
  norms(n);
  // as the tie solve: 1e-10 of the projected gradient at X = 0, or round-off of v*
  const Real stop = contact_math::max(1e-20 * cold, 1e-26 * scale);
  const int cap = 20 * _passes;
  // Divergence guard: rows the ties already fix (a failed sleepy CP between node pairs its tied
  // neighbours hold) with a target that is not quite theirs (its gap) make the system
  // inconsistent. The projected gradient then falls to a floor and grows again, without bound,
  // as the iterates leave the operator's range; the solve stops there and takes its best iterate.
  auto best_x = _cg_best;
  Real best = n[0] + n[1];
  Kokkos::deep_copy(best_x, X);
  int it = 0;
  for (; it < cap && n[0] + n[1] > stop; ++it)
  {
    if (n[1] <=
        n[2]) // proportional (Gamma = 1): the bound rows want less than the free rows can give
    {
      tieApply(nodes, dt, Pv, AP);
      Real pap, gp;
      curvature(pap, gp);
      if (!(pap > 0))
        break;
      // the longest step along -P that keeps every slide line in compression
      Real alpha_f = std::numeric_limits<Real>::max();
      Kokkos::parallel_reduce(
          "scpdyn::contact::boundFeasible", range,
          KOKKOS_LAMBDA(const Index c, Real &m) {
            const Index p = c / Q;
            if (mode(c) != TieNormal)
              return;
            const Real x[3] = {X(c, 0), X(c, 1), X(c, 2)}, pv[3] = {Pv(c, 0), Pv(c, 1), Pv(c, 2)};
            const Real lam = along(cp, p, x), pn = along(cp, p, pv);
            if (lam > 0 && pn > 0)
              m = contact_math::min(m, lam / pn);
          },
          Kokkos::Min<Real>(alpha_f));
      if (_comm.max)
        alpha_f = -_comm.max(-alpha_f);
      const Real alpha_cg = gp / pap;
      if (alpha_cg < alpha_f)
      { // conjugate gradient step
        step(alpha_cg);
        ExactSums<1> conj;
        Kokkos::parallel_reduce(
            "scpdyn::contact::boundConjugate", range,
            KOKKOS_LAMBDA(const Index c, ExactSums<1> &acc) {
              const Index p = c / Q;
              if (!ownsPlane(F, cp, p))
                return;
              const Real x[3] = {X(c, 0), X(c, 1), X(c, 2)}, g[3] = {G(c, 0), G(c, 1), G(c, 2)};
              Real phi[3], beta[3], phit[3];
              gradientParts(cp, p, mode(c), x, g, abar, phi, beta, phit);
              for (int d = 0; d < 3; ++d)
                acc.add(0, phi[d] * AP(c, d));
            },
            ExactSumsReducer<1>(conj));
        Real phi_ap;
        exactTotals(conj, &phi_ap);
        const Real gamma = phi_ap / pap;
        Kokkos::parallel_for(
            "scpdyn::contact::boundDirection", range, KOKKOS_LAMBDA(const Index c) {
              const Index p = c / Q;
              const Real x[3] = {X(c, 0), X(c, 1), X(c, 2)}, g[3] = {G(c, 0), G(c, 1), G(c, 2)};
              Real phi[3], beta[3], phit[3];
              gradientParts(cp, p, mode(c), x, g, abar, phi, beta, phit);
              for (int d = 0; d < 3; ++d)
                Pv(c, d) = phi[d] - gamma * Pv(c, d);
            });
      }
      else
      { // expansion: to the bound, then a projected gradient step, then g afresh
        step(alpha_f);
        Kokkos::parallel_for(
            "scpdyn::contact::boundProject", range, KOKKOS_LAMBDA(const Index c) {
              const Index p = c / Q;
              const Real x[3] = {X(c, 0), X(c, 1), X(c, 2)}, g[3] = {G(c, 0), G(c, 1), G(c, 2)};
              Real phi[3], beta[3], phit[3];
              gradientParts(cp, p, mode(c), x, g, abar, phi, beta, phit);
              Real y[3];
              for (int d = 0; d < 3; ++d)
                y[d] = x[d] - abar * phi[d];
              if (mode(c) == TieNormal)
              {
                const Real lam = contact_math::max(along(cp, p, y), 0.0);
                for (int d = 0; d < 3; ++d)
                  y[d] = lam * cp.normal(p, d);
              }
              for (int d = 0; d < 3; ++d)
                X(c, d) = y[d];
            });
        tieApply(nodes, dt, X, AP);
        Kokkos::parallel_for(
            "scpdyn::contact::boundGradient", range, KOKKOS_LAMBDA(const Index c) {
              for (int d = 0; d < 3; ++d)
                G(c, d) = AP(c, d) - Bh(c, d);
            });
        freeDirection();
      }
    }
    else
    { // proportioning: push the bound rows the gradient asks to push
      Kokkos::parallel_for(
          "scpdyn::contact::boundChopped", range, KOKKOS_LAMBDA(const Index c) {
            const Index p = c / Q;
            const Real x[3] = {X(c, 0), X(c, 1), X(c, 2)}, g[3] = {G(c, 0), G(c, 1), G(c, 2)};
            Real phi[3], beta[3], phit[3];
            gradientParts(cp, p, mode(c), x, g, abar, phi, beta, phit);
            for (int d = 0; d < 3; ++d)
              Pv(c, d) = beta[d];
          });
      tieApply(nodes, dt, Pv, AP);
      Real pap, gp;
      curvature(pap, gp);
      if (!(pap > 0))
        break;
      step(gp / pap);
      freeDirection();
    }
    norms(n);
    if (n[0] + n[1] < best)
    {
      best = n[0] + n[1];
      Kokkos::deep_copy(best_x, X);
    }
    else if (n[0] + n[1] > kDivergedGrowth * best)
    {
      Kokkos::deep_copy(X, best_x);
      break;
    }
  }

  // back to forces; a slide line without force this cycle is not tied
  Kokkos::parallel_for(
      "scpdyn::contact::boundForces", range, KOKKOS_LAMBDA(const Index c) {
        const Index p = c / Q;
        const Real x[3] = {X(c, 0), X(c, 1), X(c, 2)};
        const bool unloaded = mode(c) == TieNormal && !(along(cp, p, x) > 0);
        if (unloaded)
          mode(c) = TieNone;
        for (int d = 0; d < 3; ++d)
          X(c, d) = unloaded ? 0.0 : S(c, d) * x[d];
      });
  return it;
}

} // namespace scpdyn
