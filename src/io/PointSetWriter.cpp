/// \file PointSetWriter.cpp
/// \brief HDF5 + XDMF point-set writer (FieldWriter.hpp): the contact points, one Polyvertex
/// grid per output time.
#include "io/FieldWriter.hpp"
#include "io/Hdf5Util.hpp"
#include "io/TextOutput.hpp"

#include <cstdio>
#include <set>
#include <sstream>
#include <stdexcept>

namespace scpdyn
{
using namespace h5detail;

PointSetWriter::PointSetWriter(const std::string &dir, const std::string &name, double empty_value,
                               const ContinueFrames &continued)
    : _h5_name(name + ".h5"), _h5_path(dir + "/" + name + ".h5"),
      _xmf_path(dir + "/" + name + ".xmf"), _empty_value(empty_value)
{
  ensureDirectory(dir);
  const bool existing = continued.frames >= 0;
  openFile(_h5_path, nullptr, _file, _dxpl, existing);
  try
  {
    if (existing)
    {
      keepFrames(_file, continued.frames, continued.last_time, _h5_path);
      _grids = xdmfFrameGrids(_xmf_path, size_t(continued.frames));
    }
    else
    {
      Handle frames(createGroup(_file, "frames", _h5_path), H5Gclose);
    }
    check(H5Fflush(_file, H5F_SCOPE_GLOBAL), "flush", _h5_path);
    writeXdmf();
  }
  catch (...)
  {
    releaseFile(_file, _dxpl);
    throw;
  }
}

PointSetWriter::~PointSetWriter()
{
  try
  {
    close();
  }
  catch (...)
  {
  }
}

void PointSetWriter::close() { closeFile(_file, _dxpl, _h5_path); }

void PointSetWriter::write(const PointFrame &frame)
{
  if (_file < 0)
    throw std::logic_error("PointSetWriter: write() after close() on '" + _h5_path + "'");
  if (frame.points.size() % 3 != 0)
    throw std::invalid_argument("PointSetWriter: points must hold n*3 values");
  const std::size_t n = frame.points.size() / 3;
  FrameInfo info{frame.time, frame.cycle, n == 0 ? 1 : n, {}};
  std::set<std::string> seen;
  for (const auto &f : frame.scalars)
  {
    if (f.first.empty() || f.first.find_first_of("/:") != std::string::npos ||
        !seen.insert(f.first).second)
      throw std::invalid_argument("PointSetWriter: invalid or duplicate field name '" + f.first +
                                  "'");
    if (f.second.size() != n)
      throw std::invalid_argument("PointSetWriter: field '" + f.first + "' has " +
                                  std::to_string(f.second.size()) + " values, expected " +
                                  std::to_string(n));
    info.names.push_back(f.first);
  }
  const std::string name = std::to_string(_grids.size());
  Handle frames(openGroup(_file, "frames", _h5_path), H5Gclose);
  Handle g(createGroup(frames, name, _h5_path), H5Gclose);
  writeScalarAttribute(g, "time", frame.time, _h5_path);
  writeScalarAttribute(g, "cycle", frame.cycle, _h5_path);
  const hsize_t count = hsize_t(info.count);
  const std::vector<double> origin(3, 0.0), empty(1, _empty_value);
  writeDataset(g, "points", {count, 3}, n == 0 ? origin.data() : frame.points.data(), _dxpl,
               _h5_path);
  // one vertex cell per point: readers that build cells from the topology's data (meshio,
  // ParaView's XDMF3 reader) find none without it
  std::vector<int> vertices(info.count);
  for (std::size_t p = 0; p < info.count; ++p)
    vertices[p] = int(p);
  writeDataset(g, "vertices", {count, 1}, vertices.data(), _dxpl, _h5_path);
  Handle pd(createGroup(g, "point_data", _h5_path), H5Gclose);
  for (const auto &f : frame.scalars)
    writeDataset(pd, f.first, {count}, n == 0 ? empty.data() : f.second.data(), _dxpl, _h5_path);
  check(H5Fflush(_file, H5F_SCOPE_GLOBAL), "flush frame " + name, _h5_path);
  _grids.push_back(frameXml(_grids.size(), info));
  writeXdmf();
}

std::string PointSetWriter::frameXml(std::size_t k, const FrameInfo &f) const
{
  std::ostringstream x;
  const std::string h5 = _h5_name + ":/frames/" + std::to_string(k);
  const std::string n = std::to_string(f.count);
  char time[32];
  std::snprintf(time, sizeof time, "%.17g", f.time);
  x << "      <Grid Name=\"frame_" << k << "\" GridType=\"Uniform\">\n"
    << "        <Time Value=\"" << time << "\"/>\n"
    << "        <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << n
    << "\" NodesPerElement=\"1\">\n"
    << "          <DataItem Dimensions=\"" << n
    << " 1\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">" << h5
    << "/vertices</DataItem>\n        </Topology>\n"
    << "        <Geometry GeometryType=\"XYZ\">\n"
    << "          <DataItem Dimensions=\"" << n
    << " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << h5
    << "/points</DataItem>\n        </Geometry>\n";
  for (const std::string &a : f.names)
    x << "        <Attribute Name=\"" << xmlEscape(a)
      << "\" AttributeType=\"Scalar\" Center=\"Node\">\n"
      << "          <DataItem Dimensions=\"" << n
      << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << h5 << "/point_data/"
      << xmlEscape(a) << "</DataItem>\n        </Attribute>\n";
  x << kXdmfGridEnd;
  return x.str();
}

void PointSetWriter::writeXdmf() const { replaceFile(_xmf_path, xdmfCollection("points", _grids)); }

} // namespace scpdyn
