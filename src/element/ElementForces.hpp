#pragma once
/// \file ElementForces.hpp
/// \brief Step 6 of the cycle: element solvers. For every element: half-step kinematics,
/// velocity gradient, objective stress rotation, material update, internal + hourglass
/// forces scattered to the nodes, and the element's stable time step.
#include "core/Fields.hpp"
#include "element/Hourglass.hpp"
#include "element/Lanes.hpp"
#include "material/MaterialParams.hpp"

#include <vector>

namespace scpdyn
{

/// \brief Per-cycle controls of the element kernels.
struct ElementControls
{
  Real dt = 0;        ///< this cycle's time step [s]
  Real half_time = 0; ///< t^n + dt/2 [s]
  Geometry2D geometry = Geometry2D::PlaneStrain;
  HourglassType hourglass = HourglassType::Viscous;
  Real hourglass_coefficient = 0.05;
  Real q_linear = 0.06;
  Real q_quadratic = 1.5;
  bool gather = false;  ///< chunked, deterministic assembly (NodeCorners) instead of atomics
  bool erosion = false; ///< a material erodes: skip eroded elements (ElementFields::eroded)
};

/// \brief First element of chunk k of the `chunks` chunks of group g (k = chunks: its end).
/// Chunks are whole packs of kElementLanes hexes (whole elements for other types), so each
/// thread's packs are those of the one-thread loop.
KOKKOS_INLINE_FUNCTION Index chunkBegin(const ElementGroup &g, int chunks, int k)
{
  const Index unit = g.type == ElementType::Hex8 ? kElementLanes : 1;
  const Index units = (g.end - g.begin + unit - 1) / unit;
  const Index first = g.begin + Index(static_cast<long long>(units) * k / chunks) * unit;
  return first < g.end ? first : g.end;
}

/// \brief Elements per block of a thread's chunk after which an after-block hook runs
/// (ElementLaunch.hpp): small enough that a block's nodes are still in cache.
constexpr Index kElementBlock = 64;

/// \brief What step 6 reports: the smallest stable element time step h / c before the Courant
/// factor, and whether an element failed.
struct ElementStepResult
{
  Real dt = 0;         ///< smallest h / c over the elements [s]
  Index inverted = -1; ///< device id of an inverted element (the lowest), else -1
  bool finite = true;  ///< false when an element's state is not finite
  bool ok() const { return finite && inverted < 0; }
};

/// \brief Run the element solvers of all groups; forces go to nodes.f_int (atomic, or plain
/// adds with one thread), or with ctl.gather to f_int and to corners.corner_force for shared
/// nodes (then call gatherCornerForces). With an after-block hook (the node sweep of step 12,
/// integrate/NodeSweep.hpp): computeElementForcesWith() in ElementLaunch.hpp.
ElementStepResult computeElementForces(const std::vector<ElementGroup> &groups,
                                       const ElementControls &ctl, const NodeFields &nodes,
                                       const ElementFields &elems,
                                       const DeviceView<MaterialParams *> &materials,
                                       const NodeCorners &corners);

/// \brief The chunk (group-major over all groups' chunks) of each node's elements when each
/// group is cut into `chunks` chunks (chunkBegin()): -1 if none, -2 once two chunks touch it;
/// and, in `last`, the last element (in the chunk's order) touching it.
std::vector<int> nodeChunks(const ElementFields &elems, const std::vector<ElementGroup> &groups,
                            Index num_nodes, int chunks, std::vector<Index> *last = nullptr);

/// \brief The chunks of the deterministic assembly (NodeCorners) for `chunks` threads: which
/// nodes two chunks share, their corners, and the corner force array. The nodes of
/// `also_shared` (those other ranks hold too) store their corners whatever the chunks.
NodeCorners makeNodeCorners(const ElementFields &elems, const std::vector<ElementGroup> &groups,
                            Index num_nodes, int chunks,
                            const std::vector<Index> &also_shared = {});

/// \brief The four rows of a hex row pack (markRowPacks()): lane l's corner kHexRowMinus[r] is
/// node base_r + l and its corner kHexRowPlus[r] node base_r + l + 1.
constexpr int kHexRowMinus[4] = {0, 3, 4, 7}, kHexRowPlus[4] = {1, 2, 5, 6};

/// \brief ElementFields::row_pack: 1 at hex e if the hexes e .. e + kElementLanes - 1 of one
/// group have, in lane l, corner a at node conn(e, a) + l, and corners 1, 2, 5, 6 at corners
/// 0, 3, 4, 7 plus one: four rows of kElementLanes + 1 consecutive nodes, which step 6 reads
/// and adds to as whole rows (loadRowTriples, addRowTriples). Block meshes numbered along x
/// (the built-in generators) are made of them; other packs take the general path.
DeviceView<std::uint8_t *> markRowPacks(const ElementFields &elems,
                                        const std::vector<ElementGroup> &groups);

/// \brief f_int(n) = sum of the corner forces of each shared node n, in ascending corner order.
void gatherCornerForces(const NodeFields &nodes, const NodeCorners &corners);

/// \brief Stable element time step of the initial state (no strain rate), before the
/// Courant factor; also initialises sound speeds and volumes.
Real initialElementTimeStep(const std::vector<ElementGroup> &groups, Geometry2D geometry,
                            const NodeFields &nodes, const ElementFields &elems,
                            const DeviceView<MaterialParams *> &materials);

} // namespace scpdyn
