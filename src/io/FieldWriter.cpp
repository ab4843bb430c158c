/// \file FieldWriter.cpp
/// \brief HDF5 (C API) + XDMF writer behind FieldWriter.hpp.
#include "io/FieldWriter.hpp"

#include "core/Types.hpp"
#include "io/Hdf5Util.hpp"
#include "io/TextOutput.hpp"

#include <hdf5.h>

#include <algorithm>
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

std::string fieldError(const std::string &what) { return "FieldWriter: " + what; }

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

namespace
{
/// The mesh checks of both constructors; returns the single cell type or -1 (mixed).
int validateMesh(const FieldMeshDesc &mesh)
{
  if (mesh.dim < 1 || mesh.dim > 3)
    throw std::invalid_argument(fieldError("dim must be 1, 2 or 3"));
  if (mesh.coords0.empty() || mesh.coords0.size() % 3 != 0)
    throw std::invalid_argument(fieldError("coords0 must hold n_nodes*3 > 0 values"));
  if (mesh.cell_types.empty())
    throw std::invalid_argument(fieldError("mesh has no cells"));
  const int num_nodes = int(mesh.coords0.size() / 3);

  std::size_t expected_conn = 0;
  int uniform = mesh.cell_types[0];
  for (int t : mesh.cell_types)
  {
    if (t < 0 || t > 3)
      throw std::invalid_argument(fieldError("unknown cell type " + std::to_string(t)));
    expected_conn += std::size_t(nodesPerElement(ElementType(t)));
    if (t != uniform)
      uniform = -1;
  }
  if (mesh.connectivity.size() != expected_conn)
    throw std::invalid_argument(
        fieldError("connectivity has " + std::to_string(mesh.connectivity.size()) +
                   " entries, cell types need " + std::to_string(expected_conn)));
  for (int n : mesh.connectivity)
    if (n < 0 || n >= num_nodes)
      throw std::invalid_argument(fieldError("connectivity references node " + std::to_string(n) +
                                             " outside [0, " + std::to_string(num_nodes) + ")"));

  return uniform;
}
} // namespace

FieldWriter::FieldWriter(const std::string &dir, const FieldMeshDesc &mesh,
                         const ContinueFrames &continued)
    : _h5_path(dir + "/" + kH5Name), _xmf_path(dir + "/" + kXmfName), _mesh(mesh)
{
  _uniform_type = validateMesh(mesh);
  _num_nodes = int(mesh.coords0.size() / 3);
  _num_cells = int(mesh.cell_types.size());
  _connectivity_length = mesh.connectivity.size();
  open(dir, continued);
}

FieldWriter::FieldWriter(const std::string &dir, const FieldMeshDesc &mesh,
                         const FieldDistribution &dist, const ContinueFrames &continued)
    : _h5_path(dir + "/" + kH5Name), _xmf_path(dir + "/" + kXmfName), _mesh(mesh),
      _distributed(true), _comm(dist.comm)
{
  MPI_Comm_rank(_comm, &_rank);
  // rank 0 holds the mesh: it checks it (the verdict goes to every rank) and sends the sizes
  std::string error;
  if (root())
    try
    {
      _uniform_type = validateMesh(mesh);
    }
    catch (const std::invalid_argument &e)
    {
      error = e.what();
    }
  long sizes[5] = {long(error.size()), long(mesh.coords0.size() / 3), long(mesh.cell_types.size()),
                   long(_uniform_type), long(mesh.connectivity.size())};
  MPI_Bcast(sizes, 5, MPI_LONG, 0, _comm);
  if (sizes[0] > 0)
  {
    error.resize(size_t(sizes[0]));
    MPI_Bcast(&error[0], int(sizes[0]), MPI_CHAR, 0, _comm);
    throw std::invalid_argument(error);
  }
  _num_nodes = int(sizes[1]), _num_cells = int(sizes[2]), _uniform_type = int(sizes[3]);
  _connectivity_length = size_t(sizes[4]);
  MPI_Bcast(&_mesh.dim, 1, MPI_INT, 0, _comm);
  // ascending rows, as runs: owned nodes only (each node is written by one rank)
  auto plan = [](const std::vector<long> &rows, RowPlan &p) {
    for (size_t i = 0; i < rows.size(); ++i)
      if (rows[i] >= 0)
        p.local.push_back(long(i));
    std::sort(p.local.begin(), p.local.end(),
              [&rows](long a, long b) { return rows[size_t(a)] < rows[size_t(b)]; });
    for (long i : p.local)
    {
      const auto r = static_cast<unsigned long long>(rows[size_t(i)]);
      if (!p.start.empty() && p.start.back() + p.length.back() == r)
        ++p.length.back();
      else
        p.start.push_back(r), p.length.push_back(1);
    }
  };
  plan(dist.node_rows, _node_plan);
  plan(dist.cell_rows, _cell_plan);
  _local_nodes = dist.node_rows.size();
  _local_cells = dist.cell_rows.size();
  open(dir, continued);
}

