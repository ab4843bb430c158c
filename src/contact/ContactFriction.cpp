// Coulomb friction of the slide lines (docs/theory.md 11.1, D16), after their normal forces are
// solved (ContactBoundSolve.cpp): at the POC of each slide-line CP that pushes, the tangential
// force that would stop the faces' relative sliding by the end of the step, capped at mu Fn,
// mu = mu_k + (mu_s - mu_k) exp(-mu_dc |Vs|) (LS-DYNA's FS, FD, DC). The force opposes the
// sliding left after the normal forces, so it only takes energy out.
//
// Stick force: the relative tangential velocity over the row's diagonal dt sum w^2 k / M, where
// k counts the friction rows on node k: where several CPs share a node (the nodes inside a
// face chain), each takes its share of the node's mass, so together they stop the sliding
// instead of each stopping it alone and overshooting (a Jacobi step with shared masses).
// The normal force is solved jointly; the friction by Jacobi passes of these per-CP forces on the
// total so far: a sticking interface stops to within what the passes leave, not to round-off.
#include "contact/ContactSystem.hpp"
#include "contact/JointConstraints.hpp"
#include "contact/TieRows.hpp"

namespace scpdyn
{
using namespace contact_kernels;
using namespace tie_rows;

namespace
{

/// Jacobi passes of the stick force: each removes most of the sliding the last one left where
/// CPs share nodes off their centres. A block on an incline at tan(theta) < mu crept at a steady
/// 6e-4 m/s with one pass; with four its velocity swings by 1e-4 m/s about rest.
constexpr int kFrictionPasses = 4;

KOKKOS_INLINE_FUNCTION bool hasFriction(const CommonPlaneData &cp, Index p, int mode)
{
  return mode == TieNormal && isSlide(cp.params(p), cp.state(p)) && cp.params(p).mu_s > 0;
}

} // namespace

void ContactSystem::slideFriction(const NodeFields &nodes, Real dt)
{
  const ContactFaceData F = _faces;
  const CommonPlaneData cp = _cp;
  const TieWeights tw = _tie;
  auto X = _cg_x, T = _cg_t, vstar = _vstar, dv = _dv;
  auto mass = nodes.mass;
  auto bc = nodes.bc;
  auto used = _faces.nodes_used;
  auto mode = _tie_mode;
  const int dim = _dim, Q = _tie_points;
  const Index rows = cp.count * Q, nused = Index(used.extent(0));
  if (_share.extent(0) != vstar.extent(0))
    _share = VectorView("contact_friction_share", vstar.extent(0));
  auto share = _share;

  // the normal forces' velocity change, and the friction rows on every node
  tieScatter(nodes, dt, X);
  Kokkos::parallel_for(
      "scpdyn::contact::frictionShareZero", Kokkos::RangePolicy<ExecSpace>(0, nused),
      KOKKOS_LAMBDA(const Index i) { share(used(i), 0) = 0; });
  Kokkos::parallel_for(
      "scpdyn::contact::frictionShares", Kokkos::RangePolicy<ExecSpace>(0, rows),
      KOKKOS_LAMBDA(const Index c) {
        const Index p = c / Q;
        if (!hasFriction(cp, p, mode(c)))
          return;
        for (int side = 0; side < 2; ++side)
        {
          const Index f = side == 0 ? cp.face1(p) : cp.face2(p);
          if (F.ghost(f))
            continue;
          for (int a = 0; a < F.num_nodes(f); ++a)
            if ((side == 0 ? tw.w1(c, a) : tw.w2(c, a)) != 0)
              Kokkos::atomic_add(&share(F.nodes(f, a), 0), 1.0);
        }
      });
  if (_comm.sum_nodes) // a shared node counts the rows of every rank
    _comm.sum_nodes(share);

  auto mu_row = _cg_z; // component 0: the row's mu, set on the first pass
  for (int pass = 0; pass < kFrictionPasses; ++pass)
  {
    Kokkos::parallel_for(
        "scpdyn::contact::friction", Kokkos::RangePolicy<ExecSpace>(0, rows),
        KOKKOS_LAMBDA(const Index c) {
          const Index p = c / Q;
          for (int d = 0; d < 3; ++d)
            T(c, d) = 0;
          if (!hasFriction(cp, p, mode(c)))
            return;
          const JointParams &P = cp.params(p);
          Real V1[3], V2[3], dV1[3], dV2[3], Vs[3], Xt[3], D[3] = {0, 0, 0};
          rowVelocity(F, cp, tw, c, p, 0, vstar, V1);
          rowVelocity(F, cp, tw, c, p, 1, vstar, V2);
          rowVelocity(F, cp, tw, c, p, 0, dv, dV1);
          rowVelocity(F, cp, tw, c, p, 1, dv, dV2);
          Real vn = 0, Fn = 0;
          for (int d = 0; d < 3; ++d)
          {
            Vs[d] = (V1[d] + dV1[d]) - (V2[d] + dV2[d]); // after the forces so far
            vn += Vs[d] * cp.normal(p, d);
            Fn += X(c, d) * cp.normal(p, d);
          }
          for (int d = 0; d < 3; ++d)
          {
            Vs[d] -= vn * cp.normal(p, d);
            Xt[d] = X(c, d) - Fn * cp.normal(p, d);
          }
          // the row's diagonal with the nodes' masses shared among their friction rows
          for (int side = 0; side < 2; ++side)
          {
            const Index f = side == 0 ? cp.face1(p) : cp.face2(p);
            for (int a = 0; a < F.num_nodes(f); ++a)
            {
              const Index k = F.nodes(f, a);
              const Real w = side == 0 ? tw.w1(c, a) : tw.w2(c, a);
              const Real k_rows = share(k, 0) > 1 ? share(k, 0) : 1.0;
              for (int d = 0; d < dim; ++d)
                if (bc(k, d) < 0)
                  D[d] += dt * w * w * k_rows / mass(k);
            }
          }
          // mu from the sliding speed before friction (the first pass)
          if (pass == 0)
          {
            Real v2 = 0;
            for (int d = 0; d < dim; ++d)
              v2 += Vs[d] * Vs[d];
            mu_row(c, 0) = P.mu_k + (P.mu_s - P.mu_k) * kmath::exp(-P.mu_dc * kmath::sqrt(v2));
          }
          // the total tangential force that stops the sliding, capped at mu Fn
          Real total[3] = {0, 0, 0}, s2 = 0;
          for (int d = 0; d < dim; ++d)
          {
            total[d] = Xt[d] + (D[d] > 0 ? Vs[d] / D[d] : 0.0);
            s2 += total[d] * total[d];
          }
          const Real cap = mu_row(c, 0) * (Fn > 0 ? Fn : 0.0), s = kmath::sqrt(s2);
          const Real scale = s > cap ? cap / s : 1.0;
          for (int d = 0; d < dim; ++d)
            T(c, d) = scale * total[d] - Xt[d];
        });
    Kokkos::parallel_for(
        "scpdyn::contact::frictionAdd", Kokkos::RangePolicy<ExecSpace>(0, rows),
        KOKKOS_LAMBDA(const Index c) {
          for (int d = 0; d < 3; ++d)
            X(c, d) += T(c, d);
        });
    if (pass + 1 < kFrictionPasses)
      tieScatter(nodes, dt, X);
  }
}

} // namespace scpdyn
