#pragma once
/// \file MeshGenerators.hpp
/// \brief Structured meshes built on the host: one block, or a wall of bricks (one part per
/// brick). Every call appends parts with their own new nodes; parts never share nodes.
///
/// Node ordering of the elements (the element code relies on it):
///   Line2: left, right.
///   Quad4: counter-clockwise, 0 (-,-), 1 (+,-), 2 (+,+), 3 (-,+).
///   Hex8:  bottom face 0-1-2-3 counter-clockwise seen from +z, top face 4-5-6-7 above them.
///   Tet4:  positive volume, ((x1-x0) x (x2-x0)) . (x3-x0) > 0.
#include "mesh/BrickBond.hpp"
#include "mesh/HostMesh.hpp"

#include <array>
#include <string>

namespace scpdyn
{

/// \brief Append one part `name`: a box of `cells` elements starting at `origin` (m) with edge
/// lengths `size` (m). Line2 uses cells[0] along x (y = z = 0); Quad4 cells[0] x cells[1] in
/// the x-y plane (z = 0); Hex8 a box; Tet4 a box of hexes each split into 6 tets by the
/// Kuhn (Freudenthal) split about the (-,-,-)-(+,+,+) diagonal, which is the same in every
/// cell and hence conforming. Sets mesh.dim; throws std::runtime_error if it disagrees with
/// the dimension of parts already in the mesh, or for non-positive cells or sizes.
void appendBlock(HostMesh &mesh, const std::string &name, ElementType type,
                 std::array<int, 3> cells, std::array<Real, 3> origin, std::array<Real, 3> size);

/// \brief Append a rectangular wall of bricks, each its own part named
/// `<prefix>.<course>.<index>`. A course is a line of bricks along the stagger axis
/// (`stagger_axis` 0 = x, 1 = y); every odd course is shifted along that axis by
/// stagger * brick length (0 <= stagger < 1) and has a partial brick at each end (lengths
/// stagger * L and (1 - stagger) * L, which get max(1, round(cells * fraction)) cells along
/// the axis), so the wall keeps its length; stagger = 0 gives a stack bond.
/// 2D (Quad4): courses stack along the other axis (stagger axis x: count[0] bricks per course,
/// count[1] courses along y; axis y: count[1] bricks per course, count[0] courses along x).
/// 3D (Hex8, Tet4): courses stack along z (count[2] of them), each with count[axis] bricks
/// along the stagger axis in count[other axis] rows; index = row * (bricks in the course) + i.
/// 1D (Line2): one course along x. `cells_per_brick` are the cells of a full brick,
/// `brick_size` its edge lengths (m).
///
/// BrickBond::English (3D only, exactly 2 rows, brick length = 2 x brick width, stagger
/// ignored): even courses (from 0, the base) are stretcher courses as above without shift;
/// odd courses are header courses, one row of bricks turned 90 degrees about z that span the
/// whole thickness (2 widths): a queen closer (a quarter brick length along the axis) at each
/// end and 2 count[axis] - 1 headers between, so no head joint of a header course lies over
/// one of the stretcher courses next to it. A header has the stretcher's cells turned with
/// it (cells along the axis and across it swapped); a closer max(1, round(cells / 2)) along
/// the axis. Header-course bricks are indexed along the axis.
void appendBrickWall(HostMesh &mesh, const std::string &prefix, ElementType type,
                     std::array<int, 3> cells_per_brick, std::array<Real, 3> origin,
                     std::array<Real, 3> brick_size, std::array<int, 3> count, Real stagger,
                     int stagger_axis = 0, BrickBond bond = BrickBond::Running);

} // namespace scpdyn
