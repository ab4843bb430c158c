#include "bc/BoundaryConditions.hpp"

#include "bc/TimeFunctions.hpp"

namespace scpdyn
{
namespace
{
template <class DeviceArray, class Fill>
void copyToDevice(const DeviceArray &dev, Fill fill)
{
  auto host = Kokkos::create_mirror_view(dev);
  fill(host);
  Kokkos::deep_copy(dev, host);
}

Real scale(const BoundaryConditions &bc, int function, Real t)
{
  return function < 0 ? 1.0 : evaluate(bc.functions[size_t(function)], t);
}
} // namespace

void updateVelocityValues(BoundaryConditions &bc, Real t)
{
  if (bc.velocity_value.empty())
    return;
  copyToDevice(bc.velocity_current, [&](auto &h) {
    for (size_t k = 0; k < bc.velocity_value.size(); ++k)
      h(k) = bc.velocity_value[k] * scale(bc, bc.velocity_function[k], t);
  });
}

void updateLoadValues(BoundaryConditions &bc, Real t)
{
  if (!bc.force_value.empty())
    copyToDevice(bc.force_current, [&](auto &h) {
      for (size_t k = 0; k < bc.force_value.size(); ++k)
      {
        const Real s = scale(bc, bc.force_function[k], t);
        for (int i = 0; i < 3; ++i)
          h(k, i) = bc.force_value[k][size_t(i)] * s;
      }
    });
  if (!bc.pressure_value.empty())
    copyToDevice(bc.pressure_current, [&](auto &h) {
      for (size_t k = 0; k < bc.pressure_value.size(); ++k)
        h(k) = bc.pressure_value[k] * scale(bc, bc.pressure_function[k], t);
    });
}

void applyFaceLoads(const BoundaryConditions &bc, const NodeFields &nodes, Real dt, int dim,
                    Geometry2D geometry)
{
  const Index count = Index(bc.pressure_bc.extent(0));
  if (count == 0)
    return;
  auto faces = bc.pressure_face;
  auto nface = bc.pressure_face_nodes;
  auto which = bc.pressure_bc;
  auto p_now = bc.pressure_current;
  auto x = nodes.x;
  auto v = nodes.v;
  AtomicVectorView f = nodes.f_ext;
  const Real h = 0.5 * dt;
  const bool axi = geometry == Geometry2D::Axisymmetric;
  Kokkos::parallel_for(
      "scpdyn::bc::pressure", Kokkos::RangePolicy<ExecSpace>(0, count),
      KOKKOS_LAMBDA(const Index k) {
        const Real p = p_now(which(k));
        const int nn = nface(k);
        Real xf[4][3];
        for (int a = 0; a < (nn == 1 ? 2 : nn); ++a)
          for (int i = 0; i < 3; ++i)
            xf[a][i] = x(faces(k, a), i) + h * v(faces(k, a), i);
        if (dim == 1)
        {
          const Real outward = xf[0][0] > xf[1][0] ? 1.0 : -1.0;
          f(faces(k, 0), 0) += -p * outward;
        }
        else if (dim == 2)
        {
          // outward normal times length: (t_y, -t_x), t = q - p
          const Real tx = xf[1][0] - xf[0][0], ty = xf[1][1] - xf[0][1];
          Real w0 = 0.5, w1 = 0.5;
          if (axi)
          {
            w0 = (2 * xf[0][0] + xf[1][0]) / 6;
            w1 = (xf[0][0] + 2 * xf[1][0]) / 6;
          }
          f(faces(k, 0), 0) += -p * ty * w0;
          f(faces(k, 0), 1) += p * tx * w0;
          f(faces(k, 1), 0) += -p * ty * w1;
          f(faces(k, 1), 1) += p * tx * w1;
        }
        else
        {
          Real P[3], Q[3];
          for (int i = 0; i < 3; ++i)
          {
            P[i] = nn == 4 ? xf[2][i] - xf[0][i] : xf[1][i] - xf[0][i];
            Q[i] = nn == 4 ? xf[3][i] - xf[1][i] : xf[2][i] - xf[0][i];
          }
          const Real A[3] = {0.5 * (P[1] * Q[2] - P[2] * Q[1]), 0.5 * (P[2] * Q[0] - P[0] * Q[2]),
                             0.5 * (P[0] * Q[1] - P[1] * Q[0])};
          for (int a = 0; a < nn; ++a)
            for (int i = 0; i < 3; ++i)
              f(faces(k, a), i) += -p * A[i] / nn;
        }
      });
}

void applyNodeForces(const BoundaryConditions &bc, const NodeFields &nodes)
{
  const Index count = Index(bc.force_node.extent(0));
  if (count == 0)
    return;
  auto node = bc.force_node;
  auto which = bc.force_bc;
  auto value = bc.force_current;
  AtomicVectorView f = nodes.f_ext;
  Kokkos::parallel_for(
      "scpdyn::bc::nodeForce", Kokkos::RangePolicy<ExecSpace>(0, count),
      KOKKOS_LAMBDA(const Index k) {
        for (int i = 0; i < 3; ++i)
          f(node(k), i) += value(which(k), i);
      });
}

void declareLateNodes(const BoundaryConditions &bc, LateNodes &late)
{
  late.declare("node forces", bc.force_node);
  auto face = Kokkos::create_mirror_view_and_copy(HostSpace(), bc.pressure_face);
  auto face_nodes = Kokkos::create_mirror_view_and_copy(HostSpace(), bc.pressure_face_nodes);
  std::vector<Index> nodes;
  for (size_t f = 0; f < face.extent(0); ++f) // (1D: the element's other node too)
    for (size_t a = 0; a < face.extent(1) && Index(a) < std::max<Index>(face_nodes(f), 2); ++a)
      if (face(f, a) >= 0)
        nodes.push_back(face(f, a));
  late.declare("face pressure", nodes);
}

} // namespace scpdyn
