// The contact's part of a restart file: the CP list by face keys with every CP's history and
// per-cycle fields, the per-node impulse and the energy accumulators (docs/theory.md 3.5, 12).
#include "contact/ContactSystem.hpp"
#include "core/HostCopy.hpp"
#include "core/InputError.hpp"
#include "io/RestartFile.hpp"

#include <algorithm>

namespace scpdyn
{
namespace
{
// CpState as doubles: every member in declaration order (ints are exact in a double)
constexpr int kCpStateValues = 22;
static_assert(sizeof(CpState) == 20 * sizeof(Real) + 2 * sizeof(int),
              "a new CpState member needs its place in packState/unpackState and a new "
              "kRestartFormatVersion");

void packState(const CpState &s, double *o)
{
  int k = 0;
  o[k++] = s.u;
  o[k++] = s.umax;
  o[k++] = s.Fn;
  for (int d = 0; d < 3; ++d)
    o[k++] = s.Fs[d];
  o[k++] = s.usp;
  for (int d = 0; d < 3; ++d)
    o[k++] = s.us[d];
  for (int d = 0; d < 3; ++d)
    o[k++] = s.n_old[d];
  o[k++] = s.u_z;
  o[k++] = s.Ac_old;
  o[k++] = s.open;
  o[k++] = s.failed;
  o[k++] = s.sigma_t_scale;
  for (int d = 0; d < 3; ++d)
    o[k++] = s.V_model[d];
  o[k++] = s.dt_model;
}

CpState unpackState(const double *o)
{
  CpState s;
  int k = 0;
  s.u = o[k++];
  s.umax = o[k++];
  s.Fn = o[k++];
  for (int d = 0; d < 3; ++d)
    s.Fs[d] = o[k++];
  s.usp = o[k++];
  for (int d = 0; d < 3; ++d)
    s.us[d] = o[k++];
  for (int d = 0; d < 3; ++d)
    s.n_old[d] = o[k++];
  s.u_z = o[k++];
  s.Ac_old = o[k++];
  s.open = int(o[k++]);
  s.failed = int(o[k++]);
  s.sigma_t_scale = o[k++];
  for (int d = 0; d < 3; ++d)
    s.V_model[d] = o[k++];
  s.dt_model = o[k++];
  return s;
}
} // namespace

void ContactSystem::saveState(RestartWriter &out) const
{
  const size_t n = size_t(_cp.count);
  out.put("contact.scalars",
          std::vector<double>{_work, _joint_work, _joint_work_peak, _joint_work_gross, _stored_peak,
                              _slide_work, _slide_work_peak, _dt_prev, _stored, double(_max_count),
                              double(_binned_cycle), _geom.h_max, double(n)});
  out.put("contact.impulse", flatten(_impulse));
  out.put("contact.cp_key1", flatten(_cp.key1));
  out.put("contact.cp_key2", flatten(_cp.key2));
  auto state = Kokkos::create_mirror_view_and_copy(HostSpace(), _cp.state);
  std::vector<double> s(n * kCpStateValues);
  for (size_t p = 0; p < n; ++p)
    packState(state(p), &s[p * kCpStateValues]);
  out.put("contact.cp_state", s);
  // the per-cycle fields too: the outputs of the cycle after a restart read some of them
  out.put("contact.cp_normal", flatten(_cp.normal));
  out.put("contact.cp_poc", flatten(_cp.poc));
  out.put("contact.cp_force", flatten(_cp.force));
  out.put("contact.cp_area", flatten(_cp.area));
  out.put("contact.cp_face_area1", flatten(_cp.face_area1));
  out.put("contact.cp_face_area2", flatten(_cp.face_area2));
  out.put("contact.cp_mstar", flatten(_cp.mstar));
  out.put("contact.cp_stored", flatten(_cp.stored));
  out.put("contact.cp_w1", flatten(_cp.w1));
  out.put("contact.cp_w2", flatten(_cp.w2));
  out.put("contact.cp_status", flatten(_cp.status));
  out.put("contact.cp_approach", flatten(_approach));
}

void ContactSystem::loadState(const RestartReader &in)
{
  const std::vector<double> sc = in.reals("contact.scalars", 13);
  _work = sc[0];
  _joint_work = sc[1];
  _joint_work_peak = sc[2];
  _joint_work_gross = sc[3];
  _stored_peak = sc[4];
  _slide_work = sc[5];
  _slide_work_peak = sc[6];
  _dt_prev = sc[7];
  _stored = sc[8];
  _max_count = Index(sc[9]);
  _binned_cycle = long(sc[10]);
  _geom.h_max = sc[11];
  const Index n = Index(sc[12]);
  const long nodes = long(_impulse.extent(0));
  unflatten(_impulse, in.reals("contact.impulse", 3 * nodes));

  const std::vector<double> k1 = in.reals("contact.cp_key1", n),
                            k2 = in.reals("contact.cp_key2", n);
  const std::vector<double> st = in.reals("contact.cp_state", long(n) * kCpStateValues);
  _cp = allocatePlanes(n);
  auto key = Kokkos::create_mirror_view_and_copy(HostSpace(), _faces.key);
  auto surface = Kokkos::create_mirror_view_and_copy(HostSpace(), _faces.surface);
  auto part = Kokkos::create_mirror_view_and_copy(HostSpace(), _faces.part);
  auto fparams = Kokkos::create_mirror_view_and_copy(HostSpace(), _faces.params);
  auto face1 = Kokkos::create_mirror_view(_cp.face1), face2 = Kokkos::create_mirror_view(_cp.face2);
  auto key1 = Kokkos::create_mirror_view(_cp.key1), key2 = Kokkos::create_mirror_view(_cp.key2);
  auto state = Kokkos::create_mirror_view(_cp.state);
  auto params = Kokkos::create_mirror_view(_cp.params);
  const long *keys = key.data();
  auto faceOf = [&](long k) {
    const long *it = std::lower_bound(keys, keys + _faces.count, k);
    if (it == keys + _faces.count || *it != k)
      throw InputError("restart file '" + in.path() + "': common plane of face key " +
                       std::to_string(k) + ", which is not a contact face of this deck");
    return Index(it - keys);
  };
  for (Index p = 0; p < n; ++p)
  {
    key1(p) = long(k1[size_t(p)]);
    key2(p) = long(k2[size_t(p)]);
    face1(p) = faceOf(key1(p));
    face2(p) = faceOf(key2(p));
    params(p) = planeParams(fparams(surface(face1(p))), fparams(surface(face2(p))),
                            part(face1(p)) == part(face2(p)));
    state(p) = unpackState(&st[size_t(p) * kCpStateValues]);
  }
  Kokkos::deep_copy(_cp.face1, face1);
  Kokkos::deep_copy(_cp.face2, face2);
  Kokkos::deep_copy(_cp.key1, key1);
  Kokkos::deep_copy(_cp.key2, key2);
  Kokkos::deep_copy(_cp.state, state);
  Kokkos::deep_copy(_cp.params, params);
  const long m = long(n);
  unflatten(_cp.normal, in.reals("contact.cp_normal", 3 * m));
  unflatten(_cp.poc, in.reals("contact.cp_poc", 3 * m));
  unflatten(_cp.force, in.reals("contact.cp_force", 3 * m));
  unflatten(_cp.area, in.reals("contact.cp_area", m));
  unflatten(_cp.face_area1, in.reals("contact.cp_face_area1", m));
  unflatten(_cp.face_area2, in.reals("contact.cp_face_area2", m));
  unflatten(_cp.mstar, in.reals("contact.cp_mstar", m));
  unflatten(_cp.stored, in.reals("contact.cp_stored", m));
  unflatten(_cp.w1, in.reals("contact.cp_w1", kMaxFaceNodes * m));
  unflatten(_cp.w2, in.reals("contact.cp_w2", kMaxFaceNodes * m));
  unflatten(_cp.status, in.reals("contact.cp_status", m));
  const std::vector<double> approach = in.reals("contact.cp_approach");
  _approach = RealView("cp_approach", approach.size());
  unflatten(_approach, approach);
  countPlanes(); // the self-contact CPs: whether the slide-line solve runs before the next search
}

} // namespace scpdyn
