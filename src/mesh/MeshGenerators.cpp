#include "mesh/MeshGenerators.hpp"
#include "core/RealText.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace scpdyn
{
namespace
{
const char *typeName(ElementType t)
{
  switch (t)
  {
  case ElementType::Line2:
    return "line2";
  case ElementType::Quad4:
    return "quad4";
  case ElementType::Hex8:
    return "hex8";
  case ElementType::Tet4:
    return "tet4";
  }
  return "?";
}

void setDimension(HostMesh &mesh, ElementType type, const std::string &name)
{
  const int dim = dimensionOf(type);
  if (mesh.dim != 0 && mesh.dim != dim)
    throw std::runtime_error("mesh part '" + name + "': " + typeName(type) + " is " +
                             std::to_string(dim) + "D but the mesh already holds " +
                             std::to_string(mesh.dim) + "D parts");
  mesh.dim = dim;
}

// The last node lands exactly on origin + size, so neighbouring blocks meet without round-off
// at least on that side.
Real gridCoord(Real origin, Real size, int i, int cells)
{
  return i == cells ? origin + size : origin + size * (Real(i) / Real(cells));
}

// The six Kuhn tets of the unit cube: path (0,0,0) -> +e_p0 -> +e_p1 -> (1,1,1) for each
// permutation p; odd permutations have their middle nodes swapped for a positive volume.
struct KuhnTet
{
  int axis[3];
  bool odd;
};
const KuhnTet kKuhn[6] = {{{0, 1, 2}, false}, {{1, 2, 0}, false}, {{2, 0, 1}, false},
                          {{0, 2, 1}, true},  {{2, 1, 0}, true},  {{1, 0, 2}, true}};
} // namespace

void appendBlock(HostMesh &mesh, const std::string &name, ElementType type,
                 std::array<int, 3> cells, std::array<Real, 3> origin, std::array<Real, 3> size)
{
  const int dim = dimensionOf(type);
  for (int d = 0; d < dim; ++d)
    if (cells[d] < 1 || !(size[d] > 0))
      throw std::runtime_error("mesh part '" + name + "': cells (" + std::to_string(cells[d]) +
                               ") and size (" + formatReal(size[d]) + " m) along axis " +
                               std::to_string(d) + " must be positive");
  setDimension(mesh, type, name);

  std::array<int, 3> n{{1, 1, 1}}; // nodes per axis
  for (int d = 0; d < dim; ++d)
    n[d] = cells[d] + 1;
  const Index base = mesh.numNodes();
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i)
      {
        std::array<Real, 3> x{{0, 0, 0}};
        const int ijk[3] = {i, j, k};
        for (int d = 0; d < dim; ++d)
          x[d] = gridCoord(origin[d], size[d], ijk[d], cells[d]);
        mesh.coords.push_back(x);
      }
  auto node = [&](int i, int j, int k) { return base + i + n[0] * (j + n[1] * k); };

  HostPart part;
  part.name = name;
  part.type = type;
  auto &conn = part.connectivity;
  const int cz = dim == 3 ? cells[2] : 1, cy = dim >= 2 ? cells[1] : 1;
  for (int k = 0; k < cz; ++k)
    for (int j = 0; j < cy; ++j)
      for (int i = 0; i < cells[0]; ++i)
      {
        switch (type)
        {
        case ElementType::Line2:
          conn.insert(conn.end(), {node(i, 0, 0), node(i + 1, 0, 0)});
          break;
        case ElementType::Quad4:
          conn.insert(conn.end(),
                      {node(i, j, 0), node(i + 1, j, 0), node(i + 1, j + 1, 0), node(i, j + 1, 0)});
          break;
        case ElementType::Hex8:
          conn.insert(conn.end(), {node(i, j, k), node(i + 1, j, k), node(i + 1, j + 1, k),
                                   node(i, j + 1, k), node(i, j, k + 1), node(i + 1, j, k + 1),
                                   node(i + 1, j + 1, k + 1), node(i, j + 1, k + 1)});
          break;
        case ElementType::Tet4:
          for (const KuhnTet &t : kKuhn)
          {
            int c[3] = {0, 0, 0};
            Index v[4];
            v[0] = node(i, j, k);
            for (int s = 0; s < 2; ++s)
            {
              c[t.axis[s]] = 1;
              v[1 + s] = node(i + c[0], j + c[1], k + c[2]);
            }
            v[3] = node(i + 1, j + 1, k + 1);
            if (t.odd)
              std::swap(v[1], v[2]);
            conn.insert(conn.end(), v, v + 4);
          }
          break;
        }
      }
  mesh.parts.push_back(std::move(part));
}

