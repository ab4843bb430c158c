#include "mesh/PartOverlap.hpp"
#include "mesh/MeshOps.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <unordered_map>

namespace scpdyn
{
namespace
{

using Vec = std::array<Real, 3>;

struct ElementRef
{
  int part;
  Index local; ///< element within its part
};

Vec nodeOf(const HostMesh &mesh, const HostPart &p, Index e, int a)
{
  return mesh.coords[size_t(p.connectivity[size_t(e * nodesPerElement(p.type) + a)])];
}

Vec centroidOf(const HostMesh &mesh, const HostPart &p, Index e)
{
  const int nn = nodesPerElement(p.type);
  Vec c{0, 0, 0};
  for (int a = 0; a < nn; ++a)
  {
    const Vec x = nodeOf(mesh, p, e, a);
    for (int d = 0; d < 3; ++d)
      c[size_t(d)] += x[size_t(d)] / nn;
  }
  return c;
}

/// True if q is behind every face plane of the element by more than tol (outward normals
/// from the element centroid; 2D faces are segments in the z = 0 plane, 1D faces points).
bool strictlyInside(const HostMesh &mesh, const HostPart &p, Index e, const Vec &q, Real tol)
{
  const Vec c = centroidOf(mesh, p, e);
  const int nf = facesPerElement(p.type), fn = nodesPerFace(p.type);
  for (int f = 0; f < nf; ++f)
  {
    Vec x[4];
    Vec fc{0, 0, 0};
    for (int i = 0; i < fn; ++i)
    {
      x[i] = nodeOf(mesh, p, e, faceLocalNode(p.type, f, i));
      for (int d = 0; d < 3; ++d)
        fc[size_t(d)] += x[i][size_t(d)] / fn;
    }
    Vec n{0, 0, 0};
    if (fn == 1)
      n = {fc[0] - c[0], 0, 0};
    else if (fn == 2)
      n = {x[1][1] - x[0][1], -(x[1][0] - x[0][0]), 0};
    else
    { // the cross product of the diagonals (of the two edges of a triangle)
      const Vec a = fn == 4 ? Vec{x[2][0] - x[0][0], x[2][1] - x[0][1], x[2][2] - x[0][2]}
                            : Vec{x[1][0] - x[0][0], x[1][1] - x[0][1], x[1][2] - x[0][2]};
      const Vec b = fn == 4 ? Vec{x[3][0] - x[1][0], x[3][1] - x[1][1], x[3][2] - x[1][2]}
                            : Vec{x[2][0] - x[0][0], x[2][1] - x[0][1], x[2][2] - x[0][2]};
      n = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    }
    Real len = 0, out = 0, s = 0;
    for (int d = 0; d < 3; ++d)
      len += n[size_t(d)] * n[size_t(d)], out += n[size_t(d)] * (fc[size_t(d)] - c[size_t(d)]);
    len = std::sqrt(len);
    if (!(len > 0))
      return false;
    const Real sign = out < 0 ? -1.0 : 1.0;
    for (int d = 0; d < 3; ++d)
      s += sign * n[size_t(d)] / len * (q[size_t(d)] - fc[size_t(d)]);
    if (s > -tol)
      return false;
  }
  return true;
}

} // namespace

std::vector<PartOverlap> overlappingParts(const HostMesh &mesh)
{
  // element boxes and the largest element extent, the grid's cell
  std::vector<ElementRef> refs;
  std::vector<std::array<Vec, 2>> boxes;
  Real cell = 0;
  for (size_t p = 0; p < mesh.parts.size(); ++p)
  {
    const HostPart &part = mesh.parts[p];
    for (Index e = 0; e < part.numElements(); ++e)
    {
      std::array<Vec, 2> b{Vec{1e300, 1e300, 1e300}, Vec{-1e300, -1e300, -1e300}};
      for (int a = 0; a < nodesPerElement(part.type); ++a)
      {
        const Vec x = nodeOf(mesh, part, e, a);
        for (int d = 0; d < 3; ++d)
          b[0][size_t(d)] = std::min(b[0][size_t(d)], x[size_t(d)]),
          b[1][size_t(d)] = std::max(b[1][size_t(d)], x[size_t(d)]);
      }
      for (int d = 0; d < mesh.dim; ++d)
        cell = std::max(cell, b[1][size_t(d)] - b[0][size_t(d)]);
      refs.push_back({int(p), e});
      boxes.push_back(b);
    }
  }
  std::vector<PartOverlap> out;
  if (!(cell > 0) || mesh.parts.size() < 2)
    return out;
  auto key = [&](const Vec &x, int d) { return long(std::floor(x[size_t(d)] / cell)); };
  std::map<std::array<long, 3>, std::vector<size_t>> grid;
  for (size_t r = 0; r < refs.size(); ++r)
  {
    std::array<long, 3> lo{0, 0, 0}, hi{0, 0, 0};
    for (int d = 0; d < mesh.dim; ++d)
      lo[size_t(d)] = key(boxes[r][0], d), hi[size_t(d)] = key(boxes[r][1], d);
    for (long i = lo[0]; i <= hi[0]; ++i)
      for (long j = lo[1]; j <= hi[1]; ++j)
        for (long k = lo[2]; k <= hi[2]; ++k)
          grid[{i, j, k}].push_back(r);
  }
  std::map<std::pair<int, int>, PartOverlap> found;
  Index first_of_part = 0;
  std::vector<Index> first(mesh.parts.size(), 0);
  for (size_t p = 0; p < mesh.parts.size(); ++p)
    first[p] = first_of_part, first_of_part += mesh.parts[p].numElements();
  for (size_t r = 0; r < refs.size(); ++r)
  {
    const HostPart &part = mesh.parts[size_t(refs[r].part)];
    const Vec q = centroidOf(mesh, part, refs[r].local);
    std::array<long, 3> k{0, 0, 0};
    for (int d = 0; d < mesh.dim; ++d)
      k[size_t(d)] = key(q, d);
    const auto it = grid.find(k);
    if (it == grid.end())
      continue;
    for (size_t s : it->second)
    {
      if (refs[s].part == refs[r].part)
        continue;
      const HostPart &other = mesh.parts[size_t(refs[s].part)];
      Real size = 0;
      for (int d = 0; d < mesh.dim; ++d)
      {
        if (q[size_t(d)] < boxes[s][0][size_t(d)] || q[size_t(d)] > boxes[s][1][size_t(d)])
          size = -1;
        if (size >= 0)
          size = std::max(size, boxes[s][1][size_t(d)] - boxes[s][0][size_t(d)]);
      }
      if (size < 0 || !strictlyInside(mesh, other, refs[s].local, q, 1e-6 * size))
        continue;
      PartOverlap &o = found[{refs[r].part, refs[s].part}];
      if (o.count++ == 0)
        o.part_a = refs[r].part, o.part_b = refs[s].part,
        o.element = first[size_t(refs[r].part)] + refs[r].local;
      break;
    }
  }
  for (const auto &kv : found)
    out.push_back(kv.second);
  return out;
}

} // namespace scpdyn
