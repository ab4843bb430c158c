#pragma once
/// \file ContactSetup.hpp
/// \brief Host-side set-up of the contact (step 2): the deck's contact surfaces become device
/// contact faces with keys, face masses and SI joint parameters.
#include "contact/ContactData.hpp"
#include "core/Fields.hpp"
#include "input/Deck.hpp"
#include "mesh/HostMesh.hpp"

#include <functional>
#include <map>
#include <string>
#include <vector>

namespace scpdyn
{

/// \brief Joint parameters of one surface in SI: Table 1 units (mm, GPa, degrees) converted,
/// derived defaults resolved (Emax, sigma_t), `bc_id` = the surface's index in the deck.
JointParams jointParamsOf(const SurfaceSpec &surface, int bc_id);

/// \brief What the contact set-up reads from the solver's set-up.
struct ContactMeshInput
{
  const Deck *deck = nullptr;
  const HostMesh *mesh = nullptr;
  const std::vector<HostFace> *external_faces = nullptr; ///< extractExternalFaces()
  /// the interior faces of the parts whose elements can erode (interiorFaces(), twins as global
  /// element ids), or null: a `part` surface takes them too, inactive until exposed (11.6)
  const std::vector<HostFace> *interior_faces = nullptr;
  const std::map<std::string, std::vector<HostFace>> *face_sets = nullptr;
  const std::vector<Index> *host_to_device_element = nullptr;
  NodeFields nodes;    ///< mass and velocity-BC flags are read
  ElementFields elems; ///< element masses are read
  /// per material: the history slot of its damage (historyNames), or -1; the sleepy switch
  std::vector<int> damage_slot;
  /// Decomposed runs: global id of every mesh element (face keys are global), and the global
  /// sum of a count (a surface must select faces on some rank, not on every one).
  const std::vector<Index> *global_element = nullptr;
  std::function<long long(long long)> global_count;
};

/// \brief The contact faces of every surface of the deck, in ascending global key, on device;
/// `info` receives the host description of each. A face named by two surfaces keeps the first.
/// Throws InputError naming the deck key for a surface that selects no external face.
ContactFaceData buildContactFaces(const ContactMeshInput &in, std::vector<ContactFaceInfo> &info);

} // namespace scpdyn
