// One rank's piece of the decomposed mesh (see LocalDomain.hpp).
#include "parallel/LocalDomain.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace scpdyn
{
namespace
{

Index findSorted(const std::vector<Index> &sorted, Index value)
{
  auto it = std::lower_bound(sorted.begin(), sorted.end(), value);
  return it != sorted.end() && *it == value ? Index(it - sorted.begin()) : Index(-1);
}

} // namespace

Index LocalDomain::localNode(Index global) const { return findSorted(global_node, global); }

Index LocalDomain::localElement(Index global) const { return findSorted(global_element, global); }

LocalDomain buildLocalDomain(const HostMesh &global, const std::vector<int> &element_rank, int rank)
{
  const Index num_elements = global.numElements();
  if (Index(element_rank.size()) != num_elements)
    throw std::runtime_error("buildLocalDomain: " + std::to_string(element_rank.size()) +
                             " element ranks for " + std::to_string(num_elements) + " elements");
  LocalDomain d;
  d.rank = rank;
  for (int r : element_rank)
    d.num_ranks = std::max(d.num_ranks, r + 1);
  d.num_ranks = std::max(d.num_ranks, rank + 1);
  d.mesh.dim = global.dim;

  // One pass over the corners: the first rank that uses each node, whether a second rank
  // does, and whether this rank does. O(nodes) memory, no per-node lists.
  const size_t num_nodes = size_t(global.numNodes());
  std::vector<int> first_rank(num_nodes, -1);
  std::vector<char> multi(num_nodes, 0), mine(num_nodes, 0);
  Index element = 0;
  for (const HostPart &part : global.parts)
  {
    const size_t npe = size_t(nodesPerElement(part.type));
    for (Index e = 0; e < part.numElements(); ++e, ++element)
    {
      const int r = element_rank[size_t(element)];
      for (size_t a = 0; a < npe; ++a)
      {
        const size_t n = size_t(part.connectivity[size_t(e) * npe + a]);
        if (first_rank[n] < 0)
          first_rank[n] = r;
        else if (first_rank[n] != r)
          multi[n] = 1;
        if (r == rank)
          mine[n] = 1;
      }
    }
  }
  std::vector<Index> local_of(num_nodes, -1);
  const size_t num_local_nodes = size_t(std::count(mine.begin(), mine.end(), char(1)));
  d.global_node.reserve(num_local_nodes);
  d.mesh.coords.reserve(num_local_nodes);
  for (size_t n = 0; n < num_nodes; ++n)
    if (mine[n])
    {
      local_of[n] = Index(d.global_node.size());
      d.global_node.push_back(Index(n));
      d.mesh.coords.push_back(global.coords[n]);
    }

  // Local parts: same order, local elements only, renumbered nodes.
  element = 0;
  for (const HostPart &part : global.parts)
  {
    // every field but the connectivity (a copied vector would keep the global capacity);
    // keep in step with HostPart
    HostPart local;
    local.name = part.name;
    local.type = part.type;
    local.material = part.material;
    const size_t npe = size_t(nodesPerElement(part.type));
    size_t count = 0;
    for (Index e = 0; e < part.numElements(); ++e)
      count += element_rank[size_t(element + e)] == rank;
    local.connectivity.reserve(count * npe);
    for (Index e = 0; e < part.numElements(); ++e, ++element)
      if (element_rank[size_t(element)] == rank)
      {
        d.global_element.push_back(element);
        for (size_t a = 0; a < npe; ++a)
          local.connectivity.push_back(local_of[size_t(part.connectivity[size_t(e) * npe + a])]);
      }
    d.mesh.parts.push_back(std::move(local));
  }

  // Ranks of the shared local nodes: a second pass over the elements touching them.
  std::vector<Index> shared_index(num_nodes, -1);
  for (size_t n = 0; n < num_nodes; ++n)
    if (mine[n] && multi[n])
    {
      shared_index[n] = d.shared.size();
      d.shared.local.push_back(local_of[n]);
      d.shared.global.push_back(Index(n));
    }
  std::vector<std::vector<int>> ranks(size_t(d.shared.size()));
  element = 0;
  for (const HostPart &part : global.parts)
  {
    const size_t npe = size_t(nodesPerElement(part.type));
    for (Index e = 0; e < part.numElements(); ++e, ++element)
      for (size_t a = 0; a < npe; ++a)
      {
        const Index s = shared_index[size_t(part.connectivity[size_t(e) * npe + a])];
        if (s >= 0)
          ranks[size_t(s)].push_back(element_rank[size_t(element)]);
      }
  }
  d.shared.rank_offsets.push_back(0);
  for (auto &list : ranks)
  {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    d.shared.ranks.insert(d.shared.ranks.end(), list.begin(), list.end());
    d.shared.rank_offsets.push_back(Index(d.shared.ranks.size()));
  }

  for (const auto &set : global.node_sets)
  {
    std::vector<Index> &dst = d.mesh.node_sets[set.first];
    for (Index n : set.second)
      if (n >= 0 && size_t(n) < num_nodes && local_of[size_t(n)] >= 0)
        dst.push_back(local_of[size_t(n)]);
  }
  for (const auto &set : global.face_sets)
    d.mesh.face_sets[set.first] = localFaces(set.second, d);
  return d;
}

std::vector<int> neighbourRanks(const SharedNodes &shared, int rank)
{
  std::vector<int> out;
  for (int r : shared.ranks)
    if (r != rank)
      out.push_back(r);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::vector<char> ownedNodes(const LocalDomain &domain)
{
  std::vector<char> owned(size_t(domain.mesh.numNodes()), 1);
  const SharedNodes &sh = domain.shared;
  for (Index s = 0; s < sh.size(); ++s)
    owned[size_t(sh.local[size_t(s)])] =
        sh.ranks[size_t(sh.rank_offsets[size_t(s)])] == domain.rank;
  return owned;
}

std::vector<HostFace> localFaces(const std::vector<HostFace> &global_faces,
                                 const LocalDomain &domain)
{
  std::vector<HostFace> out;
  for (HostFace f : global_faces)
  {
    const Index e = domain.localElement(f.element);
    if (e < 0)
      continue;
    f.element = e;
    for (int i = 0; i < f.num_nodes; ++i)
      f.nodes[size_t(i)] = domain.localNode(f.nodes[size_t(i)]);
    out.push_back(f);
  }
  return out;
}

} // namespace scpdyn
