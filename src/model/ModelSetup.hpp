#pragma once
/// \file ModelSetup.hpp
/// \brief The set-up of a Model (steps 1 and 2), in the order run() gives; one function a
/// part, in ModelSetup.cpp (mesh, fields, sets, BCs, initial state, node sweep),
/// ModelDecompose.cpp, ModelContact.cpp and ModelGauges.cpp. Only Model's constructor uses it.
#include "model/Model.hpp"
#include "parallel/OrderedNodeSum.hpp"

#include <functional>

namespace scpdyn
{

class ModelSetup
{
public:
  explicit ModelSetup(Model &model) : _m(model) {}
  /// \brief Every step of the set-up, in order.
  void run();

private:
  Model &_m;

  void checkMeshSize() const;
  void warnUnconnectedGroups(const HostMesh &g, const std::string &key) const;
  void setupMesh();
  void decompose();
  void setupFields();
  void finishDecomposition();
  /// The decomposed run's terms of its shared nodes: every corner (e, a) of a device element
  /// at a shared node, keyed key(e, a), with value slot slot(e, a); without `slot`, slots
  /// numbered in (e, a) order, and `corners` lists the corner of each.
  std::vector<std::vector<NodeTerm>> cornerTerms(const std::function<TermKey(Index, int)> &key,
                                                 const std::function<Index(Index, int)> &slot,
                                                 std::vector<std::pair<Index, int>> *corners) const;
  void setupCornerSum();
  /// Step 2 [A] of a decomposed run: the shared nodes' masses, from the element masses, in
  /// the serial order.
  void sumSharedMasses(const RealView::HostMirror &element_mass,
                       const RealView::HostMirror &node_mass) const;
  void setupSets();
  void setupBoundaryConditions();
  void setupContact();
  void setupContactGhosts();
  void setupPartRelease();
  void setupNodeSweep();
  void setupGauges();
  void setupInitialState();
  void checkSetNotEmpty(std::size_t local_count, const std::string &message) const;
  void unifyNodeSet(std::vector<Index> &nodes) const;
  Index globalElement(Index mesh_element) const { return _m.globalElement(mesh_element); }
  Index meshElementOfDevice(Index device) const { return _m.meshElementOfDevice(device); }
  Index globalNode(Index local) const { return _m.globalNode(local); }
};

} // namespace scpdyn
