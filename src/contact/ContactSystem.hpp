#pragma once
/// \file ContactSystem.hpp
/// \brief The runtime of the Simple Common Plane contact (scp-method.md 2-12, Appendix A): owns
/// the contact faces and the live common planes, runs detection (steps 3 and 9 on search
/// cycles), the per-cycle CP forces (step 9), the explicit-contact time-step limit (19) and the
/// contact energy. Used by the Solver; everything heavy runs in Kokkos kernels.
#include "bc/BoundaryConditions.hpp"
#include "contact/ContactData.hpp"
#include "contact/ContactSearch.hpp"
#include "contact/ContactSetup.hpp"

#include <string>
#include <vector>

namespace scpdyn
{

/// \brief Host copy of the live CPs for output (one point per CP).
struct ContactPointsHost
{
  std::vector<double> poc;          ///< 3 per CP [m]
  std::vector<double> area;         ///< Ac [m^2]
  std::vector<double> normal_force; ///< Fn, > 0 compression [N]
  std::vector<double> shear_force;  ///< |Fs| [N]
  std::vector<double> closure;      ///< u [m]
  std::vector<double> slip;         ///< plastic slip usp*a [m]
  std::vector<double> state;        ///< CpStatus
  std::vector<double> key1, key2;   ///< global face keys
};

/// \brief Why the contact stopped a run; the Solver turns it into a SimulationError.
struct ContactFailure
{
  bool failed = false;
  std::string message;
};

class ContactSystem
{
public:
  /// \brief Set-up (step 2): faces of the deck's contact surfaces, parameters, empty CP list.
  explicit ContactSystem(const ContactMeshInput &in);

  /// \brief True on the cycles that search for new CPs (cycle 0, then every search_interval).
  bool searchDue(long cycle) const;
  /// \brief Step 3: on search cycles, half-step face geometry and sorting bins.
  void sortIntoBins(const NodeFields &nodes, Real dt, long cycle);
  /// \brief Step 9: detection on search cycles, then every CP's force (sub-steps A-E), scattered
  /// atomically to a contact-force field and added to nodes.f_int. Returns a failure naming the
  /// CP when a force is not finite or a joint's closure passes its aperture; the forces are then
  /// not applied and the CP histories are restored.
  ContactFailure computeForces(const NodeFields &nodes, const BoundaryConditions &bc, Real dt,
                               long cycle, Real time);
  /// \brief Step 12: smallest explicit-contact time step (19) over the active explicit CPs, from
  /// v^{n+1} (nodes.v after the update); `dt_element` is the element Courant step [s]. 1e300
  /// when no explicit CP limits.
  Real stableTimeStep(const NodeFields &nodes, const ElementFields &elements,
                      Real dt_element) const;

  /// \brief Contact energy: work done on the joints by the mesh, = stored + dissipated [J].
  Real energy() const { return _work; }
  /// \brief Elastic energy stored in the joints now [J].
  Real storedEnergy() const { return _stored; }
  Real dissipatedEnergy() const { return _work - _stored; }
  Index count() const { return _cp.count; }
  Index maxCount() const { return _max_count; }
  const ContactFaceData &faces() const { return _faces; }
  const CommonPlaneData &planes() const { return _cp; }
  const std::vector<ContactFaceInfo> &faceInfo() const { return _info; }
  /// \brief The contact force of the last step on every node [N] (zero away from contact faces).
  const VectorView &nodalForces() const { return _fc; }
  /// \brief The live CPs, copied to the host.
  ContactPointsHost points() const;
  /// \brief "faces (element 12 face 1 of part 'a') and (element 40 face 3 of part 'b')".
  std::string describe(Index cp) const;

private:
  void detect(const NodeFields &nodes, Real dt);
  void computeVstar(const NodeFields &nodes, const BoundaryConditions &bc, Real dt);
  void jointForces(const NodeFields &nodes, Real dt);
  void constraintPasses(const NodeFields &nodes, Real dt);
  int tieSolve(const NodeFields &nodes, Real dt);
  void tieScatter(const NodeFields &nodes, Real dt, const VectorView &force);
  ContactFailure finish(const NodeFields &nodes, Real dt, long cycle, Real time);

  int _dim = 2;
  bool _axisym = false;
  long _search_interval = 1;
  int _passes = 5;
  Real _search_gap = -1;
  ContactFaceData _faces;
  std::vector<ContactFaceInfo> _info;
  std::vector<std::string> _part_names;
  CommonPlaneData _cp;
  FaceGeometryData _geom;
  FaceBins _bins;
  long _binned_cycle = -1;
  bool _has_constraints = false, _has_explicit = false;
  bool _has_sticky = false, _has_slide = false;
  VectorView _cg_x, _cg_r, _cg_p, _cg_z, _cg_ap, _cg_b; ///< conjugate-gradient vectors of the ties
  IndexView _tie_mode;   ///< per CP: which velocity constraint it imposes this cycle

  VectorView _vstar;     ///< v* of 10.6 (contact nodes; other entries unused)
  VectorView _dv;        ///< velocity increments of one constraint pass
  VectorView _fc;        ///< contact force of this cycle (contact nodes) [N]
  VectorView _impulse;   ///< last cycle's contact impulse fc dt (contact nodes) [N s]
  DeviceView<CpState *> _state_before; ///< CP histories at the start of step 9 (restored on failure)
  Real _work = 0;        ///< contact energy [J]
  Real _stored = 0;
  Index _max_count = 0;
};

} // namespace scpdyn
