#include "contact/JointGauge.hpp"

#include <cmath>

namespace scpdyn
{

JointGaugeSums jointGaugeSums(const CommonPlaneData &cp, const ContactFaceData &faces,
                              const Real point[3], Real radius)
{
  JointGaugeSums sums;
  if (cp.count == 0)
    return sums;
  auto poc = cp.poc;
  auto area = cp.area;
  auto state = cp.state;
  auto params = cp.params;
  auto status = cp.status;
  auto face1 = cp.face1;
  auto ghost = faces.ghost;
  const Real p0 = point[0], p1 = point[1], p2 = point[2], r2 = radius * radius;
  Kokkos::parallel_reduce(
      "jointGauge", Kokkos::RangePolicy<ExecSpace>(0, cp.count),
      KOKKOS_LAMBDA(const Index c, JointGaugeSums &s) {
        if (ghost(face1(c)) != 0)
          return; // the rank of face 1 counts it
        const Real d0 = poc(c, 0) - p0, d1 = poc(c, 1) - p1, d2 = poc(c, 2) - p2;
        if (d0 * d0 + d1 * d1 + d2 * d2 > r2)
          return;
        const CpState &st = state(c);
        const Real slip = st.usp * params(c).a;
        s.count += 1;
        s.closure += st.u;
        s.slip += slip;
        if (status(c) == CpInactive)
          return;
        const Real A = area(c);
        s.area += A;
        s.normal_force += st.Fn;
        s.shear_force +=
            kmath::sqrt(st.Fs[0] * st.Fs[0] + st.Fs[1] * st.Fs[1] + st.Fs[2] * st.Fs[2]);
        s.closure_area += st.u * A;
        s.slip_area += slip * A;
      },
      Kokkos::Sum<JointGaugeSums>(sums));
  return sums;
}

Real jointGaugeQuantity(const JointGaugeSums &s, int code)
{
  const bool touching = s.area > 0;
  auto mean = [&](Real weighted, Real plain) {
    return touching ? weighted / s.area : s.count > 0 ? plain / s.count : Real(0);
  };
  switch (code)
  {
  case 0:
    return touching ? s.normal_force / s.area : 0;
  case 1:
    return touching ? s.shear_force / s.area : 0;
  case 2:
    return s.normal_force;
  case 3:
    return s.shear_force;
  case 4:
    return s.area;
  case 5:
    return mean(s.closure_area, s.closure);
  case 6:
    return mean(s.slip_area, s.slip);
  default:
    return s.count;
  }
}

} // namespace scpdyn
