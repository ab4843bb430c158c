#pragma once
#include <array>
/// \file Solver.hpp
/// \brief The explicit Lagrangian solver: runs the 13-step cycle of the paper (docs/theory.md
/// 2.2) in Solver::cycle() on the Model that set-up built (model/Model.hpp), and holds what
/// changes from cycle to cycle: time, time step, energies, timers.
#include "core/Timers.hpp"
#include "integrate/LateNodes.hpp"
#include "integrate/NodeUpdate.hpp"
#include "integrate/TimeStep.hpp"
#include "model/Model.hpp"

#include <mpi.h>

#include <memory>

namespace scpdyn
{

class Outputs;
class ContactSystem;
class RestartWriter;
class RestartReader;
struct DomainDecomposition;

/// \brief A run that cannot go on (inverted element, non-finite state); the message names
/// the element and cycle. main() exits with status 3 after the outputs are flushed.
struct SimulationError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

/// \brief Energies of the whole model [J] (per metre in plane strain, per radian axisymmetric).
struct EnergyReport
{
  Real kinetic = 0;
  Real internal = 0;
  Real hourglass = 0;
  Real external_work = 0;
  Real contact = 0;
  Real balance_error = 0; ///< (E - E0 - W_ext) / reference, on the leapfrog's conserved energy
  Real momentum[3] = {0, 0, 0};
  Real contact_dissipation = 0; ///< part of `contact` dissipated (contact - stored)
  Real damping = 0;             ///< energy the settling stage's damping dissipated (>= 0) [J]
  Real eroded = 0;              ///< internal + hourglass energy eroded elements held [J]
  long eroded_elements = 0;     ///< elements eroded so far, over all ranks
};

class Solver
{
public:
  /// \brief Set-up (steps 1 and 2): builds the Model (model/Model.hpp) and the first time step.
  /// With more than one rank in `comm` the mesh is decomposed: every rank reads the same deck
  /// and keeps its own elements, nodes and faces; every member function below is then
  /// collective over `comm` unless it says otherwise. One rank runs exactly the serial code.
  explicit Solver(const Deck &deck, MPI_Comm comm = MPI_COMM_WORLD);
  ~Solver();

  /// \brief Run to the end time with outputs in `output_dir`; returns the number of cycles.
  /// A signal caught by driver/Interruption.hpp on any rank stops it at the end of the cycle
  /// in whose time-step reduction the signal is first seen, on every rank alike, with complete
  /// outputs of that cycle (interruptedBy() says which signal).
  /// With `restart_file` the run continues from that restart file (loadState()).
  long run(const std::string &output_dir, const std::string &restart_file = "");
  /// \brief Everything the next cycle reads from the last one (driver/Restart.cpp): one place
  /// for the state a restart file holds, in the global numbering (any rank count reads it).
  void saveState(RestartWriter &out) const;
  /// \brief The state saveState() wrote, in place of the initial state set-up built.
  void loadState(const RestartReader &in);
  /// \brief One cycle of the 13 steps.
  void cycle();

