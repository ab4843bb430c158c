// Element partition with METIS on the dual graph plus joint edges (see Partitioner.hpp).
#include "parallel/Partitioner.hpp"

#include "mesh/MeshOps.hpp"

#include <metis.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <tuple>

namespace scpdyn
{
namespace
{

using Vec3 = std::array<Real, 3>;

struct FaceGeometry
{
  Vec3 centroid{};
  Vec3 normal{}; ///< unit outward normal
  Real size = 0; ///< 2 x max node distance from the centroid (1D: element length) [m]
};

Vec3 sub(const Vec3 &a, const Vec3 &b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Real dot(const Vec3 &a, const Vec3 &b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/// Centroid, outward normal and size of every external face. The normal of a polygon comes
/// from Newell's formula (exact for planar faces, the mean normal of a warped quad).
std::vector<FaceGeometry> faceGeometry(const HostMesh &mesh, const std::vector<HostFace> &faces)
{
  std::vector<Index> first_element(mesh.parts.size() + 1, 0);
  for (size_t p = 0; p < mesh.parts.size(); ++p)
    first_element[p + 1] = first_element[p] + mesh.parts[p].numElements();
  std::vector<FaceGeometry> out(faces.size());
  for (size_t k = 0; k < faces.size(); ++k)
  {
    const HostFace &f = faces[k];
    FaceGeometry &g = out[k];
    for (int i = 0; i < f.num_nodes; ++i)
      for (int d = 0; d < 3; ++d)
        g.centroid[d] += mesh.coords[size_t(f.nodes[i])][d] / f.num_nodes;
    for (int i = 0; i < f.num_nodes; ++i)
    {
      const Vec3 r = sub(mesh.coords[size_t(f.nodes[i])], g.centroid);
      g.size = std::max(g.size, 2 * std::sqrt(dot(r, r)));
    }
    if (f.num_nodes == 1)
    {
      // 1D: the face is a point; the normal is -x for local face 0, +x for face 1
      g.normal = {f.local_face == 0 ? Real(-1) : Real(1), 0, 0};
      const HostPart &part = mesh.parts[size_t(f.part)];
      const Index e = f.element - first_element[size_t(f.part)];
      const Vec3 &a = mesh.coords[size_t(part.connectivity[size_t(2 * e)])];
      const Vec3 &b = mesh.coords[size_t(part.connectivity[size_t(2 * e + 1)])];
      g.size = std::abs(b[0] - a[0]);
    }
    else if (f.num_nodes == 2)
    {
      // 2D segment with the element on its left: outward normal = (dy, -dx)
      const Vec3 t = sub(mesh.coords[size_t(f.nodes[1])], mesh.coords[size_t(f.nodes[0])]);
      g.normal = {t[1], -t[0], 0};
    }
    else
    {
      for (int i = 0; i < f.num_nodes; ++i)
      {
        const Vec3 &a = mesh.coords[size_t(f.nodes[i])];
        const Vec3 &b = mesh.coords[size_t(f.nodes[(i + 1) % f.num_nodes])];
        g.normal[0] += (a[1] - b[1]) * (a[2] + b[2]);
        g.normal[1] += (a[2] - b[2]) * (a[0] + b[0]);
        g.normal[2] += (a[0] - b[0]) * (a[1] + b[1]);
      }
    }
    const Real len = std::sqrt(dot(g.normal, g.normal));
    if (len > 0)
      for (int d = 0; d < 3; ++d)
        g.normal[d] /= len;
  }
  return out;
}

struct Edge
{
  Index a, b;
  int w;
};

/// Element pairs that share a face (same sorted node ids), whatever their parts.
void faceEdges(const HostMesh &mesh, int weight, std::vector<Edge> &edges)
{
  struct Key
  {
    std::array<Index, kMaxFaceNodes> nodes;
    Index element;
  };
  std::vector<Key> keys;
  size_t count = 0;
  for (const HostPart &p : mesh.parts)
    count += size_t(p.numElements()) * size_t(facesPerElement(p.type));
  keys.reserve(count);
  Index element = 0;
  for (const HostPart &part : mesh.parts)
  {
    const int npe = nodesPerElement(part.type), npf = nodesPerFace(part.type);
    for (Index e = 0; e < part.numElements(); ++e, ++element)
      for (int f = 0; f < facesPerElement(part.type); ++f)
      {
        Key k{{{-1, -1, -1, -1}}, element};
        for (int i = 0; i < npf; ++i)
          k.nodes[size_t(i)] =
              part.connectivity[size_t(e) * size_t(npe) + size_t(faceLocalNode(part.type, f, i))];
        std::sort(k.nodes.begin(), k.nodes.begin() + npf);
        keys.push_back(k);
      }
  }
  std::sort(keys.begin(), keys.end(), [](const Key &x, const Key &y) {
    return std::tie(x.nodes, x.element) < std::tie(y.nodes, y.element);
  });
  for (size_t i = 0; i < keys.size();)
  {
    size_t j = i + 1;
    while (j < keys.size() && keys[j].nodes == keys[i].nodes)
      ++j;
    for (size_t a = i; a < j; ++a)
      for (size_t b = a + 1; b < j; ++b)
        if (keys[a].element != keys[b].element)
          edges.push_back({keys[a].element, keys[b].element, weight});
    i = j;
  }
}

} // namespace

std::vector<std::pair<Index, Index>> jointFacePairs(const HostMesh &mesh,
                                                    const std::vector<HostFace> &external_faces,
                                                    const PartitionOptions &options)
{
  std::vector<std::pair<Index, Index>> pairs;
  if (external_faces.empty())
    return pairs;
  const std::vector<FaceGeometry> geo = faceGeometry(mesh, external_faces);
  Real h = 0;
  Vec3 lo = geo[0].centroid;
  for (const FaceGeometry &g : geo)
  {
    h = std::max(h, g.size);
    for (int d = 0; d < 3; ++d)
      lo[d] = std::min(lo[d], g.centroid[d]);
  }
  // Partners lie within max(overlap, gap) x (larger size) <= h of each other when both
  // factors are <= 1, so a grid of cell h finds them in the 27 neighbouring cells.
  const Real reach = std::max({options.joint_overlap, options.joint_gap, Real(1)});
  const Real cell = std::max(h * reach, Real(1e-300));
  using Cell = std::array<std::int64_t, 3>;
  std::vector<std::pair<Cell, Index>> grid(geo.size());
  for (size_t k = 0; k < geo.size(); ++k)
  {
    Cell c;
    for (int d = 0; d < 3; ++d)
      c[size_t(d)] = std::int64_t(std::floor((geo[k].centroid[d] - lo[d]) / cell));
    grid[k] = {c, Index(k)};
  }
  std::sort(grid.begin(), grid.end());
  for (const auto &entry : grid)
  {
    const Index a = entry.second;
    const FaceGeometry &ga = geo[size_t(a)];
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz)
        {
          const Cell c{entry.first[0] + dx, entry.first[1] + dy, entry.first[2] + dz};
          auto it = std::lower_bound(grid.begin(), grid.end(), std::make_pair(c, Index(-1)));
          for (; it != grid.end() && it->first == c; ++it)
          {
            const Index b = it->second;
            if (b <= a || external_faces[size_t(b)].part == external_faces[size_t(a)].part)
              continue;
            const FaceGeometry &gb = geo[size_t(b)];
            if (dot(ga.normal, gb.normal) >= -0.9)
              continue;
            const Vec3 d = sub(gb.centroid, ga.centroid);
            const Real gap = dot(d, ga.normal);
            const Real tangential = std::sqrt(std::max(Real(0), dot(d, d) - gap * gap));
            const Real size = std::max(ga.size, gb.size);
            if (std::abs(gap) <= options.joint_gap * size &&
                tangential <= options.joint_overlap * size)
              pairs.push_back({a, b});
          }
        }
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

std::vector<int> partitionElements(const HostMesh &mesh,
                                   const std::vector<HostFace> &external_faces, int nparts,
                                   const PartitionOptions &options)
{
  if (nparts < 1)
    throw std::runtime_error("partitionElements: nparts must be >= 1, got " +
                             std::to_string(nparts));
  const Index num_elements = mesh.numElements();
  std::vector<int> rank(size_t(num_elements), 0);
  if (nparts == 1 || num_elements == 0)
    return rank;

  std::vector<Edge> edges;
  faceEdges(mesh, options.face_weight, edges);
  if (options.joint_weight > 0)
    for (const auto &p : jointFacePairs(mesh, external_faces, options))
      edges.push_back({external_faces[size_t(p.first)].element,
                       external_faces[size_t(p.second)].element, options.joint_weight});
  // Symmetric CSR without duplicates; a pair found twice keeps the larger weight.
  for (Edge &e : edges)
    if (e.a > e.b)
      std::swap(e.a, e.b);
  std::sort(edges.begin(), edges.end(), [](const Edge &x, const Edge &y) {
    return std::tie(x.a, x.b, y.w) < std::tie(y.a, y.b, x.w);
  });
  edges.erase(std::unique(edges.begin(), edges.end(),
                          [](const Edge &x, const Edge &y) { return x.a == y.a && x.b == y.b; }),
              edges.end());
  std::vector<idx_t> xadj(size_t(num_elements) + 1, 0);
  for (const Edge &e : edges)
  {
    ++xadj[size_t(e.a) + 1];
    ++xadj[size_t(e.b) + 1];
  }
  for (size_t i = 0; i < size_t(num_elements); ++i)
    xadj[i + 1] += xadj[i];
  std::vector<idx_t> adjncy(size_t(xadj.back())), adjwgt(size_t(xadj.back()));
  std::vector<idx_t> fill(xadj.begin(), xadj.end() - 1);
  for (const Edge &e : edges)
  {
    adjncy[size_t(fill[size_t(e.a)])] = e.b;
    adjwgt[size_t(fill[size_t(e.a)]++)] = e.w;
    adjncy[size_t(fill[size_t(e.b)])] = e.a;
    adjwgt[size_t(fill[size_t(e.b)]++)] = e.w;
  }
  edges.clear();
  edges.shrink_to_fit();
  if (adjncy.empty())
  {
    // no adjacency at all (e.g. separate 1D points): contiguous equal slices
    for (Index e = 0; e < num_elements; ++e)
      rank[size_t(e)] = int((long long)(e)*nparts / num_elements);
    return rank;
  }

  idx_t options_metis[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options_metis);
  options_metis[METIS_OPTION_SEED] = options.seed;
  options_metis[METIS_OPTION_UFACTOR] = options.ufactor;
  options_metis[METIS_OPTION_NUMBERING] = 0;
  idx_t nvtxs = num_elements, ncon = 1, np = nparts, objval = 0;
  std::vector<idx_t> part(size_t(num_elements), 0);
  const int status = METIS_PartGraphKway(&nvtxs, &ncon, xadj.data(), adjncy.data(), nullptr,
                                         nullptr, adjwgt.data(), &np, nullptr, nullptr,
                                         options_metis, &objval, part.data());
  if (status != METIS_OK)
    throw std::runtime_error("partitionElements: METIS_PartGraphKway failed with status " +
                             std::to_string(status));
  for (size_t e = 0; e < part.size(); ++e)
    rank[e] = int(part[e]);
  return rank;
}

std::vector<int> partitionElementsOnRoot(const HostMesh &mesh,
                                         const std::vector<HostFace> &external_faces, MPI_Comm comm,
                                         const PartitionOptions &options)
{
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  std::vector<int> part;
  if (rank == 0)
    part = partitionElements(mesh, external_faces, size, options);
  else
    part.assign(size_t(mesh.numElements()), 0);
  if (size > 1)
    MPI_Bcast(part.data(), int(part.size()), MPI_INT, 0, comm);
  return part;
}

} // namespace scpdyn