void FieldWriter::open(const std::string &dir, const ContinueFrames &continued)
{
  if (root())
    ensureDirectory(dir);
  if (_distributed)
    MPI_Barrier(_comm); // the directory exists before any rank opens the file
  const bool existing = continued.frames >= 0;
  if (existing)
  {
    // rank 0 reads the XDMF text; its verdict goes to every rank before any collective call
    std::string error;
    if (root())
      try
      {
        _grids = xdmfFrameGrids(_xmf_path, size_t(continued.frames));
      }
      catch (const std::runtime_error &e)
      {
        error = e.what();
      }
    long length = long(error.size());
    if (_distributed)
      MPI_Bcast(&length, 1, MPI_LONG, 0, _comm);
    error.resize(size_t(length));
    if (_distributed && length > 0)
      MPI_Bcast(&error[0], int(length), MPI_CHAR, 0, _comm);
    if (length > 0)
      throw std::runtime_error(error);
    _grids.resize(size_t(continued.frames));
  }
  openFile(_h5_path, _distributed ? &_comm : nullptr, _file, _dxpl, existing);
  try
  {
    if (existing)
    {
      // the mesh the file has is this run's (same deck): only its size is checked
      Handle coords(H5Dopen2(_file, "mesh/coords0", H5P_DEFAULT), H5Dclose);
      Handle space(coords < 0 ? -1 : H5Dget_space(coords), H5Sclose);
      if (space < 0 || H5Sget_simple_extent_npoints(space) != hssize_t(3) * _num_nodes)
        throw std::runtime_error("cannot continue '" + _h5_path + "': not this mesh's file");
      keepFrames(_file, continued.frames, continued.last_time, _h5_path);
    }
    else
      writeMesh();
    check(H5Fflush(_file, H5F_SCOPE_GLOBAL), "flush the mesh", _h5_path);
    if (root())
      writeXdmf();
  }
  catch (...)
  {
    // The destructor does not run for a throwing constructor: release the handles here.
    releaseFile(_file, _dxpl);
    throw;
  }
}

template <class T>
void FieldWriter::writeRows(std::int64_t loc, const std::string &name, const RowPlan *plan,
                            std::size_t rows, int comps, const T *data)
{
  std::vector<hsize_t> dims{hsize_t(rows)};
  if (comps > 1)
    dims.push_back(hsize_t(comps));
  if (!_distributed)
  {
    writeDataset(loc, name, dims, data, _dxpl, _h5_path);
    return;
  }
  if (!plan) // written whole by rank 0
  {
    writeDatasetRows(loc, name, dims, RowRuns::all(root() ? hsize_t(rows) : 0), data, _dxpl,
                     _h5_path);
    return;
  }
  RowRuns runs;
  runs.start.assign(plan->start.begin(), plan->start.end());
  runs.length.assign(plan->length.begin(), plan->length.end());
  runs.rows = hsize_t(plan->local.size());
  std::vector<T> packed(plan->local.size() * size_t(comps));
  for (size_t k = 0; k < plan->local.size(); ++k)
    for (int c = 0; c < comps; ++c)
      packed[k * size_t(comps) + size_t(c)] =
          data[size_t(plan->local[k]) * size_t(comps) + size_t(c)];
  writeDatasetRows(loc, name, dims, runs, packed.data(), _dxpl, _h5_path);
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

void FieldWriter::close() { closeFile(_file, _dxpl, _h5_path); }

void FieldWriter::writeMesh()
{
  // a decomposed run: rank 0 holds the whole mesh and writes it; the others join the
  // collective dataset creation and transfers with nothing selected
  Handle g(createGroup(_file, "mesh", _h5_path), H5Gclose);
  const size_t n = size_t(_num_nodes), ne = size_t(_num_cells);
  writeRows(g, "coords0", nullptr, n, 3, _mesh.coords0.data());
  writeRows(g, "cell_types", nullptr, ne, 1, _mesh.cell_types.data());
  writeRows(g, "connectivity", nullptr, _connectivity_length, 1, _mesh.connectivity.data());

  // XDMF wants (ne, npe) for one type, or type code [+ node count for Polyline] + nodes.
  std::vector<int> topo;
  if (_uniform_type >= 0)
    topo = _mesh.connectivity;
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
  }
  long length = long(topo.size());
  if (_distributed)
    MPI_Bcast(&length, 1, MPI_LONG, 0, _comm);
  _topology_length = size_t(length);
  if (_uniform_type >= 0)
    writeRows(g, "topology", nullptr, ne, nodesPerElement(ElementType(_uniform_type)), topo.data());
  else
    writeRows(g, "topology", nullptr, _topology_length, 1, topo.data());
  writeScalarAttribute(g, "dim", long(_mesh.dim), _h5_path);
  Handle frames(createGroup(_file, "frames", _h5_path), H5Gclose);
}

