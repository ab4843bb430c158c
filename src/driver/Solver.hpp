#pragma once
/// \file Solver.hpp
/// \brief The explicit Lagrangian solver: owns the problem's data and runs the 13-step cycle
/// of the paper (scp-method.md section 2) in Solver::cycle().
#include "bc/BoundaryConditions.hpp"
#include "core/Fields.hpp"
#include "core/Timers.hpp"
#include "element/ElementForces.hpp"
#include "integrate/NodeUpdate.hpp"
#include "integrate/TimeStep.hpp"
#include "input/Deck.hpp"
#include "mesh/HostMesh.hpp"

#include <mpi.h>

#include <memory>

namespace scpdyn
{

class Outputs;
class ContactSystem;
struct SolverDecomposition;

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
};

/// \brief A gauge resolved to a node or element id and quantity codes.
struct GaugeSlot
{
  std::string column;
  bool on_element = false;
  Index id = -1;
  int quantity = 0;
  int joint = -1; ///< joint gauges: index of the gauge's point and radius (else -1)
};

class Solver
{
public:
  /// \brief Set-up (steps 1 and 2): meshes, sets, materials, BCs, initial state. With more
  /// than one rank in `comm` the mesh is decomposed (issue 4): every rank reads the same deck
  /// and keeps its own elements, nodes and faces; every member function below is then
  /// collective over `comm` unless it says otherwise. One rank runs exactly the serial code.
  explicit Solver(const Deck &deck, MPI_Comm comm = MPI_COMM_WORLD);
  ~Solver();

  /// \brief Run to the end time with outputs in `output_dir`; returns the number of cycles.
  long run(const std::string &output_dir);
  /// \brief One cycle of the 13 steps.
  void cycle();

  Real time() const { return _time; }
  Real dt() const { return _dt; }
  /// \brief The element controls step 6 of the next cycle runs with (the deck's, this dt).
  ElementControls elementControls() const
  {
    ElementControls c = _controls;
    c.dt = _dt;
    c.half_time = _time + 0.5 * _dt;
    return c;
  }
  long cycles() const { return _cycle; }
  const Deck &deck() const { return _deck; }
  /// \brief This rank's mesh (the whole mesh on one rank).
  const HostMesh &mesh() const { return _mesh; }
  const NodeFields &nodes() const { return _nodes; }
  const ElementFields &elements() const { return _elems; }
  const std::vector<GaugeSlot> &gauges() const { return _gauges; }
  const BoundaryConditions &boundaryConditions() const { return _bc; }
  const StepTimers &timers() const { return _timers; }
  /// \brief Wall-clock time spent in cycle() so far on this rank [s] (the steps' timers plus
  /// whatever runs between them).
  double cycleWallTime() const { return _cycle_wall; }
  const std::vector<ElementGroup> &groups() const { return _groups; }
  const std::vector<MaterialParams> &materialParams() const { return _materials_host; }
  /// \brief The materials as the element step reads them (device copy of materialParams()).
  const DeviceView<MaterialParams *> &materials() const { return _materials; }
  /// \brief Device element id of a mesh element id (parts numbered in deck order).
  Index deviceElement(Index mesh_element) const { return _host_to_device_element[size_t(mesh_element)]; }
  /// \brief Current energies and momentum of the whole model (reduces over elements and
  /// ranks; not free).
  EnergyReport energies() const;
  /// \brief Current gauge values, in the order of gauges(), on every rank (each from the rank
  /// that owns its node or element).
  std::vector<Real> gaugeValues() const;
  /// \brief Step 12 inside step 6 (inactive with numerics.node_update separate, or with
  /// atomic adds on more than one thread).
  const NodeSweep &nodeSweep() const { return _sweep; }
  /// \brief Nodes step 6 integrates, over all ranks (0 without the sweep).
  long sweepNodeCount() const { return _sweep_nodes; }
  /// \brief The common-plane contact, or null when the deck has no contact surfaces.
  const ContactSystem *contact() const { return _contact.get(); }

