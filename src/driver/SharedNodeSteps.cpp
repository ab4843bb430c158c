// Steps 7, 9b and the face loads' sum (step 10) of a decomposed run (docs/theory.md 2.2): the forces of the nodes shared
// between ranks summed over their copies; and the collective error check that keeps the ranks
// in step when one of them fails.
#include "driver/Solver.hpp"

#include "contact/ContactSystem.hpp"
#include "parallel/Decomposition.hpp"
#include "parallel/Mpi.hpp"
#include "parallel/SharedNodeForces.hpp"

namespace scpdyn
{

void Solver::collectiveCheck(const std::string &local_error) const
{
  // decomposed: the lowest failing rank's message on every rank, so all of them stop together
  const std::string error = _m.dd ? firstErrorOfAnyRank(local_error, _m.comm) : local_error;
  if (!error.empty())
    throw SimulationError(error);
}

void Solver::stepExchangeSharedNodeForces()
{
  if (!_m.dd)
    return;
  ScopedStep t(_timers, "07_shared_node_forces");
  if (_m.dd->corner_sum) // the corners of every rank in the serial order
    _m.dd->corner_sum->sum(_m.corners.corner_force, _m.nodes.f_int);
  else
    _m.dd->halo->sum(_m.nodes.f_int);
}

void Solver::stepExchangeContactPartials()
{
  if (!_m.dd || !_m.contact || _m.contact->sharedNodesWhole())
    return;
  ScopedStep t(_timers, "09b_shared_contact_forces");
  // the partials come from the contact's own field, which holds zero at a node this rank's
  // contact does not touch (f_contact there holds the last cycle's sum)
  sumSharedPartials(*_m.dd->halo, _m.dd->shared_nodes, _m.contact->nodalForces(), _m.dd->f_contact,
                    _m.nodes.f_contact);
}

void Solver::sumSharedFaceLoads()
{
  if (!_m.dd || _m.bc.pressure_value.empty())
    return;
  // the face loads again, into their own array, summed over the copies of each shared node
  Kokkos::deep_copy(_m.dd->f_load, 0.0);
  NodeFields into = _m.nodes;
  into.f_ext = _m.dd->f_load;
  applyFaceLoads(_m.bc, into, _dt, _m.deck.dimension, _m.deck.geometry);
  sumSharedLoads(*_m.dd->halo, _m.dd->shared_nodes, _m.dd->f_load, _m.nodes, _gravity.data());
}

} // namespace scpdyn
