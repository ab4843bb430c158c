#pragma once
/// \file ContactData.hpp
/// \brief Device data of the common-plane contact: the contact faces (fixed for the run) and the
/// common planes (CPs), each a struct of Views indexed by face or CP id (docs/theory.md 3, 12).
#include "contact/CommonPlaneState.hpp"

#include <string>
#include <vector>

namespace scpdyn
{

/// \brief External faces that carry a contact condition, in ascending global face key
/// (mesh element id * 8 + local face, 3.5): the face of a CP with the smaller index is face 1.
struct ContactFaceData
{
  Index count = 0;
  DeviceView<Index *[kMaxFaceNodes]> nodes; ///< outward-ordered nodes, -1 padded
  IndexView num_nodes;
  IndexView element; ///< device element id of the element behind the face
  IndexView surface; ///< contact surface (face-BC id) of the face
  IndexView part;    ///< mesh part of the element behind: two faces of one part are self-contact
  /// 1: the face is searched; 0: an interior face erosion has not exposed, or a face of an
  /// eroded element (11.6)
  IndexView active;
  RealView mass; ///< face mass M_f = m_e N_face/N_elem (10.1) [kg]
  /// twice the distance from the face's centroid to its element's, at set-up [m]: a hex's
  /// thickness behind the face; how deep a pair may overlap and still be a contact (3.2 rule 5)
  RealView depth;
  IndexView rigid; ///< 1 when every node of the face has all velocity components prescribed
  DeviceView<JointParams *> params; ///< per surface, resolved SI parameters
  IndexView nodes_used;             ///< the distinct nodes of all contact faces, ascending
  /// 1D only: the other node of the element behind the (point) face, which orients the face
  /// normal (4.1 in 1D); -1 in 2D and 3D
  IndexView back;
  // Decomposed runs: the faces of this rank and its ghost faces (faces of other
  // ranks near its own, ascending key among them); a ghost face's element is -2 - its global
  // element id, its nodes may be ghost nodes (numbered after the local nodes).
  DeviceView<long *> key; ///< global face key (3.5)
  IndexView ghost;        ///< 1 for a ghost face: no force is applied to its nodes here
  RealView density;       ///< ghost faces: density of the element behind [kg/m^3] (19)
  /// sleepy switch (11.4): plastic strain and damage of the element behind, every cycle
  DeviceView<Real *[2]> failure;
};

/// \brief Allocates the per-face Views of `F` for `n` faces and sets `F.count`; `params` and
/// `nodes_used` are left to the caller.
inline void allocateFaces(ContactFaceData &F, size_t n)
{
  F.count = Index(n);
  F.nodes = DeviceView<Index *[kMaxFaceNodes]>("contact_face_nodes", n);
  F.num_nodes = IndexView("contact_face_num_nodes", n);
  F.element = IndexView("contact_face_element", n);
  F.surface = IndexView("contact_face_surface", n);
  F.part = IndexView("contact_face_part", n);
  F.active = IndexView("contact_face_active", n);
  F.mass = RealView("contact_face_mass", n);
  F.depth = RealView("contact_face_depth", n);
  F.rigid = IndexView("contact_face_rigid", n);
  F.back = IndexView("contact_face_back", n);
  F.key = DeviceView<long *>("contact_face_key", n);
  F.ghost = IndexView("contact_face_ghost", n);
  F.density = RealView("contact_face_density", n);
  F.failure = DeviceView<Real *[2]>("contact_face_failure", n);
}

/// \brief Host mirrors of the per-face Views filled at set-up (density excepted: ghost
/// densities arrive later), and their copy to the device.
struct ContactFaceHost
{
  DeviceView<Index *[kMaxFaceNodes]>::HostMirror nodes;
  IndexView::HostMirror num_nodes, element, surface, part, active, rigid, back, ghost;
  RealView::HostMirror mass, depth;
  DeviceView<long *>::HostMirror key;