  // Domain decomposition (issue 4); the defaults describe the serial run.
  MPI_Comm comm() const { return _comm; }
  int rank() const { return _rank; }
  int numRanks() const { return _num_ranks; }
  /// \brief The decomposition, or null on one rank.
  const SolverDecomposition *decomposition() const { return _dd.get(); }
  /// \brief Global id of a local node / mesh element (identity on one rank).
  Index globalNode(Index local) const;
  Index globalElement(Index mesh_element) const;
  /// \brief Nodes and elements of the whole model (summed over ranks).
  long globalNodeCount() const;
  long globalElementCount() const;

private:
  void setupMesh();
  void setupFields();
  void setupSets();
  void setupBoundaryConditions();
  void setupGauges();
  void jointGaugeValues(std::vector<Real> &out) const;
  void setupInitialState();
  void setupContact();
  void decompose();
  void finishDecomposition();
  void setupContactGhosts();
  void ensureNodeCapacity(Index count);
  void restrictGhosts();
  void checkSetNotEmpty(std::size_t local_count, const std::string &message) const;
  void unifyNodeSet(std::vector<Index> &nodes) const;
  void stepExchangeLoadPartials(); // 10b
  void collectiveCheck(const std::string &local_error) const;
  Index meshElementOfDevice(Index device) const;

  // the cycle's steps (numbers as in the paper)
  void stepSortIntoBins();             // 3
  void stepExchangeFaceConnectivity(); // 4
  void stepZeroForces();               // 5
  void stepElementSolvers();           // 6
  void stepExchangeSharedNodeForces(); // 7
  void stepExchangeGhostFaceData();    // 8
  void stepContactForces();            // 9
  void stepFaceBoundaryConditions();   // 10
  void stepNodeBoundaryConditions();   // 11
  void stepUpdateNodes();              // 12
  void setupNodeSweep();
  void checkEarlyNodes() const;
  TimeStepControls timeStepControls() const { return {_deck.courant, _deck.dt_max}; }

  Deck _deck;
  HostMesh _mesh;
  std::vector<HostFace> _external_faces;
  std::map<std::string, std::vector<Index>> _node_sets;
  std::map<std::string, std::vector<HostFace>> _face_sets;

  NodeFields _nodes;
  ElementFields _elems;
  NodeCorners _corners;
  NodeSweep _sweep; ///< step 12 of the early nodes inside step 6 (numerics.node_update fused)
  long _sweep_nodes = 0; ///< its nodes over all ranks
  std::vector<ElementGroup> _groups;
  DeviceView<MaterialParams *> _materials;
  std::vector<MaterialParams> _materials_host;
  BoundaryConditions _bc;
  bool _external_loads = true; ///< hasExternalLoads(): steps 5 and 12 handle f_ext
  bool _forces_zeroed = false; ///< step 12 left f_int = 0 and f_ext = m g for step 5
  ElementControls _controls;
  std::vector<GaugeSlot> _gauges;
  /// joint gauges: the CPs within `radius` [m] (0: half the largest contact face) of the node
  /// nearest the gauge's point (device id on the rank that owns it, else -1)
  struct JointGauge
  {
    Index anchor = -1;
    Real radius = 0;
  };
  std::vector<JointGauge> _joint_gauges;
  IndexView _gauge_id;       ///< device copies of the gauge slots
  IndexView _gauge_code;     ///< quantity code, + 100 for element quantities
  std::vector<int> _part_spec;                 ///< deck parts[] entry of every mesh part
  std::vector<Index> _host_to_device_element;  ///< mesh element id -> device element id

  Real _time = 0;
  Real _dt = 0;
  Real _dt_next = 0;
  bool _check_sweep = nodeSweepCheckEnabled(); ///< LateNodes.hpp's check mode
  EarlyNodeSnapshot _early_snapshot;
  TimeStepLimits _limits; ///< this cycle's limits on the next step, this rank
  long _cycle = 0;
  Real _external_work = 0;
  Real _kinetic_mid = 0;     ///< 1/2 sum m v^n.v^{n+1} of the last step
  Real _initial_energy = 0;
  Real _energy_scale = 0;    ///< largest |energy| seen, the balance error's reference
  NodeSums _last_sums;
  StepTimers _timers;
  std::shared_ptr<ContactSystem> _contact; ///< shared_ptr: no complete type needed in ~Solver

  MPI_Comm _comm = MPI_COMM_WORLD;
  int _rank = 0, _num_ranks = 1;
  std::shared_ptr<SolverDecomposition> _dd; ///< null on one rank
  std::unique_ptr<HostMesh> _global_mesh;   ///< the whole mesh during set-up (decomposed runs)
  double _cycle_wall = 0;
};

} // namespace scpdyn
