#include "mesh/MeshOps.hpp"
#include "core/RealText.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <string>
#include <tuple>

namespace scpdyn
{
namespace
{
using Vec3 = std::array<Real, 3>;

Vec3 sub(const Vec3 &a, const Vec3 &b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Real norm(const Vec3 &a) { return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }
Real det3(const Vec3 &a, const Vec3 &b, const Vec3 &c)
{
  return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
         a[2] * (b[0] * c[1] - b[1] * c[0]);
}

// Relative threshold on sin(angle): catches collinear/coplanar corners despite round-off.
constexpr Real kDegenerate = 1e-12;

void checkPartIndex(const HostMesh &mesh, int p)
{
  if (p < 0 || p >= int(mesh.parts.size()))
    throw std::runtime_error("mesh: part index " + std::to_string(p) + " out of range (" +
                             std::to_string(mesh.parts.size()) + " parts)");
}

// Hex8 node at reference corner (a, b, c) in {0,1}^3 (bottom face counter-clockwise).
int hexNode(int a, int b, int c)
{
  static const int bottom[2][2] = {{0, 3}, {1, 2}}; // [a][b]
  return 4 * c + bottom[a][b];
}

// Returns an empty string when the element is valid, else what is wrong with it.
std::string elementProblem(const HostMesh &mesh, ElementType type, const Index *n)
{
  auto x = [&](int i) { return mesh.coords[n[i]]; };
  switch (type)
  {
  case ElementType::Line2:
    return x(1)[0] - x(0)[0] > 0 ? "" : "non-positive length";
  case ElementType::Quad4:
    for (int i = 0; i < 4; ++i)
    {
      const Vec3 e1 = sub(x((i + 1) % 4), x(i)), e2 = sub(x((i + 3) % 4), x(i));
      const Real cross = e1[0] * e2[1] - e1[1] * e2[0];
      if (!(cross > kDegenerate * norm(e1) * norm(e2)))
        return "inverted or degenerate at corner " + std::to_string(i) + " (signed corner area " +
               formatReal(0.5 * cross) + " m^2)";
    }
    return "";
  case ElementType::Hex8:
    for (int c = 0; c < 2; ++c)
      for (int b = 0; b < 2; ++b)
        for (int a = 0; a < 2; ++a)
        {
          const Vec3 ex = sub(x(hexNode(1, b, c)), x(hexNode(0, b, c)));
          const Vec3 ey = sub(x(hexNode(a, 1, c)), x(hexNode(a, 0, c)));
          const Vec3 ez = sub(x(hexNode(a, b, 1)), x(hexNode(a, b, 0)));
          const Real j = det3(ex, ey, ez);
          if (!(j > kDegenerate * norm(ex) * norm(ey) * norm(ez)))
            return "inverted or degenerate at corner " + std::to_string(hexNode(a, b, c)) +
                   " (corner Jacobian " + std::to_string(j) + " m^3)";
        }
    return "";
  case ElementType::Tet4:
  {
    const Vec3 e1 = sub(x(1), x(0)), e2 = sub(x(2), x(0)), e3 = sub(x(3), x(0));
    const Real v = det3(e1, e2, e3);
    if (!(v > kDegenerate * norm(e1) * norm(e2) * norm(e3)))
      return "inverted or degenerate (6 x volume " + formatReal(v) + " m^3)";
    return "";
  }
  }
  return "unknown element type";
}

Real elementMeasure(const HostMesh &mesh, ElementType type, const Index *n)
{
  auto x = [&](int i) { return mesh.coords[n[i]]; };
  switch (type)
  {
  case ElementType::Line2:
    return x(1)[0] - x(0)[0];
  case ElementType::Quad4:
  { // shoelace: exact area of a planar bilinear quad
    Real a = 0;
    for (int i = 0; i < 4; ++i)
      a += x(i)[0] * x((i + 1) % 4)[1] - x((i + 1) % 4)[0] * x(i)[1];
    return 0.5 * a;
  }
  case ElementType::Tet4:
    return det3(sub(x(1), x(0)), sub(x(2), x(0)), sub(x(3), x(0))) / 6.0;
  case ElementType::Hex8:
  { // det J is at most quadratic in each reference coordinate: 2x2x2 Gauss is exact
    static const Real s[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                 {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
    const Real g = 1.0 / std::sqrt(3.0);
    Real vol = 0;
    for (int q = 0; q < 8; ++q)
    {
      const Real p[3] = {s[q][0] * g, s[q][1] * g, s[q][2] * g};
      Vec3 col[3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
      for (int a = 0; a < 8; ++a)
        for (int d = 0; d < 3; ++d)
        {
          Real dn = 0.125 * s[a][d];
          for (int o = 0; o < 3; ++o)
            if (o != d)
              dn *= 1 + s[a][o] * p[o];
          for (int k = 0; k < 3; ++k)
            col[d][k] += dn * x(a)[k];
        }
      vol += det3(col[0], col[1], col[2]); // unit weights
    }
    return vol;
  }
  }
  return 0;
}

bool inBox(const Vec3 &x, const Vec3 &lo, const Vec3 &hi, Real tol)
{
  for (int d = 0; d < 3; ++d)
    if (x[d] < lo[d] - tol || x[d] > hi[d] + tol)
      return false;
  return true;
}

Index findRoot(std::vector<Index> &parent, Index i)
{
  while (parent[i] != i)
  {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}
} // namespace

int faceLocalNode(ElementType t, int f, int i)
{
  switch (t)
  {
  case ElementType::Line2:
    return kLine2Faces[f][i];
  case ElementType::Quad4:
    return kQuad4Faces[f][i];
  case ElementType::Hex8:
    return kHex8Faces[f][i];
  case ElementType::Tet4:
    return kTet4Faces[f][i];
  }
  return -1;
}

namespace
{

/// Every face of every element, in (element, local face) order, and how many faces have the
/// same nodes. Faces are grouped across parts: two parts whose nodes were merged share the faces
/// between them, and those faces are inside the body, not on its surface.
struct ElementFaces
{
  std::vector<HostFace> faces;
  std::vector<size_t> group_size; ///< per face: the faces with its nodes (itself too)
  std::vector<size_t> partner;    ///< per face of a group of two: the other one
};

ElementFaces elementFaces(const HostMesh &mesh)
{
  ElementFaces out;
  std::vector<std::array<Index, kMaxFaceNodes>> keys;
  Index element = 0;
  for (int p = 0; p < int(mesh.parts.size()); ++p)
  {
    const HostPart &part = mesh.parts[p];
    const int npe = nodesPerElement(part.type), npf = nodesPerFace(part.type);
    for (Index e = 0; e < part.numElements(); ++e, ++element)
      for (int f = 0; f < facesPerElement(part.type); ++f)
      {
        HostFace face;
        face.num_nodes = npf;
        face.element = element;
        face.local_face = f;
        face.part = p;
        for (int i = 0; i < npf; ++i)
          face.nodes[i] = part.connectivity[size_t(e) * npe + faceLocalNode(part.type, f, i)];
        std::array<Index, kMaxFaceNodes> key = face.nodes;
        std::sort(key.begin(), key.begin() + npf);
        out.faces.push_back(face);
        keys.push_back(key);
      }
  }
  // sort a permutation by the sorted nodes, so the faces keep their (element, face) order
  std::vector<size_t> perm(keys.size());
  std::iota(perm.begin(), perm.end(), size_t(0));
  auto less = [&](size_t a, size_t b) { return keys[a] < keys[b]; };
  std::sort(perm.begin(), perm.end(), less);
  out.group_size.assign(keys.size(), 0);
  out.partner.assign(keys.size(), 0);
  for (size_t i = 0; i < perm.size();)
  {
    size_t j = i + 1;
    while (j < perm.size() && !less(perm[i], perm[j]))
      ++j;
    for (size_t k = i; k < j; ++k)
      out.group_size[perm[k]] = j - i;
    if (j == i + 2)
      out.partner[perm[i]] = perm[i + 1], out.partner[perm[i + 1]] = perm[i];
    i = j;
  }
  return out;
}

} // namespace

std::vector<HostFace> extractExternalFaces(const HostMesh &mesh)
{
  const ElementFaces all = elementFaces(mesh);
  std::vector<HostFace> out;
  for (size_t i = 0; i < all.faces.size(); ++i)
    if (all.group_size[i] == 1)
      out.push_back(all.faces[i]);
  return out;
}

std::vector<HostFace> interiorFaces(const HostMesh &mesh, const std::vector<char> &parts)
{
  const ElementFaces all = elementFaces(mesh);
  std::vector<HostFace> out;
  for (size_t i = 0; i < all.faces.size(); ++i)
    if (all.group_size[i] == 2 &&
        (parts[size_t(all.faces[i].part)] || parts[size_t(all.faces[all.partner[i]].part)]))
    {
      HostFace f = all.faces[i];
      f.twin = all.faces[all.partner[i]].element;
      out.push_back(f);
    }
  return out;
}

void moveNodesRigidly(HostMesh &mesh, std::size_t first, Real angle,
                      const std::array<Real, 3> &axis, const std::array<Real, 3> &point,
                      const std::array<Real, 3> &shift)
{
  const Real c = std::cos(angle), s = std::sin(angle);
  const std::array<Real, 3> &k = axis;
  for (std::size_t n = first; n < mesh.coords.size(); ++n)
  {
    std::array<Real, 3> &x = mesh.coords[n];
    const Real v[3] = {x[0] - point[0], x[1] - point[1], x[2] - point[2]};
    const Real kv = k[0] * v[0] + k[1] * v[1] + k[2] * v[2];
    const Real kxv[3] = {k[1] * v[2] - k[2] * v[1], k[2] * v[0] - k[0] * v[2],
                         k[0] * v[1] - k[1] * v[0]};
    // v cos + (k x v) sin + k (k.v)(1 - cos)
    for (int d = 0; d < 3; ++d)
      x[size_t(d)] =
          point[size_t(d)] + v[d] * c + kxv[d] * s + k[size_t(d)] * kv * (1 - c) + shift[size_t(d)];
  }
}

void mergeCoincidentNodes(HostMesh &mesh, const std::vector<int> &parts, Real tolerance)
{
  if (!(tolerance >= 0))
    throw std::runtime_error("mergeCoincidentNodes: tolerance must be >= 0");
  const std::vector<Index> nodes = nodesOfParts(mesh, parts);
  if (nodes.empty())
    return;
  Vec3 lo = mesh.coords[nodes[0]], hi = lo;
  for (Index n : nodes)
    for (int d = 0; d < 3; ++d)
    {
      lo[d] = std::min(lo[d], mesh.coords[n][d]);
      hi[d] = std::max(hi[d], mesh.coords[n][d]);
    }
  const Real extent = std::max(norm(sub(hi, lo)), Real(1e-300));
  // Grid cells no smaller than tolerance, so partners are in the 27 neighbouring cells; a
  // floor keeps cell indices well inside int64 for tiny (or zero) tolerances.
  const Real h = std::max(tolerance, 1e-12 * extent);
  using Cell = std::array<std::int64_t, 3>;
  std::vector<std::pair<Cell, Index>> grid;
  grid.reserve(nodes.size());
  for (Index n : nodes)
  {
    Cell c;
    for (int d = 0; d < 3; ++d)
      c[d] = std::int64_t(std::floor((mesh.coords[n][d] - lo[d]) / h));
    grid.push_back({c, n});
  }
  std::sort(grid.begin(), grid.end());
  std::vector<Index> parent(mesh.numNodes());
  std::iota(parent.begin(), parent.end(), Index(0));
  for (const auto &g : grid)
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz)
        {
          const Cell c{g.first[0] + dx, g.first[1] + dy, g.first[2] + dz};
          auto it = std::lower_bound(grid.begin(), grid.end(), std::make_pair(c, Index(-1)));
          for (; it != grid.end() && it->first == c; ++it)
          {
            if (it->second <= g.second ||
                norm(sub(mesh.coords[it->second], mesh.coords[g.second])) > tolerance)
              continue;
            const Index ra = findRoot(parent, g.second), rb = findRoot(parent, it->second);
            if (ra < rb)
              parent[rb] = ra;
            else
              parent[ra] = rb;
          }
        }
  std::vector<Index> renum(mesh.numNodes());
  std::vector<std::array<Real, 3>> coords;
  for (Index i = 0; i < mesh.numNodes(); ++i)
  {
    const Index r = findRoot(parent, i); // the lowest id of its group, so r <= i
    if (r == i)
    {
      renum[i] = Index(coords.size());
      coords.push_back(mesh.coords[i]);
    }
    else
      renum[i] = renum[r];
  }
  mesh.coords.swap(coords);
  for (auto &part : mesh.parts)
    for (auto &n : part.connectivity)
      n = renum[n];
  for (auto &set : mesh.node_sets)
  {
    for (auto &n : set.second)
      n = renum[n];
    std::sort(set.second.begin(), set.second.end());
    set.second.erase(std::unique(set.second.begin(), set.second.end()), set.second.end());
  }
  for (auto &set : mesh.face_sets)
    for (auto &f : set.second)
      for (int i = 0; i < f.num_nodes; ++i)
        f.nodes[i] = renum[f.nodes[i]];
}

MeshBox meshBox(const HostMesh &mesh)
{
  MeshBox b;
  for (const auto &c : mesh.coords)
    for (size_t i = 0; i < 3; ++i)
    {
      b.lo[i] = std::min(b.lo[i], c[i]);
      b.hi[i] = std::max(b.hi[i], c[i]);
    }
  return b;
}

std::vector<Index> nodesInBox(const HostMesh &mesh, std::array<Real, 3> lo, std::array<Real, 3> hi,
                              Real tol)
{
  std::vector<Index> out;
  for (Index i = 0; i < mesh.numNodes(); ++i)
    if (inBox(mesh.coords[i], lo, hi, tol))
      out.push_back(i);
  return out;
}

std::vector<HostFace> facesInBox(const std::vector<HostFace> &external, const HostMesh &mesh,
                                 std::array<Real, 3> lo, std::array<Real, 3> hi, Real tol)
{
  std::vector<HostFace> out;
  for (const auto &f : external)
  {
    bool inside = true;
    for (int i = 0; i < f.num_nodes && inside; ++i)
      inside = inBox(mesh.coords[f.nodes[i]], lo, hi, tol);
    if (inside)
      out.push_back(f);
  }
  return out;
}

std::vector<Index> nodesOfParts(const HostMesh &mesh, const std::vector<int> &parts)
{
  std::vector<Index> out;
  for (int p : parts)
  {
    checkPartIndex(mesh, p);
    out.insert(out.end(), mesh.parts[p].connectivity.begin(), mesh.parts[p].connectivity.end());
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::vector<HostFace> facesOfParts(const std::vector<HostFace> &external,
                                   const std::vector<int> &parts)
{
  std::vector<HostFace> out;
  for (const auto &f : external)
    if (std::find(parts.begin(), parts.end(), f.part) != parts.end())
      out.push_back(f);
  return out;
}

void checkElements(const HostMesh &mesh)
{
  for (const auto &part : mesh.parts)
  {
    if (part.numElements() == 0)
      throw std::runtime_error("part '" + part.name + "' has no elements");
    const int npe = nodesPerElement(part.type);
    if (part.connectivity.size() % size_t(npe) != 0)
      throw std::runtime_error("part '" + part.name +
                               "': connectivity length is not a multiple of " +
                               std::to_string(npe));
    for (Index n : part.connectivity)
      if (n < 0 || n >= mesh.numNodes())
        throw std::runtime_error("part '" + part.name + "': node id " + std::to_string(n) +
                                 " out of range");
    for (Index e = 0; e < part.numElements(); ++e)
    {
      const std::string what = elementProblem(mesh, part.type, &part.connectivity[size_t(e) * npe]);
      if (!what.empty())
        throw std::runtime_error("part '" + part.name + "', element " + std::to_string(e) + ": " +
                                 what);
    }
  }
}

Real meshMeasure(const HostMesh &mesh, int part)
{
  checkPartIndex(mesh, part);
  const HostPart &p = mesh.parts[part];
  const int npe = nodesPerElement(p.type);
  Real sum = 0;
  for (Index e = 0; e < p.numElements(); ++e)
    sum += elementMeasure(mesh, p.type, &p.connectivity[size_t(e) * npe]);
  return sum;
}

void appendMesh(HostMesh &dst, HostMesh src, const std::string &prefix)
{
  const Index node_offset = dst.numNodes();
  const Index element_offset = dst.numElements();
  const int part_offset = int(dst.parts.size());
  dst.dim = src.dim;
  dst.coords.insert(dst.coords.end(), src.coords.begin(), src.coords.end());
  for (auto &p : src.parts)
  {
    for (auto &n : p.connectivity)
      n += node_offset;
    p.name = prefix + p.name;
    dst.parts.push_back(std::move(p));
  }
  for (auto &kv : src.node_sets)
  {
    auto &out = dst.node_sets[kv.first];
    for (Index n : kv.second)
      out.push_back(n + node_offset);
  }
  for (auto &kv : src.face_sets)
  {
    auto &out = dst.face_sets[kv.first];
    for (HostFace f : kv.second)
    {
      for (int k = 0; k < f.num_nodes; ++k)
        f.nodes[size_t(k)] += node_offset;
      f.element += element_offset;
      f.part += part_offset;
      out.push_back(f);
    }
  }
}

} // namespace scpdyn