void FieldWriter::write(const FieldFrame &frame)
{
  if (_file < 0)
    throw std::logic_error(fieldError("write() after close() on '" + _h5_path + "'"));
  // sizes of this process's arrays: the whole mesh, or a decomposed run's local part
  const std::size_t n = _distributed ? _local_nodes : std::size_t(_num_nodes);
  const std::size_t ne = _distributed ? _local_cells : std::size_t(_num_cells);
  const RowPlan *nodes = _distributed ? &_node_plan : nullptr;
  const RowPlan *cells = _distributed ? &_cell_plan : nullptr;
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
  if (!has_displacement && _distributed)
    throw std::invalid_argument(fieldError("a decomposed run's frame needs a 'displacement'"));
  if (!has_displacement)
  {
    checkName("displacement", node_names, "node");
    info.attributes.push_back({"displacement", false, 3});
  }

  const std::string name = std::to_string(_grids.size());
  Handle frames(openGroup(_file, "frames", _h5_path), H5Gclose);
  Handle g(createGroup(frames, name, _h5_path), H5Gclose);
  writeScalarAttribute(g, "time", frame.time, _h5_path);
  writeScalarAttribute(g, "cycle", frame.cycle, _h5_path);
  writeRows(g, "coords", nodes, size_t(_num_nodes), 3, frame.coords.data());

  Handle pd(createGroup(g, "point_data", _h5_path), H5Gclose);
  for (const auto &f : frame.node_vectors)
    writeRows(pd, f.first, nodes, size_t(_num_nodes), 3, f.second.data());
  for (const auto &f : frame.node_scalars)
    writeRows(pd, f.first, nodes, size_t(_num_nodes), 1, f.second.data());
  if (!has_displacement)
  {
    std::vector<double> u(n * 3);
    for (std::size_t i = 0; i < n * 3; ++i)
      u[i] = frame.coords[i] - _mesh.coords0[i];
    writeRows(pd, "displacement", nodes, size_t(_num_nodes), 3, u.data());
  }

  Handle cd(createGroup(g, "cell_data", _h5_path), H5Gclose);
  for (const auto &f : frame.cell_scalars)
    writeRows(cd, f.first, cells, size_t(_num_cells), 1, f.second.data());
  std::vector<double> t6(ne * 6);
  for (const auto &f : frame.cell_tensors6)
  {
    // Voigt (xx yy zz xy yz zx) -> XDMF Tensor6 (xx xy xz yy yz zz); xz = zx by symmetry.
    static const int from_voigt[6] = {0, 3, 5, 1, 4, 2};
    for (std::size_t e = 0; e < ne; ++e)
      for (int c = 0; c < 6; ++c)
        t6[e * 6 + std::size_t(c)] = f.second[e * 6 + std::size_t(from_voigt[c])];
    writeRows(cd, f.first, cells, size_t(_num_cells), 6, t6.data());
  }
  // Data on disk before the sidecar points at it: a crash never leaves dangling references.
  check(H5Fflush(_file, H5F_SCOPE_GLOBAL), "flush frame " + name, _h5_path);
  _grids.push_back(root() ? frameXml(_grids.size(), info) : std::string());
  if (root())
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

std::string FieldWriter::frameXml(std::size_t k, const FrameInfo &f) const
{
  std::ostringstream x;
  const std::string n = std::to_string(_num_nodes), ne = std::to_string(_num_cells);
  const std::string h5 = std::string(kH5Name) + ":/frames/" + std::to_string(k);
  char time[32];
  std::snprintf(time, sizeof time, "%.17g", f.time);
  x << "      <Grid Name=\"frame_" << k << "\" GridType=\"Uniform\">\n"
    << "        <Time Value=\"" << time << "\"/>\n"
    << "        " << topologyXml() << "        <Geometry GeometryType=\"XYZ\">\n"
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
  x << kXdmfGridEnd;
  return x.str();
}

void FieldWriter::writeXdmf() const
{
  // Write-then-rename: readers and post-crash inspection only ever see a complete file.
  replaceFile(_xmf_path, xdmfCollection("fields", _grids));
}

} // namespace scpdyn
