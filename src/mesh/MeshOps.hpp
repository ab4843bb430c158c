#pragma once
/// \file MeshOps.hpp
/// \brief Host-side queries and edits of a HostMesh: external faces, merging of coincident
/// nodes, selections by box and by part, element validity checks and measures.
///
/// Local face numbering. Face f of an element lists its local nodes in the order that makes
/// the normal point out of the element (2D: element on the left of the segment; 3D:
/// right-handed about the outward normal). For the reference elements of MeshGenerators.hpp:
///   Line2: 0 = {0} (at -x), 1 = {1} (at +x)
///   Quad4: f = {f, f+1 mod 4}: 0 = -y, 1 = +x, 2 = +y, 3 = -x
///   Hex8:  0 = {0,1,5,4} -y, 1 = {1,2,6,5} +x, 2 = {2,3,7,6} +y, 3 = {0,4,7,3} -x,
///          4 = {0,3,2,1} -z, 5 = {4,5,6,7} +z
///   Tet4 (positive volume): 0 = {0,1,3}, 1 = {1,2,3}, 2 = {0,3,2}, 3 = {0,2,1}
/// (the Exodus side order: tet face 0 is opposite node 2, 1 opposite 0, 2 opposite 1, 3 opposite 3).
#include "mesh/HostMesh.hpp"

#include <cmath>

#include <array>
#include <string>
#include <vector>

namespace scpdyn
{

inline constexpr int kLine2Faces[2][1] = {{0}, {1}};
inline constexpr int kQuad4Faces[4][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
inline constexpr int kHex8Faces[6][4] = {{0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6},
                                         {0, 4, 7, 3}, {0, 3, 2, 1}, {4, 5, 6, 7}};
inline constexpr int kTet4Faces[4][3] = {{0, 1, 3}, {1, 2, 3}, {0, 3, 2}, {0, 2, 1}};

/// \brief Number of faces of one element: 2 (Line2), 4 (Quad4, Tet4), 6 (Hex8).
constexpr int facesPerElement(ElementType t)
{
  return t == ElementType::Line2 ? 2 : t == ElementType::Hex8 ? 6 : 4;
}

/// \brief Local node `i` (0 <= i < nodesPerFace(t)) of local face `f` of an element of type t.
int faceLocalNode(ElementType t, int f, int i);

/// \brief External faces of the mesh: faces no other element has. Parts that do not share nodes
/// keep all their faces (the faces between two such parts are external for both, the contact's
/// business); faces between parts whose nodes were merged are inside one body and are not
/// external. Elements are numbered globally in part order; the result is sorted by element,
/// then local face.
std::vector<HostFace> extractExternalFaces(const HostMesh &mesh);

/// \brief The faces two elements share where either element is of a part with `parts[p]` != 0
/// (the two may be of merged parts): each face once per element (outward for it), with `twin` =
/// the other element. In (element, local face) order. They are the faces element erosion can
/// expose (docs/theory.md 11.6).
std::vector<HostFace> interiorFaces(const HostMesh &mesh, const std::vector<char> &parts);

/// \brief Merge nodes of the listed parts that lie within `tolerance` (m) of each other
/// (transitively). The lowest id of a group is kept, all nodes of the mesh are renumbered
/// compactly in their old order, and connectivity, node sets and face sets are updated.
/// Uses a sorted grid of cell size `tolerance`: O(n log n).
void mergeCoincidentNodes(HostMesh &mesh, const std::vector<int> &parts, Real tolerance);

/// \brief Moves nodes [first, end) as a rigid body: rotation by `angle` [rad] about the line
/// through `point` along the unit vector `axis` (Rodrigues' formula; 2D meshes: axis z), then
/// translation by `shift`.
void moveNodesRigidly(HostMesh &mesh, std::size_t first, Real angle,
                      const std::array<Real, 3> &axis, const std::array<Real, 3> &point,
                      const std::array<Real, 3> &shift);

/// \brief Sorted ids of nodes inside the box [lo - tol, hi + tol] (m) in every coordinate.
std::vector<Index> nodesInBox(const HostMesh &mesh, std::array<Real, 3> lo, std::array<Real, 3> hi,
                              Real tol);

/// \brief Faces of `external` whose nodes all lie inside [lo - tol, hi + tol] (m).
std::vector<HostFace> facesInBox(const std::vector<HostFace> &external, const HostMesh &mesh,
                                 std::array<Real, 3> lo, std::array<Real, 3> hi, Real tol);

/// \brief Sorted, unique ids of the nodes used by the listed parts.
std::vector<Index> nodesOfParts(const HostMesh &mesh, const std::vector<int> &parts);

/// \brief The faces of `external` that belong to one of the listed parts (order kept).
std::vector<HostFace> facesOfParts(const std::vector<HostFace> &external,
                                   const std::vector<int> &parts);

/// \brief Throws std::runtime_error naming part and element for an inverted or degenerate
/// element (Quad4: a corner triangle of non-positive area; Hex8: a non-positive corner
/// Jacobian; Tet4: non-positive volume; Line2: non-positive length), or for an empty part.
/// "Degenerate" is judged relative to the element's edge lengths (sine of a corner angle
/// below 1e-12), so collinear or coincident nodes are caught despite round-off.
void checkElements(const HostMesh &mesh);

/// \brief Appends `src` to `dst`: nodes, parts (names prefixed with `prefix`), node sets and
/// face sets, with node, element and part ids shifted past what `dst` already holds.
void appendMesh(HostMesh &dst, HostMesh src, const std::string &prefix);

/// \brief The box of every node of a mesh [m] (unused components are zero, so 0 to 0).
struct MeshBox
{
  std::array<Real, 3> lo{{1e300, 1e300, 1e300}}, hi{{-1e300, -1e300, -1e300}};
  Real diagonal() const
  {
    Real d = 0;
    for (int i = 0; i < 3; ++i)
      d += (hi[size_t(i)] - lo[size_t(i)]) * (hi[size_t(i)] - lo[size_t(i)]);
    return std::sqrt(d);
  }
};
MeshBox meshBox(const HostMesh &mesh);

/// \brief Length (m), area (m^2) or volume (m^3) of one part (exact for these element types).
Real meshMeasure(const HostMesh &mesh, int part);

} // namespace scpdyn
