#include "mesh/GmshReader.hpp"

#include "mesh/MeshOps.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <unordered_map>
#include <vector>

namespace scpdyn
{
namespace
{
using Tag = long long;

std::string gmshTypeName(int t)
{
  static const std::map<int, std::string> names = {
      {1, "line2"},  {2, "tri3"},     {3, "quad4"},  {4, "tet4"},   {5, "hex8"},
      {6, "prism6"}, {7, "pyramid5"}, {8, "line3"},  {9, "tri6"},   {10, "quad9"},
      {11, "tet10"}, {12, "hex27"},   {15, "point"}, {16, "quad8"}, {17, "hex20"}};
  auto it = names.find(t);
  return "gmsh type " + std::to_string(t) + (it != names.end() ? " (" + it->second + ")" : "");
}

// Line-oriented reader: gmsh ASCII writes one node, element or entity per line, so every
// error can name its line.
struct Lines
{
  std::ifstream in;
  std::string path, text;
  int no = 0;

  [[noreturn]] void failAt(int line, const std::string &what) const
  {
    throw std::runtime_error(path + ":" + std::to_string(line) + ": " + what);
  }
  [[noreturn]] void fail(const std::string &what) const { failAt(no, what); }
  bool next()
  {
    if (!std::getline(in, text))
      return false;
    ++no;
    if (!text.empty() && text.back() == '\r')
      text.pop_back();
    return true;
  }
  void need(const std::string &section)
  {
    if (!next())
      fail("unexpected end of file inside " + section);
  }
  std::vector<std::string> tokens(size_t at_least, const std::string &what) const
  {
    std::istringstream s(text);
    std::vector<std::string> t;
    for (std::string w; s >> w;)
      t.push_back(w);
    if (t.size() < at_least)
      fail("expected " + what + ", got '" + text + "'");
    return t;
  }
  Tag toInt(const std::string &s) const
  {
    size_t used = 0;
    Tag v = 0;
    try
    {
      v = std::stoll(s, &used);
    }
    catch (const std::exception &)
    {
      used = 0;
    }
    if (used == 0 || used != s.size())
      fail("expected an integer, got '" + s + "'");
    return v;
  }
  Real toReal(const std::string &s) const
  {
    size_t used = 0;
    Real v = 0;
    try
    {
      v = std::stod(s, &used);
    }
    catch (const std::exception &)
    {
      used = 0;
    }
    if (used == 0 || used != s.size())
      fail("expected a number, got '" + s + "'");
    return v;
  }
};

struct Block
{
  int dim, entity, type, line, count;
  std::vector<std::vector<Tag>> nodes; // node tags per element
  std::vector<int> lines;              // line of each element
};

struct FileData
{
  std::map<std::pair<int, int>, std::string> names;       // (dim, phys tag) -> name
  std::map<std::pair<int, int>, std::vector<int>> physOf; // (dim, entity) -> phys tags
  std::unordered_map<Tag, std::array<Real, 3>> coords;
  std::vector<Block> blocks;
};

void readSection(Lines &in, const std::string &name, FileData &fd)
{
  const std::string end = "$End" + name.substr(1);
  if (name == "$PhysicalNames")
  {
    in.need(name);
    const Tag n = in.toInt(in.tokens(1, "the number of physical names")[0]);
    for (Tag i = 0; i < n; ++i)
    {
      in.need(name);
      auto t = in.tokens(3, "dim tag \"name\"");
      const size_t q0 = in.text.find('"'), q1 = in.text.rfind('"');
      if (q0 == std::string::npos || q1 == q0)
        in.fail("physical name must be quoted");
      fd.names[{int(in.toInt(t[0])), int(in.toInt(t[1]))}] = in.text.substr(q0 + 1, q1 - q0 - 1);
    }
  }
  else if (name == "$Entities")
  {
    in.need(name);
    auto t = in.tokens(4, "numPoints numCurves numSurfaces numVolumes");
    for (int dim = 0; dim < 4; ++dim)
      for (Tag i = 0, n = in.toInt(t[dim]); i < n; ++i)
      {
        in.need(name);
        const size_t first = dim == 0 ? 4 : 7; // point: tag x y z; others: tag + bounding box
        auto e = in.tokens(first + 1, "an entity line");
        const Tag np = in.toInt(e[first]);
        if (e.size() < first + 1 + size_t(np))
          in.fail("entity line lists fewer physical tags than announced");
        auto &phys = fd.physOf[{dim, int(in.toInt(e[0]))}];
        for (Tag k = 0; k < np; ++k)
          phys.push_back(std::abs(int(in.toInt(e[first + 1 + k]))));
      }
  }
  else if (name == "$Nodes")
  {
    in.need(name);
    const Tag nblocks = in.toInt(in.tokens(4, "numEntityBlocks numNodes minTag maxTag")[0]);
    std::unordered_map<Tag, int> node_line; // line of each node's coordinates
    for (Tag b = 0; b < nblocks; ++b)
    {
      in.need(name);
      const Tag n = in.toInt(in.tokens(4, "entityDim entityTag parametric numNodes")[3]);
      std::vector<Tag> tags;
      while (Tag(tags.size()) < n)
      {
        in.need(name);
        for (const auto &w : in.tokens(1, "node tags"))
          tags.push_back(in.toInt(w));
      }
      for (Tag i = 0; i < n; ++i)
      {
        in.need(name);
        auto x = in.tokens(3, "x y z");
        if (!node_line.emplace(tags[i], in.no).second) // else the last copy would win
          in.fail("node tag " + std::to_string(tags[i]) + " given twice (first at line " +
                  std::to_string(node_line[tags[i]]) + ")");
        fd.coords[tags[i]] = {in.toReal(x[0]), in.toReal(x[1]), in.toReal(x[2])};
      }
    }
  }
  else if (name == "$Elements")
  {
    in.need(name);
    const Tag nblocks = in.toInt(in.tokens(4, "numEntityBlocks numElements minTag maxTag")[0]);
    for (Tag b = 0; b < nblocks; ++b)
    {
      in.need(name);
      auto h = in.tokens(4, "entityDim entityTag elementType numElements");
      Block blk{int(in.toInt(h[0])),
                int(in.toInt(h[1])),
                int(in.toInt(h[2])),
                in.no,
                int(in.toInt(h[3])),
                {},
                {}};
      for (int i = 0; i < blk.count; ++i)
      {
        in.need(name);
        auto e = in.tokens(2, "element tag and node tags");
        std::vector<Tag> nodes;
        for (size_t k = 1; k < e.size(); ++k)
          nodes.push_back(in.toInt(e[k]));
        blk.nodes.push_back(std::move(nodes));
        blk.lines.push_back(in.no);
      }
      fd.blocks.push_back(std::move(blk));
    }
  }
  else if (name == "$PartitionedEntities")
    in.fail("partitioned gmsh meshes are not supported (write the mesh unpartitioned)");
  // Every section, read or skipped, must end with its $End marker.
  for (;;)
  {
    in.need(name);
    if (in.text == end)
      return;
    if (name == "$PhysicalNames" || name == "$Entities" || name == "$Nodes" || name == "$Elements")
      in.fail("expected " + end + ", got '" + in.text + "'");
  }
}

std::string physName(const FileData &fd, int dim, int tag)
{
  auto it = fd.names.find({dim, tag});
  return it != fd.names.end() ? it->second : "physical_" + std::to_string(tag);
}

const std::vector<int> &groupsOf(const FileData &fd, const Block &b)
{
  static const std::vector<int> none;
  auto it = fd.physOf.find({b.dim, b.entity});
  return it != fd.physOf.end() ? it->second : none;
}

// Where gmsh gives an element negative measure (e.g. a surface meshed clockwise), flip it.
void orient(ElementType t, const std::vector<std::array<Real, 3>> &x, Index *n)
{
  auto d = [&](int a, int b, int k) { return x[n[a]][k] - x[n[b]][k]; };
  auto det = [](const Real a[3], const Real b[3], const Real c[3]) {
    return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
           a[2] * (b[0] * c[1] - b[1] * c[0]);
  };
  if (t == ElementType::Line2 && d(1, 0, 0) < 0)
    std::swap(n[0], n[1]);
  else if (t == ElementType::Quad4 &&
           d(2, 0, 0) * d(3, 1, 1) - d(2, 0, 1) * d(3, 1, 0) < 0) // diagonals' cross product
    std::swap(n[1], n[3]);
  else if (t == ElementType::Tet4)
  {
    Real a[3], b[3], c[3];
    for (int k = 0; k < 3; ++k)
      a[k] = d(1, 0, k), b[k] = d(2, 0, k), c[k] = d(3, 0, k);
    if (det(a, b, c) < 0)
      std::swap(n[1], n[2]);
  }
  else if (t == ElementType::Hex8)
  {
    Real a[3], b[3], c[3]; // mean edge vectors: the Jacobian at the centre (up to 1/4)
    for (int k = 0; k < 3; ++k)
    {
      a[k] = d(1, 0, k) + d(2, 3, k) + d(5, 4, k) + d(6, 7, k);
      b[k] = d(3, 0, k) + d(2, 1, k) + d(7, 4, k) + d(6, 5, k);
      c[k] = d(4, 0, k) + d(5, 1, k) + d(6, 2, k) + d(7, 3, k);
    }
    if (det(a, b, c) < 0)
    {
      std::swap(n[1], n[3]);
      std::swap(n[5], n[7]);
    }
  }
}

bool topType(int gtype, int dim, ElementType &t)
{
  const std::map<int, ElementType> map = {{1, ElementType::Line2},
                                          {3, ElementType::Quad4},
                                          {4, ElementType::Tet4},
                                          {5, ElementType::Hex8}};
  auto it = map.find(gtype);
  if (it == map.end() || dimensionOf(it->second) != dim)
    return false;
  t = it->second;
  return true;
}

bool isFaceType(int gtype, int top)
{
  return (top == 1 && gtype == 15) || (top == 2 && gtype == 1) ||
         (top == 3 && (gtype == 2 || gtype == 3));
}
} // namespace

HostMesh readGmsh41(const std::string &path)
{
  Lines in;
  in.path = path;
  in.in.open(path);
  if (!in.in)
    throw std::runtime_error(path + ": cannot open gmsh mesh file");
  FileData fd;
  bool have_format = false;
  while (in.next())
  {
    if (in.text.empty())
      continue;
    if (in.text[0] != '$')
      in.fail("expected a section such as $Nodes, got '" + in.text + "'");
    const std::string name = in.text;
    if (name == "$MeshFormat")
    {
      in.need(name);
      auto t = in.tokens(3, "version file-type data-size");
      if (t[0] != "4.1")
        in.fail("gmsh format version " + t[0] + " is not supported; write 4.1 (-format msh41)");
      if (t[1] != "0")
        in.fail("binary gmsh files are not supported; write ASCII (no -bin)");
      in.need(name);
      if (in.text != "$EndMeshFormat")
        in.fail("expected $EndMeshFormat");
      have_format = true;
      continue;
    }
    if (!have_format)
      in.fail("the file must start with $MeshFormat");
    readSection(in, name, fd);
  }
  if (!have_format)
    in.fail("no $MeshFormat section: not a gmsh file");

  int top = -1;
  for (const Block &b : fd.blocks)
    if (b.count > 0)
      top = std::max(top, b.dim);
  if (top < 1)
    in.fail("no elements of dimension 1, 2 or 3 in the file");

  // Group the top-dimension blocks into parts: physical tag -> blocks (tag -1: unnamed).
  std::map<int, std::vector<const Block *>> groups;
  for (const Block &b : fd.blocks)
  {
    if (b.dim != top || b.count == 0)
      continue;
    ElementType t;
    if (!topType(b.type, top, t))
      in.failAt(b.line, "unsupported element type " + gmshTypeName(b.type) +
                            " in the top dimension " + std::to_string(top) +
                            " (use line2, quad4, hex8 or tet4)");
    const auto &g = groupsOf(fd, b);
    if (g.size() > 1)
      in.failAt(b.line, "elements of entity " + std::to_string(b.entity) + " belong to " +
                            std::to_string(g.size()) + " physical groups of dimension " +
                            std::to_string(top) + "; a part element must belong to one");
    groups[g.empty() ? -1 : g[0]].push_back(&b);
  }
  std::vector<int> order; // physical tags ascending, unnamed last
  for (const auto &g : groups)
    if (g.first >= 0)
      order.push_back(g.first);
  if (groups.count(-1))
    order.push_back(-1);

  HostMesh mesh;
  mesh.dim = top;
  std::vector<Tag> gmshTag;                           // our node -> gmsh tag
  std::unordered_map<Tag, std::vector<Index>> copies; // gmsh tag -> our nodes
  for (int phys : order)
  {
    const auto &blocks = groups[phys];
    HostPart part;
    part.name = phys < 0 ? "unnamed" : physName(fd, top, phys);
    topType(blocks[0]->type, top, part.type);
    std::vector<Tag> tags;
    for (const Block *b : blocks)
    {
      ElementType t;
      topType(b->type, top, t);
      if (t != part.type)
        in.failAt(b->line, "physical group '" + part.name + "' mixes " +
                               gmshTypeName(blocks[0]->type) + " (line " +
                               std::to_string(blocks[0]->line) + ") and " + gmshTypeName(b->type) +
                               "; a part holds one element type");
      for (size_t e = 0; e < b->nodes.size(); ++e)
      {
        if (int(b->nodes[e].size()) != nodesPerElement(t))
          in.failAt(b->lines[e], gmshTypeName(b->type) + " element needs " +
                                     std::to_string(nodesPerElement(t)) + " node tags");
        for (Tag n : b->nodes[e])
          if (!fd.coords.count(n))
            in.failAt(b->lines[e], "unknown node tag " + std::to_string(n));
        tags.insert(tags.end(), b->nodes[e].begin(), b->nodes[e].end());
      }
    }
    std::sort(tags.begin(), tags.end());
    tags.erase(std::unique(tags.begin(), tags.end()), tags.end());
    std::unordered_map<Tag, Index> local; // this part's copy of each gmsh node
    for (Tag n : tags)
    {
      local[n] = mesh.numNodes();
      copies[n].push_back(mesh.numNodes());
      gmshTag.push_back(n);
      mesh.coords.push_back(fd.coords[n]);
    }
    const int npe = nodesPerElement(part.type);
    for (const Block *b : blocks)
      for (const auto &el : b->nodes)
      {
        for (Tag n : el)
          part.connectivity.push_back(local[n]);
        orient(part.type, mesh.coords, &part.connectivity[part.connectivity.size() - npe]);
      }
    mesh.parts.push_back(std::move(part));
  }

  Real extent = 0;
  for (const auto &x : mesh.coords)
    extent = std::max({extent, std::abs(x[0]), std::abs(x[1]), std::abs(x[2])});
  for (Index i = 0; i < mesh.numNodes(); ++i)
    for (int k = top; k < 3; ++k)
      if (std::abs(mesh.coords[i][k]) > 1e-12 * extent)
        in.fail("node " + std::to_string(gmshTag[i]) + " of this " + std::to_string(top) +
                "D mesh has a non-zero " + "xyz"[k] +
                " coordinate (2D meshes lie in z = 0, 1D along x)");
  try
  {
    checkElements(mesh);
  }
  catch (const std::runtime_error &e)
  {
    throw std::runtime_error(path + ": " + e.what());
  }

  // External faces keyed by their sorted gmsh node tags, for the face sets.
  const std::vector<HostFace> external = extractExternalFaces(mesh);
  std::map<std::vector<Tag>, std::vector<size_t>> faceOf;
  for (size_t f = 0; f < external.size(); ++f)
  {
    std::vector<Tag> key;
    for (int i = 0; i < external[f].num_nodes; ++i)
      key.push_back(gmshTag[external[f].nodes[i]]);
    std::sort(key.begin(), key.end());
    faceOf[key].push_back(f);
  }
  for (const Block &b : fd.blocks)
  {
    if (b.dim >= top)
      continue;
    for (int phys : groupsOf(fd, b))
    {
      const std::string name = physName(fd, b.dim, phys);
      const bool faces = b.dim == top - 1;
      if (faces && !isFaceType(b.type, top))
        in.failAt(b.line, "physical group '" + name + "' of dimension " + std::to_string(b.dim) +
                              " has elements of unsupported " + gmshTypeName(b.type));
      auto &nodes = mesh.node_sets[name];
      std::vector<HostFace> *faceSet = faces ? &mesh.face_sets[name] : nullptr;
      for (size_t e = 0; e < b.nodes.size(); ++e)
      {
        for (Tag n : b.nodes[e])
        {
          auto it = copies.find(n);
          if (it == copies.end())
            in.failAt(b.lines[e], "node " + std::to_string(n) + " of physical group '" + name +
                                      "' belongs to no part");
          nodes.insert(nodes.end(), it->second.begin(), it->second.end());
        }
        if (!faces)
          continue;
        std::vector<Tag> key = b.nodes[e];
        std::sort(key.begin(), key.end());
        auto it = faceOf.find(key);
        if (it == faceOf.end())
          in.failAt(b.lines[e], "element of physical group '" + name + "' (dimension " +
                                    std::to_string(b.dim) +
                                    ") is not an external face of any part; "
                                    "mixed top dimensions or interior faces are not supported");
        for (size_t f : it->second)
          faceSet->push_back(external[f]);
      }
    }
  }
  for (auto &s : mesh.node_sets)
  {
    std::sort(s.second.begin(), s.second.end());
    s.second.erase(std::unique(s.second.begin(), s.second.end()), s.second.end());
  }
  return mesh;
}

} // namespace scpdyn