namespace
{
// One header course of an English bond (appendBrickWall): a queen closer of a quarter brick
// length at each end, full headers between, all spanning both rows.
void appendHeaderCourse(HostMesh &mesh, const std::string &prefix, ElementType type,
                        std::array<int, 3> cells_per_brick, std::array<Real, 3> origin,
                        std::array<Real, 3> brick_size, int along, int course, int s)
{
  const int r = 1 - s; // across the wall
  const Real L = brick_size[size_t(s)];
  // (start, length) in brick lengths along the axis: closers of 1/4, headers of 1/2
  std::vector<std::pair<Real, Real>> seg;
  seg.push_back({0, 0.25});
  for (int k = 0; k + 1 < 2 * along; ++k)
    seg.push_back({0.25 + 0.5 * k, 0.5});
  seg.push_back({along - 0.25, 0.25});
  for (size_t i = 0; i < seg.size(); ++i)
  {
    std::array<int, 3> cells = cells_per_brick;
    cells[size_t(s)] = cells_per_brick[size_t(r)]; // the stretcher turned by 90 degrees
    cells[size_t(r)] = cells_per_brick[size_t(s)];
    if (seg[i].second < 0.5)
      cells[size_t(s)] = std::max(1, int(std::lround(cells_per_brick[size_t(r)] * 0.5)));
    std::array<Real, 3> o = origin, size = brick_size;
    o[size_t(s)] = origin[size_t(s)] + L * seg[i].first;
    o[2] = origin[2] + brick_size[2] * course;
    size[size_t(s)] = L * seg[i].second;
    size[size_t(r)] = 2 * brick_size[size_t(r)]; // the thickness of the stretcher courses
    appendBlock(mesh, prefix + "." + std::to_string(course) + "." + std::to_string(i), type, cells,
                o, size);
  }
}
} // namespace

void appendBrickWall(HostMesh &mesh, const std::string &prefix, ElementType type,
                     std::array<int, 3> cells_per_brick, std::array<Real, 3> origin,
                     std::array<Real, 3> brick_size, std::array<int, 3> count, Real stagger,
                     int stagger_axis, BrickBond bond)
{
  if (!(stagger >= 0 && stagger < 1))
    throw std::runtime_error("brick wall '" + prefix + "': stagger must lie in [0, 1), got " +
                             std::to_string(stagger));
  // 1D: one course, a row of line2 blocks along x (the jointed bar of the paper's Fig. 2)
  const int dim = dimensionOf(type);
  if (stagger_axis < 0 || stagger_axis > 1 || (dim == 1 && stagger_axis != 0))
    throw std::runtime_error("brick wall '" + prefix + "': stagger axis must be x" +
                             (dim > 1 ? " or y" : "") + " in " + std::to_string(dim) + "D");
  const bool is3d = dim == 3;
  const int s = stagger_axis;
  // courses stack across the stagger axis in 2D, along z in 3D; rows are the third axis of 3D
  const int course_axis = is3d ? 2 : 1 - s;
  const int row_axis = 1 - s;
  const int courses = dim == 1 ? 1 : count[size_t(course_axis)];
  const int rows = is3d ? count[size_t(row_axis)] : 1;
  const int along = count[size_t(s)];
  if (along < 1 || courses < 1 || rows < 1)
    throw std::runtime_error("brick wall '" + prefix + "': brick counts must be positive");
  const Real L = brick_size[size_t(s)];
  const bool english = bond == BrickBond::English;
  if (english)
  {
    const Real W = brick_size[size_t(row_axis)];
    if (!is3d || rows != 2 || !(std::fabs(L - 2 * W) <= 1e-9 * L))
      throw std::runtime_error("brick wall '" + prefix +
                               "': an English bond needs a 3D wall of exactly 2 rows through "
                               "the thickness and a brick length of 2 brick widths");
    stagger = 0; // its stretcher courses are not shifted; the closers offset the headers
  }

  for (int c = 0; c < courses; ++c)
  {
    if (english && c % 2 == 1)
    {
      appendHeaderCourse(mesh, prefix, type, cells_per_brick, origin, brick_size, along, c, s);
      continue;
    }
    // Segments of the course along the stagger axis as (start offset, length fraction) in
    // brick lengths.
    std::vector<std::pair<Real, Real>> seg;
    const bool shifted = (c % 2 == 1) && stagger > 0;
    if (shifted)
    {
      seg.push_back({0, stagger});
      for (int i = 0; i + 1 < along; ++i)
        seg.push_back({stagger + i, 1});
      seg.push_back({stagger + along - 1, 1 - stagger});
    }
    else
      for (int i = 0; i < along; ++i)
        seg.push_back({Real(i), 1});

    for (int j = 0; j < rows; ++j)
      for (size_t i = 0; i < seg.size(); ++i)
      {
        std::array<int, 3> cells = cells_per_brick;
        std::array<Real, 3> o = origin, size = brick_size;
        if (seg[i].second < 1)
        {
          cells[size_t(s)] =
              std::max(1, int(std::lround(cells_per_brick[size_t(s)] * seg[i].second)));
          size[size_t(s)] = L * seg[i].second;
        }
        o[size_t(s)] = origin[size_t(s)] + L * seg[i].first;
        if (is3d)
          o[size_t(row_axis)] = origin[size_t(row_axis)] + brick_size[size_t(row_axis)] * j;
        o[size_t(course_axis)] = origin[size_t(course_axis)] + brick_size[size_t(course_axis)] * c;
        const std::string name =
            prefix + "." + std::to_string(c) + "." + std::to_string(j * int(seg.size()) + int(i));
        appendBlock(mesh, name, type, cells, o, size);
      }
  }
}

} // namespace scpdyn