  Real time() const { return _time; }
  Real dt() const { return _dt; }
  /// \brief The deck's gravity at time t: its vector times its function, if any [m/s^2].
  std::array<Real, 3> gravityAt(Real t) const;
  /// \brief The time step of the next cycle (before the first cycle: the first time step).
  Real nextDt() const { return _dt_next; }
  /// \brief The smallest time step the run has taken, the cycle that took it (0-based; it
  /// starts at `time`) and what set it.
  struct SmallestStep
  {
    Real dt = 1e300, time = 0;
    long cycle = -1;
    std::string control;
  };
  const SmallestStep &smallestStep() const { return _smallest_step; }
  /// \brief The first time step (cycle 0, at time 0) and what set it, described as
  /// smallestStep() describes its step.
  const SmallestStep &firstStep() const { return _first_step; }
  /// \brief The signal (SIGINT, SIGTERM) that stopped run() before the end, the same on every
  /// rank; 0 when the run was not interrupted (driver/Interruption.hpp).
  int interruptedBy() const { return _interrupted_by; }
  /// \brief The element controls step 6 of the next cycle runs with (the deck's, this dt).
  ElementControls elementControls() const
  {
    ElementControls c = _m.controls;
    c.dt = _dt;
    c.half_time = _time + 0.5 * _dt;
    return c;
  }
  long cycles() const { return _cycle; }
  /// \brief This cycle's step 12 damps (the settling stage, docs/theory.md 2.4): before its
  /// end, and the cycle after it (coefficient 0) that books the last damped impulse's second
  /// half.
  bool damped() const { return _damped; }
  /// \brief Every element is eroded: the run ended (docs/theory.md 11.6).
  bool allEroded() const { return _all_eroded; }
  const Deck &deck() const { return _m.deck; }
  /// \brief This rank's mesh (the whole mesh on one rank).
  const HostMesh &mesh() const { return _m.mesh; }
  const NodeFields &nodes() const { return _m.nodes; }
  const ElementFields &elements() const { return _m.elems; }
  const std::vector<GaugeSlot> &gauges() const { return _m.gauges; }
  const BoundaryConditions &boundaryConditions() const { return _m.bc; }
  const StepTimers &timers() const { return _timers; }
  /// \brief Wall-clock time spent in cycle() so far on this rank [s] (the steps' timers plus
  /// whatever runs between them).
  double cycleWallTime() const { return _cycle_wall; }
  const std::vector<ElementGroup> &groups() const { return _m.groups; }
  const std::vector<MaterialParams> &materialParams() const { return _m.materials_host; }
  /// \brief The materials as the element step reads them (device copy of materialParams()).
  const DeviceView<MaterialParams *> &materials() const { return _m.materials; }
  /// \brief Device element id of a mesh element id (parts numbered in deck order).
  Index deviceElement(Index mesh_element) const
  {
    return _m.host_to_device_element[size_t(mesh_element)];
  }
  /// \brief Current energies and momentum of the whole model (reduces over elements and
  /// ranks; not free).
  EnergyReport energies() const;
  /// \brief Current gauge values, in the order of gauges(), on every rank (each from the rank
  /// that owns its node or element).
  std::vector<Real> gaugeValues() const;
  /// \brief Step 12 inside step 6 (inactive with numerics.node_update separate, or with
  /// atomic adds on more than one thread).
  const NodeSweep &nodeSweep() const { return _m.sweep; }
  /// \brief Nodes step 6 integrates, over all ranks (0 without the sweep).
  long sweepNodeCount() const { return _m.sweep_nodes; }
  /// \brief The common-plane contact, or null when the deck has no contact surfaces.
  const ContactSystem *contact() const { return _m.contact.get(); }

  // Domain decomposition; the defaults describe the serial run.
  MPI_Comm comm() const { return _m.comm; }
  int rank() const { return _m.rank; }
  int numRanks() const { return _m.num_ranks; }
  /// \brief The decomposition, or null on one rank.
  const DomainDecomposition *decomposition() const { return _m.dd.get(); }
  /// \brief Global id of a local node / mesh element (identity on one rank).
  Index globalNode(Index local) const { return _m.globalNode(local); }
  Index globalElement(Index mesh_element) const { return _m.globalElement(mesh_element); }
  /// \brief Nodes and elements of the whole model (summed over ranks).
  long globalNodeCount() const { return _m.globalNodeCount(); }
  long globalElementCount() const { return _m.globalElementCount(); }
  /// \brief What set-up built.
  const Model &model() const { return _m; }

private:
  void startCycles();
  bool reachedEnd() const;
  /// \brief The end of an interrupted run, on every rank at the end of the same cycle: a restart
  /// file (the state is then that of a whole cycle on every rank), the last frame, rows and
  /// summary.json.
  void endInterruptedRun(Outputs &out);
  void jointGaugeValues(std::vector<Real> &out) const;
  void ensureNodeCapacity(Index count);
  /// \brief Step 4's choice of the ghost faces and nodes, at this cycle's positions (collective).
  void rebuildGhostFaces();
  void restrictGhosts();
  /// \brief Global id of every node slot of the node Views, ghost nodes included (-1: unused).
  std::vector<Index> nodeSlotGlobalIds() const;
  void stepExchangeContactPartials(); // 9b
  void sumSharedFaceLoads();          // in 10
  void collectiveCheck(const std::string &local_error) const;
  void checkEarlyNodes() const;
  /// \brief "contact surface 'j' (option explicit)" if the element has a contact face, else "".
  std::string contactSurfaceOf(Index mesh_element) const;
  TimeStepControls timeStepControls() const { return {_m.deck.courant, _m.deck.dt_max}; }
  Index meshElementOfDevice(Index device) const { return _m.meshElementOfDevice(device); }

