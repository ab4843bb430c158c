#pragma once
/// \file ModelSetup.hpp
/// \brief The set-up of a Model (steps 1 and 2), in the order run() gives; one function a
/// part, in ModelSetup.cpp (mesh, fields, sets, BCs, initial state, node sweep),
/// ModelDecompose.cpp, ModelContact.cpp and ModelGauges.cpp. Only Model's constructor uses it.
#include "model/Model.hpp"

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
