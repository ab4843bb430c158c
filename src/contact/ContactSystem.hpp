#pragma once
/// \file ContactSystem.hpp
/// \brief The runtime of the Simple Common Plane contact (docs/theory.md 2-12, Appendix A): owns
/// the contact faces and the live common planes, runs detection (steps 3 and 9 on search
/// cycles), the per-cycle CP forces (step 9), the explicit-contact time-step limit (19) and the
/// contact energy. Used by the Solver; everything heavy runs in Kokkos kernels.
#include "bc/BoundaryConditions.hpp"
#include "contact/ContactData.hpp"
#include "contact/ContactSearch.hpp"
#include "contact/ContactSetup.hpp"
#include "core/ExactSum.hpp"
#include "parallel/OrderedNodeSum.hpp"

#include <mpi.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace scpdyn
{

struct GhostFaceDesc;
class RestartWriter;
class RestartReader;

/// \brief What the contact of a decomposed run needs from the communication layer;
/// empty members on one rank.
struct ContactComm
{
  /// Sum a nodal vector over the copies of every shared node, then copy the owners' values to
  /// the ghost nodes (the constraint solve's velocity increments).
  std::function<void(const VectorView &)> sum_nodes;
  /// Global sums (added in rank order, the same bits on every rank) and maximum.
  std::function<void(Real *, int)> sum;
  std::function<Real(Real)> max;
  /// Integer sums over the ranks (the limbs of ExactSums: exact, so in any order).
  std::function<void(std::int64_t *, int)> sum_exact;
  /// Under numerics.scatter gather: the nodes other ranks hold too (per local node, its index
  /// in the plans' term lists, or -1; 1 where this rank owns it), and the plan that sums their
  /// terms over the ranks in the serial order (collective), so the shared nodes get the
  /// serial run's bits; then only the ghost nodes need the owners' values.
  std::vector<Index> shared_index;
  std::vector<char> owned;
  std::function<std::shared_ptr<OrderedNodeSum>(const std::vector<std::vector<NodeTerm>> &)>
      ordered_plan;
  std::function<void(const VectorView &)> gather_ghosts;
};

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
  std::vector<double> failed;       ///< sleepy CPs: 1 once switched to sliding, else 0
  std::vector<double> key1, key2;   ///< global face keys (last: gatherPoints sorts on them)

  /// \brief The per-CP scalars, in output order.
  std::vector<std::vector<double> *> scalars()
  {
    return {&area, &normal_force, &shear_force, &closure, &slip, &state, &failed, &key1, &key2};
  }
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

  /// \brief True on the cycles that search for new CPs: cycle 0, then every search_interval;
  /// with `search_gap: motion` instead the cycles planSearch found the contact nodes may have
  /// moved a quarter of the gap since the last search, or erosion exposed faces (docs/theory.md
  /// 3.1a).
  bool searchDue(long cycle) const;
  /// \brief Step 3, first of all (collective in a decomposed run), with `search_gap: motion`:
  /// the contact nodes' fastest speed bounds their motion since the last search; a search is
  /// due when the bound reaches a quarter of that search's gap (or faces were exposed), and
  /// then it sets the next gap for search_interval cycles at the current speed.
  void planSearch(const NodeFields &nodes, Real dt, long cycle);
  /// \brief The velocities were set, not integrated (a part released, 2.4): the implicit CPs'
  /// predicted end-of-step velocities (10.6) do not describe how the mesh moved, so the next
  /// step does without their feedback. Every CP alike, so every rank and every copy of a CP
  /// agree.
  void velocitiesSet();
  /// \brief The largest gap at which a CP is created at this search, for faces up to
  /// `face_size`: the deck's `search_gap`, the motion gap of planSearch, or `face_size`.
  Real searchGap(Real face_size) const;
  /// \brief Step 3: on search cycles, half-step face geometry and sorting bins.
  void sortIntoBins(const NodeFields &nodes, Real dt, long cycle);
  /// \brief Step 9: detection on search cycles, then every CP's force (sub-steps A-E), scattered
  /// atomically to a contact-force field and written to nodes.f_contact (its contact nodes;
  /// the other entries are left alone, at zero unless step 9b wrote them). Returns a failure naming a
  /// CP when the contact diverged (contact/ContactChecks.hpp: a non-finite force or history, a
  /// joint closure past 2 apertures, energy created); the forces are then not applied and the
  /// CP histories are restored.
  ContactFailure computeForces(const NodeFields &nodes, const BoundaryConditions &bc, Real dt,
                               long cycle, Real time);
  /// \brief Step 9 acts on the nodes of the contact faces (in 1D also on the node that orients
  /// a point face) after step 6 (integrate/LateNodes.hpp).
  void declareLateNodes(LateNodes &late) const;
  /// \brief Step 12: smallest explicit-contact time step (19) over the active explicit CPs, with
  /// their approach velocity of step 9 (v^n: after step 12 a ghost face's velocity is a step
  /// old, and a CP computed on two ranks must get one answer); `dt_element`, the horizon of the
  /// predicted closure,
  /// is the elements' own step of this cycle over all ranks (integrate/TimeStep.hpp) [s]. 1e300
  /// when no explicit CP limits.
  Real stableTimeStep(const NodeFields &nodes, const ElementFields &elements,
                      Real dt_element) const;
  /// \brief Before cycle 0: the limit (19) over the pairs the first search finds at x^0 with
  /// v^0, so that it holds from the first cycle of a CP that exists at t = 0 (bodies touching or
  /// within one step of each other). The pairs are then dropped: cycle 0 searches as always
  /// and the CPs it creates start from its own step. Collective in a decomposed run (the ghost
  /// faces must be set) [s]; 1e300 without explicit contacts.
  Real firstTimeStep(const NodeFields &nodes, const ElementFields &elements, Real dt_element);

  // Decomposed runs: the Solver sets the communication once and, on search cycles
  // (step 4), the ghost faces; each rank computes every CP with at least one of its own faces,
  // applies forces to its own faces only, and counts a CP in sums (energy, constraint solve,
  // outputs) on the rank of its face 1. energy(), storedEnergy() and maxCount() are then this
  // rank's parts, summed by the caller.
  void setComm(const ContactComm &comm);
  /// \brief Step 4 on search cycles: this rank's faces plus `ghosts` (ascending key, nodes in
  /// local + ghost numbering) become the contact faces; `node_count` = local + ghost nodes;
  /// `shared_nodes` (the nodes other ranks hold too) join the per-cycle node arrays, so their
  /// partial sums are always this rank's own.
  void setGhostFaces(const std::vector<GhostFaceDesc> &ghosts, Index node_count,
                     const std::vector<Index> &shared_nodes);
  /// \brief This rank's own faces (nodes in local numbering, `back` in 1D) for the exchange.
  std::vector<GhostFaceDesc> ownFaces() const;
  Index numOwnFaces() const { return _own.count; }
  /// \brief Element density behind each own face [kg/m^3] (the explicit time step (19)).
  std::vector<Real> ownFaceDensity(const ElementFields &elements) const;
  /// \brief Step 8: the ghost faces' element densities, in the order of setGhostFaces.
  void setGhostDensity(const std::vector<Real> &density);
  bool hasExplicit() const { return _has_explicit; }
  /// \brief Decomposed: the forces of the nodes other ranks hold are whole on every copy after
  /// computeForces() (summed over the ranks in the serial order), so step 9b has nothing to add.
  bool sharedNodesWhole() const { return _copy_node.extent(0) > 0; }
  /// \brief Whether a contact surface has the sleepy option (its CPs can fail).
  bool hasSleepy() const { return _has_sleepy; }
  /// \brief Whether a sleepy surface switches on a failure measure of its elements (not the
  /// time): its faces then need the measures every cycle (step 8 for the ghost faces).
  bool needsFailureMeasures() const { return _failure_from_elements; }
  /// \brief Before step 9: the failure measures of the elements behind this rank's faces.
  void updateFailureMeasures(const ElementFields &elements);
  /// \brief Failure measure `column` (0 plastic strain, 1 damage) behind each own face.
  std::vector<Real> ownFaceFailure(const ElementFields &elements, int column) const;
  /// \brief Step 8: the ghost faces' failure measure `column`, in the order of setGhostFaces.
  void setGhostFailure(int column, const std::vector<Real> &measure);
  /// \brief Sleepy CPs that have switched to sliding, over all ranks (collective).
  Index failedCount() const;
  /// \brief The elements eroded this cycle (global element ids, ascending, the same list on
  /// every rank): their faces leave the contact, and the faces they expose join their part's
  /// surfaces, at the next search (docs/theory.md 11.6).
  void elementsEroded(const std::vector<Index> &global_elements);
  /// \brief On a search cycle, before the search (and before the ghost-face exchange): the
  /// faces of the elements eroded since the last search leave, the faces they expose join.
  /// Returns whether the own faces' activity changed (ownFaces() then tells other ranks).
  bool applyErosion();
  /// \brief After a restart, before the ghost faces are rebuilt: the eroded elements saveState()
  /// wrote, and the own faces active as they were when it wrote them.
  void loadErosion(const RestartReader &in);
  /// \brief Per ghost face (order of setGhostFaces): 1 if a live CP uses it. Until the next
  /// search only these need fresh ghost data.
  std::vector<char> ghostFacesInPlanes() const;

  /// \brief Contact energy: work done on the joints by the mesh, = stored + dissipated [J].
  Real energy() const { return _work; }
  /// \brief Elastic energy stored in the joints now [J].
  Real storedEnergy() const { return _stored; }
  Real dissipatedEnergy() const { return _work - _stored; }
  Index count() const { return _cp.count; }
  /// \brief Largest contact-face diameter at the last search [m] (the same on every rank).
  Real largestFaceSize() const { return _geom.h_max; }
  Index maxCount() const { return _max_count; }
  /// \brief Searches for new CPs so far (3.1, 3.1a), set-up ones excluded.
  long searches() const { return _searches; }
  /// \brief Cycles whose ties were solved alone by conjugate gradients (10.8), and their
  /// iterations in all (the same on every rank).
  long tieSolves() const { return _tie_solves; }
  long tieIterations() const { return _tie_iterations; }
  const ContactFaceData &faces() const { return _faces; }
  const CommonPlaneData &planes() const { return _cp; }
  const std::vector<ContactFaceInfo> &faceInfo() const { return _info; }
  /// \brief The contact force of the last step on every node [N] (zero away from contact faces).
  const VectorView &nodalForces() const { return _fc; }
  /// \brief The live CPs, copied to the host.
  ContactPointsHost points() const;
  /// \brief The CPs (by face keys, 3.5, with their histories) and the contact accumulators,
  /// for a restart file (contact/ContactRestart.cpp). Collective over `comm` (MPI_COMM_NULL:
  /// one rank): every CP once (from the rank of its face 1), ascending face keys; each rank's
  /// own sums and impulses by rank and global node. `node_global`: the global id of each node
  /// slot, ghost nodes included; `v` the nodal velocities.
  void saveState(RestartWriter &out, MPI_Comm comm, const std::vector<Index> &node_global,
                 const VectorView &v) const;
  /// \brief The state saveState() wrote, at any rank count: each rank takes the CPs with a face
  /// of its own and the other of its own or a ghost face (the ghost faces are chosen first),
  /// found by key, their parameters averaged again (3.6). At the writer's rank count the ranks
  /// take their own partial sums back; at another, rank 0 takes their totals.
  void loadState(const RestartReader &in, MPI_Comm comm, const std::vector<Index> &node_global);
  /// \brief "common plane 3 between faces (element 12 face 1 of part 'a') and (element 40 face
  /// 3 of part 'b') of contact surface 'j' (option implicit)".
  std::string describe(Index cp) const;

private:
  void detect(const NodeFields &nodes, Real dt);
  void releaseSleepy(Real time);
  void computeVstar(const NodeFields &nodes, const BoundaryConditions &bc, Real dt);
  void jointForces(const NodeFields &nodes, Real dt);
  void constraintPasses(const NodeFields &nodes, Real dt);
  int tieSolve(const NodeFields &nodes, Real dt);
  int boundSolve(const NodeFields &nodes, Real dt);
  void tieApply(const NodeFields &nodes, Real dt, const VectorView &in, const VectorView &out);
  Real tieOperatorBound(const NodeFields &nodes, Real dt);
  void slideFriction(const NodeFields &nodes, Real dt);
  void recordApproach(const NodeFields &nodes);
  void tieScatter(const NodeFields &nodes, Real dt, const VectorView &force);
  void allocateTieRows();
  ContactFailure finish(const NodeFields &nodes, Real dt, long cycle, Real time);
  void resizeNodeArrays(size_t n);
  Real globalSum(Real local) const;
  /// \brief The N sums of a reduction over every rank's rows, rounded once (ExactSum.hpp): the
  /// same bits at any thread and rank count.
  template <int N>
  void exactTotals(ExactSums<N> &s, Real out[N]) const
  {
    if (_comm.sum_exact)
      _comm.sum_exact(&s.word[0][0], N * ExactSums<N>::kWords);
    for (int j = 0; j < N; ++j)
      out[j] = s.value(j);
  }
  /// \brief After a search or a restore: the CP count's peak and the self-contact CPs
  /// (collective in a decomposed run).
  void countPlanes();
  /// fn(face, its index among the ghosts of setGhostFaces) for every ghost face
  template <class Fn>
  void eachGhostFace(Fn &&fn) const
  {
    for (Index f = 0; f < _faces.count; ++f)
      if (_ghost_of_face[size_t(f)] >= 0)
        fn(f, size_t(_ghost_of_face[size_t(f)]));
  }

  int _dim = 2;
  bool _axisym = false;
  long _search_interval = 1;
  int _passes = 5;
  Real _search_gap = -1;
  bool _gap_from_motion = false; ///< `search_gap: motion`
  Real _motion = 0;              ///< bound on a contact node's motion since the last search [m]
  Real _motion_gap = 0;          ///< the gap the motion of the last search's speed asks for [m]
  long _searches = 0;            ///< searches()
  long _planned_cycle = -1;      ///< the cycle planSearch decided ...
  bool _planned_due = false;     ///< ... and whether it searches
  bool searchScheduled(long cycle) const;
  ContactFaceData _faces;
  std::vector<ContactFaceInfo> _info;
  ContactFaceData _own; ///< this rank's faces (= _faces without ghosts)
  std::vector<ContactFaceInfo> _own_info;
  std::vector<Index> _ghost_of_face; ///< per face: its index among the ghosts, or -1
  void loadRankPartials(const RestartReader &in, MPI_Comm comm,
                        const std::vector<Index> &node_global);
  ContactComm _comm;
  std::vector<std::string> _part_names;
  std::vector<std::string> _surface_labels; ///< per surface: "'name' (option o)", for messages
  CommonPlaneData _cp;
  FaceGeometryData _geom;
  FaceBins _bins;
  long _binned_cycle = -1;
  bool _has_explicit = false;
  bool _has_slide = false, _has_friction = false;
  std::vector<Index> _eroded;         ///< eroded elements, global ids, ascending (11.6)
  std::vector<Index> _eroded_pending; ///< ... eroded since the last search
  void activateExposedFaces();        ///< own faces active by _eroded
  Index _self_contact_planes = 0;     ///< self-contact CPs (11.5) since the last search, all ranks
  /// \brief Whether slide-line CPs may be live: a slide-line surface, or self-contact
  bool slideLinesLive() const { return _has_slide || _self_contact_planes > 0; }
  long _tie_solves = 0, _tie_iterations = 0; ///< see tieSolves()
  /// \brief The contact forces summed at the nodes in a fixed order (numerics.scatter
  /// gather, more than one thread): each joint CP, and each tie row of the velocity
  /// constraints, writes its nodes' shares into its slots (shareSlot()), and each contact node
  /// adds its slots in ascending CP or row order, the order of the one-thread plain adds, so
  /// the bits are those of one thread at any thread count. Guarded by
  /// Cli.GatherContactIsBitwiseThreadIndependent and Cli.GatherConstraintsAreBitwiseThreadIndependent.
  bool _gather_forces = false;
  /// \brief Per contact node (nodes_used), the slots it sums in ascending order: of the CPs
  /// (shareSlot(p, side, a)) or of the tie rows (shareSlot(c, side, a)), with the slots' values.
  struct NodeSlotRows
  {
    VectorView share;     ///< per slot: a node's share [N, or m/s for velocity increments]
    IndexView offsets;    ///< per contact node + 1: its slots' range
    IndexView slots;      ///< slots, ascending within each node's range
    long generation = -1; ///< the CP list (_cp_generation) they describe
    /// decomposed: the slots of the nodes other ranks hold, summed over the ranks in order (the
    /// nodes' ranges above are then empty)
    std::shared_ptr<OrderedNodeSum> across;
  };
  NodeSlotRows _share_rows; ///< the joint CPs' (one entry per CP)
  NodeSlotRows _tie_rows;   ///< the tie rows' (_tie_points entries per CP)
  long _cp_generation = 0;  ///< bumped whenever the CP list is replaced
  /// the nodes' slot lists of the current CP list, per_cp entries per CP (host)
  void buildSlotRows(int per_cp, NodeSlotRows &rows);
  /// out(k) = (from_zero ? 0 : out(k)) + each contact node's slots, in order (decomposed: the
  /// slots of every rank at a shared node)
  void assembleSlots(const NodeSlotRows &rows, const VectorView &out, bool from_zero);
  /// A nodal sum of this rank's CPs made whole over the ranks: after assembleSlots(rows) only
  /// the ghost nodes are missing (the shared ones are whole); without rows the shared-node
  /// partial sums of sum_nodes.
  void sumOverRanks(const NodeSlotRows *rows, const VectorView &f) const;
  /// per local node: 1 at the shared nodes this rank does not own, when their contact forces
  /// are whole on every copy (ContactComm::ordered_plan; else empty)
  DeviceView<std::uint8_t *> _copy_node;
  /// `rows` (per_cp entries per CP) up to date for the current CP list, under _gather_forces;
  /// else null (the atomic adds)
  const NodeSlotRows *slotRows(int per_cp, NodeSlotRows &rows);
  Index _constraint_planes = 0; ///< CPs of the velocity-constraint options, all ranks, ditto
  /// \brief Whether the correction passes run (10.8): a CP of a velocity-constraint option on
  /// some rank. Without one they would only solve for zero forces, at the cost of passes over every CP.
  bool constraintsLive() const { return _constraint_planes > 0; }
  bool _has_sleepy = false;            ///< a sleepy surface: its CPs switch (releaseSleepy)
  bool _failure_from_elements = false; ///< ... on a measure of their elements, not the time
  IndexView _damage_slot;              ///< per material: its history slot of damage, or -1
  VectorView _share; ///< per node (component 0): friction rows on it (ContactFriction.cpp)
  VectorView _cg_x, _cg_r, _cg_p, _cg_z, _cg_ap, _cg_b; ///< conjugate-gradient vectors of the ties
  VectorView _cg_w;    ///< per tie row: |V1| + |V2| of v*, the scale of the solve's round-off stop
  VectorView _cg_s;    ///< per tie row: D^(-1/2), the bound solve's scaling
  VectorView _cg_t;    ///< per tie row: scratch of the bound solve
  VectorView _cg_best; ///< per tie row: the bound solve's best iterate (its divergence guard)
  /// per tie row: the diagonal of the tie operator (tieDiagonal; components 0-2, the normal
  /// tie's in 3), fixed within a cycle: the conjugate gradients compute it once, not per pass
  DeviceView<Real *[4]> _cg_diag;
  IndexView _tie_mode; ///< per tie row: which velocity constraint it imposes this cycle
  TieWeights _tie;     ///< per tie row: the face weights at its point (step 9, A-D)
  int _tie_points = 1; ///< tie rows per CP: 2 in 2D (tieWeights2D), else 1

  VectorView _vstar;   ///< v* of 10.6 (contact nodes; other entries unused)
  VectorView _dv;      ///< velocity increments of one constraint pass
  VectorView _fc;      ///< contact force of this cycle (contact nodes) [N]
  VectorView _impulse; ///< last cycle's contact impulse fc dt (contact nodes) [N s]
  DeviceView<CpState *>
      _state_before; ///< CP histories at the start of step 9 (restored on failure)
  Real _work = 0;    ///< contact energy [J]
  // energy-creation check (ContactFinish.cpp): the joint CPs' net work, its peak, the sum of
  // its |increments|, the peak stored energy, and the step of the last cycle
  RealView _cp_work, _cp_carried; ///< per CP this cycle: its net work, the work it carries
  RealView _approach; ///< per CP: its normal approach velocity in step 9, for the step-12 limit
  Real _joint_work = 0, _joint_work_peak = 0, _joint_work_gross = 0, _stored_peak = 0;
  Real _slide_work = 0, _slide_work_peak = 0; ///< the slide lines' net work and its peak
  Real _slide_carried = 0; ///< the work the slide lines carried between the bodies, summed |.|
  Real _dt_prev = 0;
  Real _stored = 0;
  Index _max_count = 0;
};

} // namespace scpdyn
