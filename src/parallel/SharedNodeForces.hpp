#pragma once
/// \file SharedNodeForces.hpp
/// \brief The nodal forces of the nodes shared between ranks, summed over their copies
/// (docs/theory.md 2.2, steps 7, 9b and 10): every copy ends with the same total, added in the
/// fixed rank order of NodeHalo, so a decomposed run equals the serial one to round-off.
#include "core/Fields.hpp"
#include "parallel/NodeHalo.hpp"

namespace scpdyn
{

/// \brief Step 9b for a force with its own field: `total(k)` = the sum over the copies of
/// `partial(k)`, this rank's part, at every shared node k. `scratch` (node-sized) carries the
/// sum, so `partial` is left alone; `total` may be a field whose unshared entries hold other
/// values (they are not touched).
void sumSharedPartials(NodeHalo &halo, const IndexView &shared, const VectorView &partial,
                       const VectorView &scratch, const VectorView &total);

/// \brief Step 10 for loads that share f_ext with the body force: at every shared node k,
/// f_ext(k) = m g + the sum over the copies of `partial(k)` (this rank's loads, summed in place),
/// with step 5's m g exactly.
void sumSharedLoads(NodeHalo &halo, const IndexView &shared, const VectorView &partial,
                    const NodeFields &nodes, const Real gravity[3]);

} // namespace scpdyn
