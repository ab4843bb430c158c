// The 13-step cycle of the paper (scp-method.md 2.2), read top to bottom in Solver::cycle().
#include "driver/Solver.hpp"

#include "contact/ContactSystem.hpp"
#include "driver/Decomposition.hpp"
#include "driver/Outputs.hpp"
#include "parallel/Mpi.hpp"

#include <chrono>
#include <cmath>
#include <sstream>

namespace scpdyn
{

void Solver::cycle()
{
  const auto start = std::chrono::steady_clock::now();
  // No shortened last step: a sudden change of dt changes the leapfrog's conserved energy
  // (an artefact in the balance); the run ends on the first cycle at or past the end time.
  _dt = _dt_next;
  stepSortIntoBins();             // 3: cycle begins; contact faces into bins when due
  stepExchangeFaceConnectivity(); // 4: bounding boxes, occupied bins, ghost-face lists
  stepZeroForces();               // 5: zero forces; external-face variables
  stepElementSolvers();           // 6: half-step kinematics, materials, internal forces
                                  //    (and step 12 of the nodes 7-11 leave alone: NodeSweep)
  stepExchangeSharedNodeForces(); // 7: sum internal forces on shared nodes
  stepExchangeGhostFaceData();    // 8: ghost faces get x, v, face masses
  stepContactForces();            // 9: common planes: detection, geometry, forces
  stepFaceBoundaryConditions();   // 10: pressure on faces
  stepExchangeLoadPartials();     // 10b: sum contact and pressure forces on shared nodes
  stepNodeBoundaryConditions();   // 11: nodal forces (velocities are imposed in 12)
  stepUpdateNodes();              // 12: v, x; next stable time step
  _time += _dt;                   // 13: back to 3 (output by the caller)
  ++_cycle;
  _cycle_wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Steps 4 and 8 (ghost contact faces) are in src/driver/ContactGhosts.cpp, 7 and 10b in
// src/driver/Decompose.cpp.

Index Solver::meshElementOfDevice(Index device) const
{
  for (size_t k = 0; k < _host_to_device_element.size(); ++k)
    if (_host_to_device_element[k] == device)
      return Index(k);
  return device;
}

void Solver::setupContact()
{
  if (_deck.contact.surfaces.empty())
    return;
  ContactMeshInput in;
  in.deck = &_deck;
  in.mesh = &_mesh;
  in.external_faces = &_external_faces;
  in.face_sets = &_face_sets;
  in.host_to_device_element = &_host_to_device_element;
  in.nodes = _nodes;
  in.elems = _elems;
  if (_dd)
  {
    in.global_element = &_dd->global_element;
    MPI_Comm comm = _comm;
    in.global_count = [comm](long long n) { return allReduceSum(n, comm); };
  }
  _contact = std::make_shared<ContactSystem>(in);
  if (_dd)
    setupContactGhosts();
}

void Solver::stepSortIntoBins()
{
  // decomposed: the search sorts in step 9, once the ghost faces have this cycle's data
  if (!_contact || _dd)
    return;
  ScopedStep t(_timers, "03_sort_into_bins");
  _contact->sortIntoBins(_nodes, _dt, _cycle);
}

void Solver::stepContactForces()
{
  if (!_contact)
    return;
  ScopedStep t(_timers, "09_contact_forces");
  const ContactFailure f = _contact->computeForces(_nodes, _bc, _dt, _cycle, _time);
  collectiveCheck(f.failed ? f.message : std::string());
  if (_dd && _contact->searchDue(_cycle) && !_contact->searchDue(_cycle + 1))
    restrictGhosts(); // until the next search, ghost data only for the faces of live CPs
}

void Solver::stepZeroForces()
{
  ScopedStep t(_timers, "05_zero_forces");
  if (!_forces_zeroed) // else the last cycle's step 12 did it in its sweep over the nodes
    zeroForces(_nodes, _deck.gravity.data(), _external_loads);
  _forces_zeroed = false;
}

void Solver::stepElementSolvers()
{
  ScopedStep t(_timers, "06_element_solvers");
  _controls = elementControls();
  if (_sweep.active) // step 12 of the early nodes, in this step's sweep
  {
    _sweep.node = nodeIntegrator(_nodes, _bc.velocity_current, _dt,
                                 _dd ? _dd->owned_device : IndexView(), _deck.gravity.data());
    _sweep.loads = _external_loads;
  }
  const ElementStepResult r =
      computeElementForces(_groups, _controls, _nodes, _elems, _materials, _corners, _sweep);
  if (_controls.gather)
    gatherCornerForces(_nodes, _corners);
  std::string error;
  if (!r.ok())
  {
    std::ostringstream os;
    if (!r.finite)
      os << "non-finite element state at cycle " << _cycle << ", time " << _time;
    else
      os << "element " << globalElement(meshElementOfDevice(r.inverted)) << " inverted at cycle "
         << _cycle << ", time " << _time << " s (dt " << _dt
         << " s): reduce time.courant or check the loading";
    error = os.str();
  }
  collectiveCheck(error); // every rank stops before the shared-node exchange
  _limits.element = r.dt;
  if (_check_sweep)
    snapshotEarlyNodes(_nodes, _early_snapshot);
}

void Solver::stepFaceBoundaryConditions()
{
  ScopedStep t(_timers, "10_face_bcs");
  updateLoadValues(_bc, _time + 0.5 * _dt);
  applyFaceLoads(_bc, _nodes, _dt, _deck.dimension, _deck.geometry);
}

void Solver::stepNodeBoundaryConditions()
{
  ScopedStep t(_timers, "11_node_bcs");
  applyNodeForces(_bc, _nodes);
}

void Solver::stepUpdateNodes()
{
  ScopedStep t(_timers, "12_update_nodes");
  if (_check_sweep)
    checkEarlyNodes();
  updateVelocityValues(_bc, _time + _dt);
  _last_sums = updateNodes(_nodes, _bc, _dt, _deck.dimension,
                           _dd ? _dd->owned_device : IndexView(), _external_loads,
                           _deck.gravity.data(), _sweep.active ? &_sweep.late_runs : nullptr);
  if (_sweep.active) // the early nodes' sums, from step 6
    _last_sums += sweepSums(_sweep);
  _forces_zeroed = true;
  const MPI_Comm comm = _dd ? _comm : MPI_COMM_NULL;
  _limits.contact = 1e300;
  if (_contact && _contact->hasExplicit()) // (19), from v^{n+1}
    _limits.contact = _contact->stableTimeStep(_nodes, _elems,
                                               elementStep(_limits, timeStepControls(), comm));
  _dt_next = nextTimeStep(_limits, timeStepControls(), _last_sums, comm);
  _external_work += _last_sums.external_work;
  _kinetic_mid = _last_sums.kinetic_mid;
  _energy_scale = std::max(_energy_scale, _last_sums.kinetic);
  if (!std::isfinite(_last_sums.kinetic))
  {
    std::ostringstream os;
    os << "non-finite nodal velocities at cycle " << _cycle << ", time " << _time;
    throw SimulationError(os.str());
  }
}

void Solver::checkEarlyNodes() const
{
  std::string what;
  const Index n = earlyNodeWrittenLate(_sweep, _nodes, _early_snapshot, _external_loads,
                                       _deck.gravity.data(), &what);
  std::string error;
  if (n >= 0)
    error = "node " + std::to_string(globalNode(n)) + " was integrated in step 6 and then " +
            "changed before step 12 (" + what + ") by a room that did not declare it late " +
            "(integrate/LateNodes.hpp) at cycle " + std::to_string(_cycle);
  collectiveCheck(error);
}

long Solver::run(const std::string &output_dir)
{
  Outputs out(*this, output_dir);
  out.begin();
  try
  {
    while (_time < _deck.end_time &&
           (_deck.max_cycles < 0 || _cycle < _deck.max_cycles))
    {
      cycle();
      out.afterCycle();
    }
  }
  catch (const SimulationError &e)
  {
    out.finish(e.what());
    throw;
  }
  out.finish("");
  return _cycle;
}

} // namespace scpdyn