  // the cycle's steps (numbers as in the paper)
  void stepSortIntoBins();             // 3
  void stepExchangeFaceConnectivity(); // 4
  void stepZeroForces();               // 5
  void stepElementSolvers();           // 6
  void stepErodeElements();            // 6b: book and announce the elements step 6 eroded
  void stepExchangeSharedNodeForces(); // 7
  void stepExchangeGhostFaceData();    // 8
  void stepContactForces();            // 9
  void stepFaceBoundaryConditions();   // 10
  void stepNodeBoundaryConditions();   // 11
  void stepUpdateNodes();              // 12

  Model _m;

  bool _forces_zeroed = false; ///< step 12 left f_int = 0 and f_ext = m g for step 5
  bool _check_sweep = nodeSweepCheckEnabled(); ///< LateNodes.hpp's check mode
  EarlyNodeSnapshot _early_snapshot;
  TimeStepLimits _limits; ///< this cycle's limits on the next step, this rank
  Real _time = 0;
  Real _dt = 0;
  Real _dt_next = 0;
  SmallestStep _smallest_step, _next_step; ///< the smallest step taken; the next one's control
  SmallestStep _first_step; ///< cycle 0's step and what set it (the pre-flight block)
  int _stop_signal = 0;     ///< a signal any rank had at the last time-step reduction
  int _interrupted_by = 0;  ///< the signal that stopped run() before the end
  void recordNextStep(MPI_Comm comm);
  int _gravity_function = -1;          ///< index into the deck's functions, or -1: constant gravity
  std::array<Real, 3> _gravity;        ///< the gravity of this cycle, g(t^n) [m/s^2]
  std::array<Real, 3> _gravity_next{}; ///< the next cycle's, g(t^n + dt) [m/s^2]
  long _cycle = 0;
  Real _external_work = 0;
  Real _kinetic_mid = 0; ///< 1/2 sum m v^n.v^{n+1} of the last step
  Real _initial_energy = 0;
  Real _energy_scale = 0;    ///< largest |energy| seen, the balance error's reference
  Real _eroded_energy = 0;   ///< internal + hourglass energy of the eroded elements [J]
  long _eroded_elements = 0; ///< elements eroded so far, over all ranks
  bool _all_eroded = false;  ///< no element is left: the run ends (docs/theory.md 11.6)
  NodeSums _last_sums;
  // the settling stage (docs/theory.md 2.4)
  bool _damped = false;      ///< this cycle's step 12 damps
  bool _damped_last = false; ///< the last cycle's step 12 damped with a coefficient > 0
  Real _damping_alpha = 0;   ///< this cycle's coefficient [1/s]
  Real _damping_work = 0;    ///< work of the damping so far (<= 0) [J]
  NodeSweep _no_sweep;       ///< the inactive sweep of a damped cycle (its step 12 is one pass)
  /// \brief Step 6 integrates the early nodes this cycle (the sweep is off while damped).
  bool fused() const { return _m.sweep.active && !_damped; }
  void releaseParts();
  StepTimers _timers;
  double _cycle_wall = 0;
};

} // namespace scpdyn
