#pragma once
/// \file Model.hpp
/// \brief What set-up (steps 1 and 2 of the cycle, docs/theory.md 2.2) builds from a deck: this
/// rank's mesh, its node and element fields, the element groups and materials, the boundary
/// conditions, the contact system, the gauges, the node sweep and, in a decomposed run, the
/// decomposition. The cycle (driver/Solver.hpp) advances it; nothing in here changes with time
/// but the fields' values. Set-up is ModelSetup (model/ModelSetup.hpp and the files beside it).
#include "bc/BoundaryConditions.hpp"
#include "bc/PartRelease.hpp"
#include "core/Fields.hpp"
#include "element/ElementForces.hpp"
#include "input/Deck.hpp"
#include "integrate/NodeSweep.hpp"
#include "mesh/HostMesh.hpp"

#include <mpi.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace scpdyn
{

class ContactSystem;
struct DomainDecomposition;

/// \brief A gauge resolved to a node or element id and quantity codes.
struct GaugeSlot
{
  std::string column;
  bool on_element = false;
  Index id = -1;
  int quantity = 0;
  int joint = -1; ///< joint gauges: index of the gauge's point and radius (else -1)
};

/// \brief A joint gauge: the CPs within `radius` [m] (0: half the largest contact face) of the
/// node nearest the gauge's point (device id on the rank that owns it, else -1).
struct JointGauge
{
  Index anchor = -1;
  Real radius = 0;
};

struct Model
{
  /// \brief Set-up (steps 1 and 2): meshes, sets, materials, BCs, contact, gauges, initial
  /// state. With more than one rank in `comm` the mesh is decomposed: every rank reads the
  /// same deck and keeps its own elements, nodes and faces (collective over `comm`).
  Model(const Deck &deck, MPI_Comm comm);
  ~Model();
  Model(const Model &) = delete;
  Model &operator=(const Model &) = delete;

  Deck deck;
  HostMesh mesh; ///< this rank's mesh (the whole mesh on one rank)
  std::vector<HostFace> external_faces;
  /// the interior faces of the parts whose material erodes, twins as global element ids: they
  /// join the part's contact surfaces when erosion exposes them (docs/theory.md 11.6)
  std::vector<HostFace> interior_faces;
  std::map<std::string, std::vector<Index>> node_sets;
  std::map<std::string, std::vector<HostFace>> face_sets;

  NodeFields nodes;
  ElementFields elems;
  NodeCorners corners;
  NodeSweep sweep;      ///< step 12 of the early nodes inside step 6 (numerics.node_update fused)
  long sweep_nodes = 0; ///< its nodes over all ranks
  std::vector<ElementGroup> groups;
  DeviceView<MaterialParams *> materials;
  std::vector<MaterialParams> materials_host;
  BoundaryConditions bc;
  PartRelease release;           ///< the held parts (parts[].release_time)
  bool external_loads = true;    ///< hasExternalLoads(): steps 5 and 12 handle f_ext
  ElementControls controls;      ///< the deck's element controls (the cycle sets dt and time)
  Real initial_element_step = 0; ///< the elements' h / c in the initial state, this rank [s]
  std::vector<GaugeSlot> gauges;
  std::vector<JointGauge> joint_gauges;
  IndexView gauge_id;                        ///< device copies of the gauge slots
  IndexView gauge_code;                      ///< quantity code, + 100 for element quantities
  std::vector<int> part_spec;                ///< deck parts[] entry of every mesh part
  std::vector<Index> host_to_device_element; ///< mesh element id -> device element id
  std::shared_ptr<ContactSystem> contact;    ///< null without contact surfaces

  MPI_Comm comm = MPI_COMM_WORLD;
  int rank = 0, num_ranks = 1;
  std::shared_ptr<DomainDecomposition> dd; ///< null on one rank
  std::unique_ptr<HostMesh> global_mesh;   ///< the whole mesh during set-up (decomposed runs)

  /// \brief Global id of a local node / mesh element (identity on one rank).
  Index globalNode(Index local) const;
  Index globalElement(Index mesh_element) const;
  /// \brief Nodes and elements of the whole model (summed over ranks).
  long globalNodeCount() const;
  long globalElementCount() const;
  /// \brief Mesh element id of a device element id.
  Index meshElementOfDevice(Index device) const;
};

} // namespace scpdyn
