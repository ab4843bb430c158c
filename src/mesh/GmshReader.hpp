#pragma once
/// \file GmshReader.hpp
/// \brief Reader for Gmsh .msh 4.1 ASCII meshes.
#include "mesh/HostMesh.hpp"

#include <string>

namespace scpdyn
{

/// \brief Read a Gmsh 4.1 ASCII mesh (sections $MeshFormat, $PhysicalNames, $Entities, $Nodes,
/// $Elements; others are skipped). Coordinates are taken as metres.
///
/// The top dimension is the highest dimension of any element. Its elements must be line2
/// (gmsh type 1), quad4 (3), hex8 (5) or tet4 (4); each physical group of that dimension
/// becomes one part (its physical name, or "physical_<tag>"), elements in no group go to a
/// part "unnamed", and every part gets its own copy of its nodes (identical coordinates).
/// Parts are ordered by physical tag, "unnamed" last. Elements are re-oriented where gmsh
/// gives them negative measure (e.g. a surface drawn clockwise). Physical groups of
/// dimension dim-1 (line2 in 2D; tri3/quad4 in 3D; points in 1D) become face sets (the
/// matching outward external faces of every part that has them, see MeshOps.hpp) and node
/// sets of the same name; lower-dimensional groups become node sets. Node sets list every
/// part copy of a node. Unnamed lower groups are also called "physical_<tag>".
///
/// Throws std::runtime_error "<path>:<line>: <what>" for: a missing file, a version other
/// than 4.1 or a binary file, an unsupported element type in the top dimension, a physical
/// group of the top dimension mixing element types or an element in two such groups, a
/// face-set element that is not an external face of any part (e.g. a separate
/// lower-dimensional mesh mixed with the top-dimensional one), unknown or duplicate node tags, a 2D mesh
/// off the z = 0 plane, and inverted or degenerate elements.
HostMesh readGmsh41(const std::string &path);

} // namespace scpdyn
