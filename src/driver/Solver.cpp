// The 13-step cycle of the paper (docs/theory.md 2.2), read top to bottom in Solver::cycle().
#include "driver/Solver.hpp"

#include "bc/TimeFunctions.hpp"
#include "contact/ContactSystem.hpp"
#include "core/InputError.hpp"
#include "parallel/Decomposition.hpp"
#include "driver/Interruption.hpp"
#include "driver/Outputs.hpp"
#include "driver/Restart.hpp"
#include "io/RestartFile.hpp"
#include "parallel/Mpi.hpp"

#include <chrono>
#include <cmath>
#include <sstream>

namespace scpdyn
{

Solver::Solver(const Deck &deck, MPI_Comm comm) : _m(deck, comm)
{
  for (size_t f = 0; f < _m.deck.functions.size(); ++f)
    if (_m.deck.functions[f].name == _m.deck.gravity_function)
      _gravity_function = int(f);
  _gravity = gravityAt(0);
  startCycles();
}

std::array<Real, 3> Solver::gravityAt(Real t) const
{
  std::array<Real, 3> g = _m.deck.gravity;
  if (_gravity_function >= 0)
  {
    const Real scale = evaluate(_m.deck.functions[size_t(_gravity_function)], t);
    for (Real &c : g)
      c *= scale;
  }
  return g;
}

Solver::~Solver() = default;

void Solver::startCycles()
{
  // the first time step, and the energies the balance starts from
  NodeSums s = nodeSums(_m.nodes, _m.dd ? _m.dd->owned_device : IndexView());
  TimeStepLimits first;
  first.element = _m.initial_element_step;
  const MPI_Comm comm = _m.dd ? _m.comm : MPI_COMM_NULL;
  if (_m.contact && _m.contact->hasExplicit())
  { // (19) from the first cycle of the CPs that exist at t = 0 (the pairs of cycle 0's search)
    stepExchangeFaceConnectivity();
    stepExchangeGhostFaceData();
    first.contact =
        _m.contact->firstTimeStep(_m.nodes, _m.elems, elementStep(first, timeStepControls(), comm));
  }
  _dt_next = nextTimeStep(first, timeStepControls(), s, comm);
  _limits = first;
  recordNextStep(comm);
  _first_step = _next_step;
  _first_step.cycle = 0;
  _first_step.time = _time;
  _last_sums = s;
  _kinetic_mid = s.kinetic;
  _initial_energy = 0;
  _initial_energy = s.kinetic + energies().internal;
  _energy_scale = std::abs(_initial_energy);
}
void Solver::cycle()
{
  const auto start = std::chrono::steady_clock::now();
  // No shortened last step: a sudden change of dt changes the leapfrog's conserved energy
  // (an artefact in the balance); the run ends on the first cycle at or past the end time.
  _dt = _dt_next;
  const SettlingSpec &settling = _m.deck.settling;
  _damped = settling.active() && (_time < settling.end || _damped_last);
  _damping_alpha = _time < settling.end ? settling.damping : 0;
  if (_next_step.dt == _dt && _dt < _smallest_step.dt) // the smallest step, now taken
  {
    _smallest_step = _next_step;
    _smallest_step.cycle = _cycle;
    _smallest_step.time = _time;
  }
  _gravity = gravityAt(_time);
  _gravity_next = gravityAt(_time + _dt); // what step 12 clears f_ext to
  stepSortIntoBins();                     // 3: cycle begins; contact faces into bins when due
  stepExchangeFaceConnectivity();         // 4: bounding boxes, occupied bins, ghost-face lists
  stepZeroForces();                       // 5: zero forces; external-face variables
  stepElementSolvers();                   // 6: half-step kinematics, materials, internal forces
      //    (and step 12 of the nodes 7-11 leave alone: NodeSweep)
  stepExchangeSharedNodeForces(); // 7: sum internal forces on shared nodes
  stepFaceBoundaryConditions();   // 10: pressure on faces, and on shared nodes their sum,
  stepNodeBoundaryConditions();   // 11: nodal forces (velocities are imposed in 12): both
                                  //     before 9, whose velocity correction sees every force
  stepExchangeGhostFaceData();    // 8: ghost faces get x, v, the forces, face masses
  stepContactForces();            // 9: common planes: detection, geometry, forces
  stepExchangeContactPartials();  // 9b: sum contact forces on shared nodes
  stepUpdateNodes();              // 12: v, x; next stable time step
  _time += _dt;                   // 13: back to 3 (output by the caller)
  ++_cycle;
  _damped_last = _damped && _damping_alpha > 0;
  if (!_m.release.groups.empty())
    releaseParts(); // the parts whose release time this cycle reached
  _cycle_wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Steps 4 and 8 (ghost contact faces) are in src/driver/ContactGhosts.cpp, 7, 9b and the load sum of 10 in
// src/driver/SharedNodeSteps.cpp; set-up in src/model/.

void Solver::stepSortIntoBins()
{
  if (!_m.contact)
    return;
  ScopedStep t(_timers, "03_sort_into_bins");
  _m.contact->planSearch(_m.nodes, _dt, _cycle); // whether this cycle searches
  // a search cycle begins with the faces erosion has exposed or removed since the last one
  // (decomposed: before step 4 tells the other ranks)
  if (_m.contact->searchDue(_cycle) && _m.contact->applyErosion() && _m.dd)
    _m.dd->own_faces = _m.contact->ownFaces();
  // decomposed: the search sorts in step 9, once the ghost faces have this cycle's data
  if (_m.dd)
    return;
  _m.contact->sortIntoBins(_m.nodes, _dt, _cycle);
}

void Solver::stepContactForces()
{
  if (!_m.contact)
    return;
  ScopedStep t(_timers, "09_contact_forces");
  _m.contact->updateFailureMeasures(_m.elems);
  const ContactFailure f = _m.contact->computeForces(_m.nodes, _m.bc, _dt, _cycle, _time);
  collectiveCheck(f.failed ? f.message : std::string());
  if (_m.dd && _m.contact->searchDue(_cycle) && !_m.contact->searchDue(_cycle + 1))
    restrictGhosts(); // until the next search, ghost data only for the faces of live CPs
}

void Solver::stepZeroForces()
{
  ScopedStep t(_timers, "05_zero_forces");
  if (!_forces_zeroed) // else the last cycle's step 12 did it in its sweep over the nodes
    zeroForces(_m.nodes, _gravity.data(), _m.external_loads);
  _forces_zeroed = false;
}

void Solver::stepElementSolvers()
{
  ScopedStep t(_timers, "06_element_solvers");
  const ElementControls controls = elementControls();
  if (fused()) // step 12 of the early nodes, in this step's sweep
  {
    _m.sweep.node = nodeIntegrator(_m.nodes, _m.bc.velocity_current, _dt,
                                   _m.dd ? _m.dd->owned_device : IndexView(), _gravity_next.data());
    _m.sweep.loads = _m.external_loads;
  }
  const ElementStepResult r =
      computeElementForces(_m.groups, controls, _m.nodes, _m.elems, _m.materials, _m.corners,
                           fused() ? _m.sweep : _no_sweep);
  if (controls.gather)
    gatherCornerForces(_m.nodes, _m.corners);
  if (controls.erosion)
    stepErodeElements();
  std::string error;
  if (!r.ok())
  {
    std::ostringstream os;
    if (!r.finite)
      os << "non-finite element state at cycle " << _cycle << ", time " << _time;
    else
    {
      os << "element " << globalElement(meshElementOfDevice(r.inverted)) << " inverted at cycle "
         << _cycle << ", time " << _time << " s (dt " << _dt << " s): ";
      const std::string surface = contactSurfaceOf(meshElementOfDevice(r.inverted));
      if (!surface.empty())
        os << "it has a face on " << surface
           << ": check that joint (aperture, moduli, C_safe) and its time step, or reduce "
              "time.courant";
      else
        os << "reduce time.courant or check the loading";
    }
    error = os.str();
  }
  collectiveCheck(error); // every rank stops before the shared-node exchange
  if (!_all_eroded)       // else the last element limit stays: the run ends with this cycle
    _limits.element = r.dt;
  if (_check_sweep && fused())
    snapshotEarlyNodes(_m.nodes, _early_snapshot);
}

void Solver::stepFaceBoundaryConditions()
{
  ScopedStep t(_timers, "10_face_bcs");
  updateLoadValues(_m.bc, _time + 0.5 * _dt);
  applyFaceLoads(_m.bc, _m.nodes, _dt, _m.deck.dimension, _m.deck.geometry);
  sumSharedFaceLoads();
}

void Solver::stepNodeBoundaryConditions()
{
  ScopedStep t(_timers, "11_node_bcs");
  applyNodeForces(_m.bc, _m.nodes);
}

void Solver::stepUpdateNodes()
{
  ScopedStep t(_timers, "12_update_nodes");
  if (_check_sweep && fused())
    checkEarlyNodes();
  updateVelocityValues(_m.bc, _time + _dt);
  const MassDamping damping = massDamping(_damping_alpha, _dt);
  _last_sums = updateNodes(_m.nodes, _m.bc, _dt, _m.deck.dimension,
                           _m.dd ? _m.dd->owned_device : IndexView(), _m.external_loads,
                           _gravity_next.data(), fused() ? &_m.sweep.late_runs : nullptr,
                           _damped ? &damping : nullptr);
  if (fused()) // the early nodes' sums, from step 6
    _last_sums += sweepSums(_m.sweep);
  _forces_zeroed = true;
  const MPI_Comm comm = _m.dd ? _m.comm : MPI_COMM_NULL;
  _limits.contact = 1e300;
  if (_m.contact && _m.contact->hasExplicit()) // (19), from v^{n+1}
    _limits.contact = _m.contact->stableTimeStep(_m.nodes, _m.elems,
                                                 elementStep(_limits, timeStepControls(), comm));
  _stop_signal = receivedSignal(); // becomes any rank's, in the reduction of the step
  _dt_next = nextTimeStep(_limits, timeStepControls(), _last_sums, comm, &_stop_signal);
  recordNextStep(comm);
  _external_work += _last_sums.external_work;
  _damping_work += _last_sums.damping_work;
  _kinetic_mid = _last_sums.kinetic_mid;
  _energy_scale = std::max(_energy_scale, _last_sums.kinetic);
  if (!std::isfinite(_last_sums.kinetic))
  {
    std::ostringstream os;
    os << "non-finite nodal velocities at cycle " << _cycle << ", time " << _time;
    throw SimulationError(os.str());
  }
}

void Solver::releaseParts()
{
  bool due = false; // the same on every rank: they have the same groups (ModelSetup)
  for (const PartRelease::Group &g : _m.release.groups)
    due = due || g.due(_time);
  if (!due)
    return;
  NodeSums gained =
      releaseDue(_m.release, _time, _m.nodes, _m.dd ? _m.dd->owned_device : IndexView());
  if (_m.contact)
    _m.contact->velocitiesSet();
  if (_m.dd) // every rank releases in the same cycle: the sums are collective
  {
    Real sum[4] = {gained.kinetic, gained.momentum[0], gained.momentum[1], gained.momentum[2]};
    allReduceSum(sum, 4, _m.comm);
    gained.kinetic = gained.kinetic_mid = gained.external_work = sum[0];
    for (int i = 0; i < 3; ++i)
      gained.momentum[i] = sum[1 + i];
  }
  // the released velocity is given, not earned: its kinetic energy is booked as external work
  // (docs/theory.md 2.4), and the energies of this cycle's row include it
  _external_work += gained.external_work;
  _kinetic_mid += gained.kinetic_mid;
  _last_sums.kinetic += gained.kinetic;
  _last_sums.kinetic_mid += gained.kinetic_mid;
  for (int i = 0; i < 3; ++i)
    _last_sums.momentum[i] += gained.momentum[i];
  _energy_scale = std::max(_energy_scale, _last_sums.kinetic);
}

void Solver::recordNextStep(MPI_Comm comm)
{
  // what sets a step that would be the smallest yet (cycle() books it once it is taken): the
  // elements' step over all ranks (with the deck's cap), else the contact
  if (!(_dt_next < _smallest_step.dt))
    return;
  const TimeStepControls ctl = timeStepControls();
  Real element = cappedElementStep(_limits, ctl);
  if (comm != MPI_COMM_NULL)
    MPI_Allreduce(MPI_IN_PLACE, &element, 1, MPI_DOUBLE, MPI_MIN, comm);
  _next_step.dt = _dt_next;
  _next_step.control = _dt_next < element      ? "contact (explicit joint limit 19)"
                       : element >= ctl.dt_max ? "time.dt_max"
                                               : "elements (Courant)";
}

std::string Solver::contactSurfaceOf(Index mesh_element) const
{
  if (!_m.contact)
    return "";
  const std::vector<ContactFaceInfo> &info = _m.contact->faceInfo();
  const size_t own = size_t(_m.contact->numOwnFaces()); // ghosts are other ranks' elements
  for (size_t f = 0; f < own && f < info.size(); ++f)
    if (info[f].mesh_element == mesh_element)
    {
      auto surface = Kokkos::create_mirror_view_and_copy(
          HostSpace(), Kokkos::subview(_m.contact->faces().surface, std::make_pair(f, f + 1)));
      const SurfaceSpec &spec = _m.deck.contact.surfaces[size_t(surface(0))];
      return "contact surface '" + spec.name + "' (option " + spec.option + ")";
    }
  return "";
}

void Solver::checkEarlyNodes() const
{
  std::string what;
  const Index n = earlyNodeWrittenLate(_m.sweep, _m.nodes, _early_snapshot, _m.external_loads,
                                       _gravity_next.data(), &what);
  std::string error;
  if (n >= 0)
    error = "node " + std::to_string(globalNode(n)) + " was integrated in step 6 and then " +
            "changed before step 12 (" + what + ") by a room that did not declare it late " +
            "(integrate/LateNodes.hpp) at cycle " + std::to_string(_cycle);
  collectiveCheck(error);
}

bool Solver::reachedEnd() const
{
  return _all_eroded ||
         !(_time < _m.deck.end_time && (_m.deck.max_cycles < 0 || _cycle < _m.deck.max_cycles));
}

long Solver::run(const std::string &output_dir, const std::string &restart_file)
{
  std::unique_ptr<RestartReader> restart;
  if (!restart_file.empty())
  {
    // every rank reads the whole file and checks it alike, so they fail together
    restart = std::make_unique<RestartReader>(restart_file, restartDeckHash(_m.deck));
    loadState(*restart);
  }
  Outputs out(*this, output_dir, restart.get());
  out.begin(restart.get());
  try
  {
    while (!reachedEnd())
    {
      cycle();
      out.afterCycle();
      if (_stop_signal && !reachedEnd()) // a signal in the last cycle of the run changes nothing
      {
        _interrupted_by = _stop_signal;
        break;
      }
    }
  }
  catch (const SimulationError &e)
  {
    out.finish(e.what());
    throw;
  }
  if (_interrupted_by)
    endInterruptedRun(out);
  else
    out.finish("");
  return _cycle;
}

void Solver::endInterruptedRun(Outputs &out)
{
  out.writeRestart();
  out.finishInterrupted(signalName(_interrupted_by));
}

} // namespace scpdyn
