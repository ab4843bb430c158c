#pragma once
/// \file HostMesh.hpp
/// \brief Host-side description of a problem's meshes, built at set-up (step 1) before the
/// data move to Kokkos Views. Every part is its own mesh: parts share no node unless the deck
/// asks for coincident nodes to be merged.
#include "core/Types.hpp"

#include <array>
#include <map>
#include <string>
#include <vector>

namespace scpdyn
{

/// \brief One part: elements of a single type, connectivity into HostMesh::coords.
struct HostPart
{
  std::string name;
  ElementType type = ElementType::Quad4;
  std::vector<Index> connectivity; ///< nodesPerElement(type) global node ids per element
  int material = -1;               ///< index into Deck::materials, set by the driver
  Index numElements() const { return Index(connectivity.size()) / nodesPerElement(type); }
};

/// \brief An external face: its nodes ordered so the normal points out of the element
/// (2D: segment with the element on its left; 3D: right-handed about the outward normal).
struct HostFace
{
  std::array<Index, kMaxFaceNodes> nodes{{-1, -1, -1, -1}};
  int num_nodes = 0;
  Index element = -1; ///< global element id (parts numbered consecutively in part order)
  int local_face = -1;
  int part = -1;
  /// an interior face (interiorFaces()): the global id of the element on its other side; -1
  /// for an external face
  Index twin = -1;
};

/// \brief All meshes of a problem plus named node and face sets.
struct HostMesh
{
  int dim = 0;
  std::vector<std::array<Real, 3>> coords; ///< unused components are zero
  std::vector<HostPart> parts;
  std::map<std::string, std::vector<Index>> node_sets;
  /// face sets: each face given by its (sorted-insensitive) node list, as on an external face
  std::map<std::string, std::vector<HostFace>> face_sets;

  Index numNodes() const { return Index(coords.size()); }
  Index numElements() const
  {
    Index n = 0;
    for (const auto &p : parts)
      n += p.numElements();
    return n;
  }
};

} // namespace scpdyn
