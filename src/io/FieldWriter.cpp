/// \file FieldWriter.cpp
/// \brief HDF5 (C API) + XDMF writer behind FieldWriter.hpp.
#include "io/FieldWriter.hpp"

#include "core/Types.hpp"
#include "io/Hdf5Util.hpp"
#include "io/TextOutput.hpp"

#include <hdf5.h>

#include <cstdio>
#include <set>
#include <sstream>
#include <stdexcept>
#include <type_traits>

namespace scpdyn
{
namespace
{
using namespace h5detail;

static_assert(sizeof(hid_t) == sizeof(std::int64_t), "FieldWriter stores hid_t as int64");

constexpr const char *kH5Name = "fields.h5";
constexpr const char *kXmfName = "fields.xmf";

/// XDMF mixed-topology codes (XdmfTopologyType.cpp): Polyline 0x2, Quad 0x5, Tet 0x6, Hex 0x9.
int xdmfMixedCode(int type)
{
  static const int codes[4] = {0x2, 0x5, 0x9, 0x6};
  return codes[type];
}

const char *xdmfTopologyName(int type)
{
  static const char *names[4] = {"Polyline", "Quadrilateral", "Hexahedron", "Tetrahedron"};
  return names[type];
}


std::string fieldError(const std::string &what)
{
  return "FieldWriter: " + what;
}

void checkName(const std::string &name, std::set<std::string> &seen, const char *where)
{
  // '/' would nest HDF5 groups and ':' breaks the XDMF "file:dataset" reference.
  if (name.empty() || name.find_first_of("/:") != std::string::npos || name == ".")
    throw std::invalid_argument(fieldError(std::string("invalid ") + where + " field name '" +
                                           name + "' (empty, '.' or containing '/' or ':')"));
  if (!seen.insert(name).second)
    throw std::invalid_argument(
        fieldError(std::string("duplicate ") + where + " field '" + name + "'"));
}

void checkSize(const NamedField &f, std::size_t expected, const char *kind)
{
  if (f.second.size() != expected)
    throw std::invalid_argument(fieldError(std::string(kind) + " '" + f.first + "' has " +
                                           std::to_string(f.second.size()) + " values, expected " +
                                           std::to_string(expected)));
}

} // namespace

FieldWriter::FieldWriter(const std::string &dir, const FieldMeshDesc &mesh)
    : _h5_path(dir + "/" + kH5Name), _xmf_path(dir + "/" + kXmfName), _mesh(mesh)
{
  if (mesh.dim < 1 || mesh.dim > 3)
    throw std::invalid_argument(fieldError("dim must be 1, 2 or 3"));
  if (mesh.coords0.empty() || mesh.coords0.size() % 3 != 0)
    throw std::invalid_argument(fieldError("coords0 must hold n_nodes*3 > 0 values"));
  if (mesh.cell_types.empty())
    throw std::invalid_argument(fieldError("mesh has no cells"));
  _num_nodes = int(mesh.coords0.size() / 3);
  _num_cells = int(mesh.cell_types.size());

  std::size_t expected_conn = 0;
  _uniform_type = mesh.cell_types[0];
  for (int t : mesh.cell_types)
  {
    if (t < 0 || t > 3)
      throw std::invalid_argument(fieldError("unknown cell type " + std::to_string(t)));
    expected_conn += std::size_t(nodesPerElement(ElementType(t)));
    if (t != _uniform_type)
      _uniform_type = -1;
  }
  if (mesh.connectivity.size() != expected_conn)
    throw std::invalid_argument(
        fieldError("connectivity has " + std::to_string(mesh.connectivity.size()) +
                   " entries, cell types need " + std::to_string(expected_conn)));
  for (int n : mesh.connectivity)
    if (n < 0 || n >= _num_nodes)
      throw std::invalid_argument(fieldError("connectivity references node " + std::to_string(n) +
                                             " outside [0, " + std::to_string(_num_nodes) + ")"));

  ensureDirectory(dir);
  {
    Handle fapl(makeFileAccessList(), H5Pclose);
    _file = createFieldFile(_h5_path, fapl);
  }
  _dxpl = H5Pcreate(H5P_DATASET_XFER);
  try
  {
    check(_dxpl < 0 ? -1 : 0, "create a transfer property list", _h5_path);
    writeMesh();
    check(H5Fflush(_file, H5F_SCOPE_GLOBAL), "flush the mesh", _h5_path);
    writeXdmf();
  }
  catch (...)
  {
    // The destructor does not run for a throwing constructor: release the handles here.
    H5Fclose(_file);
    if (_dxpl >= 0)
      H5Pclose(_dxpl);
    _file = _dxpl = -1;
    throw;
  }
}

FieldWriter::~FieldWriter()
{
  try
  {
    close();
  }
  catch (...)
  {
    // A destructor must not throw; close() explicitly to see the error.
  }
}

void FieldWriter::close()
{
  if (_file < 0)
    return;
  const herr_t flushed = H5Fflush(_file, H5F_SCOPE_GLOBAL);
  const herr_t closed = H5Fclose(_file);
  H5Pclose(_dxpl);
  _file = _dxpl = -1;
  check(flushed < 0 || closed < 0 ? -1 : 0, "close the file", _h5_path);
}

void FieldWriter::writeMesh()
{
  Handle g(createGroup(_file, "mesh", _h5_path), H5Gclose);
  const hsize_t n = hsize_t(_num_nodes), ne = hsize_t(_num_cells);
  writeDataset(g, "coords0", {n, 3}, _mesh.coords0.data(), _dxpl, _h5_path);
  writeDataset(g, "cell_types", {ne}, _mesh.cell_types.data(), _dxpl, _h5_path);
  writeDataset(g, "connectivity", {hsize_t(_mesh.connectivity.size())}, _mesh.connectivity.data(),
               _dxpl, _h5_path);

  // XDMF wants (ne, npe) for one type, or type code [+ node count for Polyline] + nodes.
  std::vector<int> topo;
  std::vector<hsize_t> topo_dims;
  if (_uniform_type >= 0)
  {
    topo = _mesh.connectivity;
    topo_dims = {ne, hsize_t(nodesPerElement(ElementType(_uniform_type)))};
  }
  else
  {
    std::size_t offset = 0;
    for (int t : _mesh.cell_types)
    {
      const int npe = nodesPerElement(ElementType(t));
      topo.push_back(xdmfMixedCode(t));
      if (t == int(ElementType::Line2))
        topo.push_back(npe);
      topo.insert(topo.end(), _mesh.connectivity.begin() + long(offset),
                  _mesh.connectivity.begin() + long(offset + npe));
      offset += std::size_t(npe);
    }
    topo_dims = {hsize_t(topo.size())};
  }
  _topology_length = topo.size();
  writeDataset(g, "topology", topo_dims, topo.data(), _dxpl, _h5_path);
  writeScalarAttribute(g, "dim", long(_mesh.dim), _h5_path);
  Handle frames(createGroup(_file, "frames", _h5_path), H5Gclose);
}

void FieldWriter::write(const FieldFrame &frame)
{
  if (_file < 0)
    throw std::logic_error(fieldError("write() after close() on '" + _h5_path + "'"));
  const std::size_t n = std::size_t(_num_nodes), ne = std::size_t(_num_cells);
  if (frame.coords.size() != n * 3)
    throw std::invalid_argument(fieldError("frame coords have " +
                                           std::to_string(frame.coords.size()) +
                                           " values, expected " + std::to_string(n * 3)));

  // Validate everything before touching the file, so a bad frame leaves no half group.
  FrameInfo info{frame.time, frame.cycle, {}};
  std::set<std::string> node_names, cell_names;
  bool has_displacement = false;
  for (const auto &f : frame.node_vectors)
  {
    checkName(f.first, node_names, "node");
    checkSize(f, n * 3, "node vector");
    info.attributes.push_back({f.first, false, 3});
    has_displacement = has_displacement || f.first == "displacement";
  }
  for (const auto &f : frame.node_scalars)
  {
    checkName(f.first, node_names, "node");
    checkSize(f, n, "node scalar");
    info.attributes.push_back({f.first, false, 1});
  }
  for (const auto &f : frame.cell_scalars)
  {
    checkName(f.first, cell_names, "cell");
    checkSize(f, ne, "cell scalar");
    info.attributes.push_back({f.first, true, 1});
  }
  for (const auto &f : frame.cell_tensors6)
  {
    checkName(f.first, cell_names, "cell");
    checkSize(f, ne * 6, "cell tensor");
    info.attributes.push_back({f.first, true, 6});
  }
  if (!has_displacement)
  {
    checkName("displacement", node_names, "node");
    info.attributes.push_back({"displacement", false, 3});
  }

  const std::string name = std::to_string(_frames.size());
  Handle frames(openGroup(_file, "frames", _h5_path), H5Gclose);
  Handle g(createGroup(frames, name, _h5_path), H5Gclose);
  writeScalarAttribute(g, "time", frame.time, _h5_path);
  writeScalarAttribute(g, "cycle", frame.cycle, _h5_path);
  writeDataset(g, "coords", {n, 3}, frame.coords.data(), _dxpl, _h5_path);

  Handle pd(createGroup(g, "point_data", _h5_path), H5Gclose);
  for (const auto &f : frame.node_vectors)
    writeDataset(pd, f.first, {n, 3}, f.second.data(), _dxpl, _h5_path);
  for (const auto &f : frame.node_scalars)
    writeDataset(pd, f.first, {n}, f.second.data(), _dxpl, _h5_path);
  if (!has_displacement)
  {
    std::vector<double> u(n * 3);
    for (std::size_t i = 0; i < n * 3; ++i)
      u[i] = frame.coords[i] - _mesh.coords0[i];
    writeDataset(pd, "displacement", {n, 3}, u.data(), _dxpl, _h5_path);
  }

  Handle cd(createGroup(g, "cell_data", _h5_path), H5Gclose);
  for (const auto &f : frame.cell_scalars)
    writeDataset(cd, f.first, {ne}, f.second.data(), _dxpl, _h5_path);
  std::vector<double> t6(ne * 6);
  for (const auto &f : frame.cell_tensors6)
  {
    // Voigt (xx yy zz xy yz zx) -> XDMF Tensor6 (xx xy xz yy yz zz); xz = zx by symmetry.
    static const int from_voigt[6] = {0, 3, 5, 1, 4, 2};
    for (std::size_t e = 0; e < ne; ++e)
      for (int c = 0; c < 6; ++c)
        t6[e * 6 + std::size_t(c)] = f.second[e * 6 + std::size_t(from_voigt[c])];
    writeDataset(cd, f.first, {ne, 6}, t6.data(), _dxpl, _h5_path);
  }
  // Data on disk before the sidecar points at it: a crash never leaves dangling references.
  check(H5Fflush(_file, H5F_SCOPE_GLOBAL), "flush frame " + name, _h5_path);
  _frames.push_back(std::move(info));
  writeXdmf();
}

std::string FieldWriter::topologyXml() const
{
  std::ostringstream s;
  const std::string ne = std::to_string(_num_cells);
  if (_uniform_type >= 0)
  {
    const int npe = nodesPerElement(ElementType(_uniform_type));
    s << "<Topology TopologyType=\"" << xdmfTopologyName(_uniform_type) << "\" NumberOfElements=\""
      << ne << "\"";
    if (_uniform_type == int(ElementType::Line2))
      s << " NodesPerElement=\"2\"";
    s << ">\n          <DataItem Dimensions=\"" << ne << " " << npe;
  }
  else
  {
    s << "<Topology TopologyType=\"Mixed\" NumberOfElements=\"" << ne << "\">\n"
      << "          <DataItem Dimensions=\"" << _topology_length;
  }
  s << "\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">" << kH5Name
    << ":/mesh/topology</DataItem>\n        </Topology>\n";
  return s.str();
}

void FieldWriter::writeXdmf() const
{
  // Version 3.0 for meshio's reader; the XDMF2-style keys (TopologyType, NumberType, ...)
  // are read by both ParaView readers (XDMF and XDMF3).
  std::ostringstream x;
  x << "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
    << "<Xdmf Version=\"3.0\">\n  <Domain>\n"
    << "    <Grid Name=\"fields\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  const std::string topology = topologyXml();
  const std::string n = std::to_string(_num_nodes), ne = std::to_string(_num_cells);
  for (std::size_t k = 0; k < _frames.size(); ++k)
  {
    const FrameInfo &f = _frames[k];
    const std::string h5 = std::string(kH5Name) + ":/frames/" + std::to_string(k);
    char time[32];
    std::snprintf(time, sizeof time, "%.17g", f.time);
    x << "      <Grid Name=\"frame_" << k << "\" GridType=\"Uniform\">\n"
      << "        <Time Value=\"" << time << "\"/>\n"
      << "        " << topology << "        <Geometry GeometryType=\"XYZ\">\n"
      << "          <DataItem Dimensions=\"" << n
      << " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << h5
      << "/coords</DataItem>\n        </Geometry>\n";
    for (const AttributeInfo &a : f.attributes)
    {
      const char *type = a.components == 1 ? "Scalar" : a.components == 3 ? "Vector" : "Tensor6";
      const std::string count = a.on_cells ? ne : n;
      x << "        <Attribute Name=\"" << xmlEscape(a.name) << "\" AttributeType=\"" << type
        << "\" Center=\"" << (a.on_cells ? "Cell" : "Node") << "\">\n"
        << "          <DataItem Dimensions=\"" << count;
      if (a.components > 1)
        x << " " << a.components;
      x << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << h5
        << (a.on_cells ? "/cell_data/" : "/point_data/") << xmlEscape(a.name)
        << "</DataItem>\n        </Attribute>\n";
    }
    x << "      </Grid>\n";
  }
  x << "    </Grid>\n  </Domain>\n</Xdmf>\n";

  // Write-then-rename: readers and post-crash inspection only ever see a complete file.
  const std::string tmp = _xmf_path + ".tmp";
  std::FILE *fp = std::fopen(tmp.c_str(), "w");
  if (!fp)
    throw std::runtime_error("FieldWriter: cannot create XDMF file '" + tmp + "'");
  const std::string text = x.str();
  const bool ok = std::fwrite(text.data(), 1, text.size(), fp) == text.size();
  if (std::fclose(fp) != 0 || !ok)
    throw std::runtime_error("FieldWriter: cannot write XDMF file '" + tmp + "'");
  if (std::rename(tmp.c_str(), _xmf_path.c_str()) != 0)
    throw std::runtime_error("FieldWriter: cannot rename '" + tmp + "' to '" + _xmf_path + "'");
}

} // namespace scpdyn