  explicit ContactFaceHost(const ContactFaceData &F)
      : nodes(Kokkos::create_mirror_view(F.nodes)),
        num_nodes(Kokkos::create_mirror_view(F.num_nodes)),
        element(Kokkos::create_mirror_view(F.element)),
        surface(Kokkos::create_mirror_view(F.surface)), part(Kokkos::create_mirror_view(F.part)),
        active(Kokkos::create_mirror_view(F.active)), rigid(Kokkos::create_mirror_view(F.rigid)),
        back(Kokkos::create_mirror_view(F.back)), ghost(Kokkos::create_mirror_view(F.ghost)),
        mass(Kokkos::create_mirror_view(F.mass)), depth(Kokkos::create_mirror_view(F.depth)),
        key(Kokkos::create_mirror_view(F.key))
  {
  }
  void copyTo(const ContactFaceData &F) const
  {
    Kokkos::deep_copy(F.nodes, nodes);
    Kokkos::deep_copy(F.num_nodes, num_nodes);
    Kokkos::deep_copy(F.element, element);
    Kokkos::deep_copy(F.surface, surface);
    Kokkos::deep_copy(F.part, part);
    Kokkos::deep_copy(F.active, active);
    Kokkos::deep_copy(F.rigid, rigid);
    Kokkos::deep_copy(F.back, back);
    Kokkos::deep_copy(F.ghost, ghost);
    Kokkos::deep_copy(F.mass, mass);
    Kokkos::deep_copy(F.depth, depth);
    Kokkos::deep_copy(F.key, key);
  }
};

/// \brief Host description of a contact face, for messages and outputs.
struct ContactFaceInfo
{
  long key = 0; ///< global face key
  Index mesh_element = -1;
  int local_face = -1;
  int part = -1; ///< mesh part index
  /// an interior face (11.6): the global id of the element on its other side, else -1
  Index twin = -1;
};

/// \brief The live common planes. `face1 < face2` (face indices), sorted by (face1, face2), so a
/// face pair is found by binary search. The per-cycle fields are rewritten every cycle.
struct CommonPlaneData
{
  Index count = 0;
  IndexView face1, face2;
  DeviceView<long *> key1, key2;    ///< global keys of the faces: the CP's identity across searches
  DeviceView<CpState *> state;      ///< history (section 12)
  DeviceView<JointParams *> params; ///< averaged parameters of the two faces (3.6)
  // per cycle
  VectorView normal;                        ///< CP normal n, face 1 -> face 2
  VectorView poc;                           ///< point of contact x_poc [m]
  VectorView force;                         ///< total CP force on face 2 [N]
  RealView area;                            ///< contact area Ac [m^2]
  RealView face_area1, face_area2;          ///< A1, A2 of the faces [m^2]
  RealView mstar;                           ///< reduced mass m* [kg]
  RealView stored;                          ///< stored elastic energy Psi [J]
  DeviceView<Real *[kMaxFaceNodes]> w1, w2; ///< nodal weights of the force on face 1, 2
  IndexView status;                         ///< CpStatus
};

/// \brief The Views of `n` CPs, zero-filled, with `count` = n.
inline CommonPlaneData allocatePlanes(Index n)
{
  CommonPlaneData c;
  const size_t m = size_t(n);
  c.count = n;
  c.face1 = IndexView("cp_face1", m);
  c.face2 = IndexView("cp_face2", m);
  c.key1 = DeviceView<long *>("cp_key1", m);
  c.key2 = DeviceView<long *>("cp_key2", m);
  c.state = DeviceView<CpState *>("cp_state", m);
  c.params = DeviceView<JointParams *>("cp_params", m);
  c.normal = VectorView("cp_normal", m);
  c.poc = VectorView("cp_poc", m);
  c.force = VectorView("cp_force", m);
  c.area = RealView("cp_area", m);
  c.face_area1 = RealView("cp_face_area1", m);
  c.face_area2 = RealView("cp_face_area2", m);
  c.mstar = RealView("cp_mstar", m);
  c.stored = RealView("cp_stored", m);
  c.w1 = DeviceView<Real *[kMaxFaceNodes]>("cp_w1", m);
  c.w2 = DeviceView<Real *[kMaxFaceNodes]>("cp_w2", m);
  c.status = IndexView("cp_status", m);
  return c;
}

/// \brief Shape-function weights of the face nodes at the tie points of the velocity
/// constraints: row c = p Q + q is tie point q of CP p (ContactConstraints.cpp).
struct TieWeights
{
  DeviceView<Real *[kMaxFaceNodes]> w1, w2; ///< face 1, face 2
};

/// \brief Per-CP status written to the outputs.
enum CpStatus : int
{
  CpInactive = 0, ///< no overlap (3.4): no force
  CpStick = 1,    ///< active, sticking (or a velocity constraint)
  CpSlip = 2,     ///< active, slipped this cycle
  CpOpen = 3      ///< active, joint open or slide line without compression: no force
};

} // namespace scpdyn
