// FieldWriter: HDF5 contents read back with the C API, XDMF structure and references,
// crash safety (a killed writer leaves a readable pair), and meshio's time-series reader.
#include "TestUtil.hpp"
#include "io/FieldWriter.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

namespace
{
using scpdyn::FieldFrame;
using scpdyn::FieldMeshDesc;
using scpdyn::FieldWriter;

std::string workDir(const std::string &name)
{
  return std::string(SCPDYN_TEST_WORKDIR) + "/io_field_" + name;
}

using scpdyn::test::readText;

/// pvbatch is there, or the test is skipped; CI (CI=true) installs it (.ci/run), so there a
/// missing pvbatch fails the test rather than skipping the only check of ParaView's readers
bool havePvbatch(std::string *why)
{
  if (std::system("command -v pvbatch > /dev/null 2>&1") == 0)
    return true;
  const char *ci = std::getenv("CI");
  *why = ci && std::string(ci) == "true"
             ? "pvbatch not installed, and CI=true: .ci/run installs paraview python3-paraview"
             : "";
  return false;
}

/// Dataset read back as doubles (HDF5 converts int datasets) plus its shape.
std::vector<double> readDataset(hid_t file, const std::string &name, std::vector<hsize_t> *dims)
{
  const hid_t d = H5Dopen2(file, name.c_str(), H5P_DEFAULT);
  EXPECT_GE(d, 0) << name;
  if (d < 0)
    return {};
  const hid_t s = H5Dget_space(d);
  std::vector<hsize_t> shape(std::size_t(H5Sget_simple_extent_ndims(s)));
  H5Sget_simple_extent_dims(s, shape.data(), nullptr);
  hsize_t count = 1;
  for (hsize_t n : shape)
    count *= n;
  std::vector<double> v(count);
  EXPECT_GE(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), 0);
  H5Sclose(s);
  H5Dclose(d);
  if (dims)
    *dims = shape;
  return v;
}

double readAttribute(hid_t file, const std::string &obj, const char *name)
{
  double v = -1.0;
  const hid_t a = H5Aopen_by_name(file, obj.c_str(), name, H5P_DEFAULT, H5P_DEFAULT);
  EXPECT_GE(a, 0) << obj << "@" << name;
  H5Aread(a, H5T_NATIVE_DOUBLE, &v);
  H5Aclose(a);
  return v;
}

template <class T>
std::vector<double> asDouble(const std::vector<T> &v)
{
  return std::vector<double>(v.begin(), v.end());
}

/// Unit hex (nodes 0-7, VTK order) with a tet on its top face (nodes 4 5 6 + apex 8).
FieldMeshDesc hexTetMesh()
{
  FieldMeshDesc m;
  m.dim = 3;
  m.coords0 = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1, 0.5, 0.5, 2};
  m.cell_types = {2, 3};
  m.connectivity = {0, 1, 2, 3, 4, 5, 6, 7, 4, 5, 6, 8};
  return m;
}

/// 2 x 1 plane quads, z = 0.
FieldMeshDesc quadMesh()
{
  FieldMeshDesc m;
  m.dim = 2;
  m.coords0 = {0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 1, 0, 1, 1, 0, 2, 1, 0};
  m.cell_types = {1, 1};
  m.connectivity = {0, 1, 4, 3, 1, 2, 5, 4};
  return m;
}

/// Frame k: values are distinct per node/cell/component/frame, so a swap shows.
FieldFrame makeFrame(const FieldMeshDesc &m, int k, bool with_displacement)
{
  const std::size_t n = m.coords0.size() / 3, ne = m.cell_types.size();
  FieldFrame f;
  f.time = 1e-4 * k + 1.0 / 3.0;
  f.cycle = 100L * k + 7;
  f.coords = m.coords0;
  std::vector<double> vel(n * 3), u(n * 3), temp(n), p(ne), part(ne), stress(ne * 6);
  for (std::size_t i = 0; i < n * 3; ++i)
  {
    f.coords[i] += 0.01 * k * double(i % 5) + 1e-13 * double(i);
    vel[i] = 10.0 * k + 0.1 * double(i);
    u[i] = -0.5 * double(k * int(i)); // deliberately not x - x0
  }
  for (std::size_t i = 0; i < n; ++i)
    temp[i] = 300.0 + k + 0.25 * double(i);
  for (std::size_t e = 0; e < ne; ++e)
  {
    p[e] = -1e6 * (k + 1) + double(e);
    part[e] = double(e);
    for (int c = 0; c < 6; ++c)
      stress[e * 6 + std::size_t(c)] = 1000.0 * k + 10.0 * double(e) + double(c + 1);
  }
  f.node_vectors = {{"velocity", vel}};
  if (with_displacement)
    f.node_vectors.push_back({"displacement", u});
  f.node_scalars = {{"temperature", temp}};
  f.cell_scalars = {{"pressure", p}, {"part", part}};
  f.cell_tensors6 = {{"stress", stress}};
  return f;
}

/// Checks everything in fields.h5 against the inputs, bit for bit.
void checkH5(const std::string &dir, const FieldMeshDesc &m, const std::vector<FieldFrame> &frames,
             const std::vector<double> &expected_topology, const std::vector<hsize_t> &topo_dims)
{
  const hid_t file = H5Fopen((dir + "/fields.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  const hsize_t n = m.coords0.size() / 3, ne = m.cell_types.size();
  std::vector<hsize_t> dims;
  EXPECT_EQ(readDataset(file, "/mesh/coords0", &dims), m.coords0);
  EXPECT_EQ(dims, (std::vector<hsize_t>{n, 3}));
  EXPECT_EQ(readDataset(file, "/mesh/cell_types", &dims), asDouble(m.cell_types));
  EXPECT_EQ(readDataset(file, "/mesh/connectivity", &dims), asDouble(m.connectivity));
  EXPECT_EQ(readDataset(file, "/mesh/topology", &dims), expected_topology);
  EXPECT_EQ(dims, topo_dims);
  EXPECT_EQ(readAttribute(file, "/mesh", "dim"), double(m.dim));

  H5G_info_t info;
  H5Gget_info_by_name(file, "/frames", &info, H5P_DEFAULT);
  EXPECT_EQ(info.nlinks, frames.size());
  for (std::size_t k = 0; k < frames.size(); ++k)
  {
    const FieldFrame &f = frames[k];
    const std::string g = "/frames/" + std::to_string(k);
    EXPECT_EQ(readAttribute(file, g, "time"), f.time);
    EXPECT_EQ(readAttribute(file, g, "cycle"), double(f.cycle));
    EXPECT_EQ(readDataset(file, g + "/coords", &dims), f.coords);
    EXPECT_EQ(dims, (std::vector<hsize_t>{n, 3}));
    bool has_u = false;
    for (const auto &v : f.node_vectors)
    {
      EXPECT_EQ(readDataset(file, g + "/point_data/" + v.first, &dims), v.second) << v.first;
      EXPECT_EQ(dims, (std::vector<hsize_t>{n, 3}));
      has_u = has_u || v.first == "displacement";
    }
    if (!has_u) // derived by the writer: x - x0, the same double subtraction
    {
      std::vector<double> u(f.coords.size());
      for (std::size_t i = 0; i < u.size(); ++i)
        u[i] = f.coords[i] - m.coords0[i];
      EXPECT_EQ(readDataset(file, g + "/point_data/displacement", &dims), u);
    }
    for (const auto &s : f.node_scalars)
      EXPECT_EQ(readDataset(file, g + "/point_data/" + s.first, &dims), s.second) << s.first;
    for (const auto &s : f.cell_scalars)
    {
      EXPECT_EQ(readDataset(file, g + "/cell_data/" + s.first, &dims), s.second) << s.first;
      EXPECT_EQ(dims, (std::vector<hsize_t>{ne}));
    }
    for (const auto &t : f.cell_tensors6)
    {
      // Voigt xx yy zz xy yz zx (indices 0..5) -> Tensor6 xx xy xz yy yz zz = 0 3 5 1 4 2
      std::vector<double> expected;
      for (std::size_t e = 0; e < ne; ++e)
        for (int c : {0, 3, 5, 1, 4, 2})
          expected.push_back(t.second[e * 6 + std::size_t(c)]);
      EXPECT_EQ(readDataset(file, g + "/cell_data/" + t.first, &dims), expected);
      EXPECT_EQ(dims, (std::vector<hsize_t>{ne, 6}));
    }
  }
  H5Fclose(file);
}

struct XmlCheck
{
  bool well_formed = true;
  std::string error;
  std::map<std::string, int> tag_count;
  int uniform_grids = 0;
  std::vector<std::pair<std::string, std::string>> data_items; ///< (Dimensions, text)
  std::vector<std::string> times;
};

std::string attributeOf(const std::string &tag, const std::string &key)
{
  const std::size_t p = tag.find(" " + key + "=\"");
  if (p == std::string::npos)
    return {};
  const std::size_t b = p + key.size() + 3;
  return tag.substr(b, tag.find('"', b) - b);
}

/// Minimal XML scan: every opened tag closed in order; collects what the test needs.
XmlCheck scanXml(const std::string &xml)
{
  XmlCheck r;
  std::vector<std::string> stack;
  std::size_t pos = 0;
  while ((pos = xml.find('<', pos)) != std::string::npos)
  {
    const std::size_t end = xml.find('>', pos);
    if (end == std::string::npos)
      return r.well_formed = false, r.error = "unterminated tag", r;
    const std::string tag = xml.substr(pos, end - pos + 1);
    const std::size_t text_begin = end + 1;
    pos = end + 1;
    if (tag[1] == '?' || tag[1] == '!')
      continue;
    if (tag[1] == '/')
    {
      const std::string name = tag.substr(2, tag.size() - 3);
      if (stack.empty() || stack.back() != name)
        return r.well_formed = false, r.error = "unbalanced </" + name + ">", r;
      stack.pop_back();
      continue;
    }
    const std::string name = tag.substr(1, tag.find_first_of(" />", 1) - 1);
    ++r.tag_count[name];
    if (name == "Grid" && attributeOf(tag, "GridType") == "Uniform")
      ++r.uniform_grids;
    if (name == "Time")
      r.times.push_back(attributeOf(tag, "Value"));
    if (name == "DataItem")
      r.data_items.push_back({attributeOf(tag, "Dimensions"),
                              xml.substr(text_begin, xml.find('<', text_begin) - text_begin)});
    if (tag[tag.size() - 2] != '/')
      stack.push_back(name);
  }
  if (!stack.empty())
    r.well_formed = false, r.error = "unclosed <" + stack.back() + ">";
  return r;
}

/// The .xmf is well formed, has one Uniform grid per frame and every DataItem names an
/// existing dataset of fields.h5 whose shape equals the declared Dimensions; times are
/// written with 17 digits, so they parse back to the very same doubles.
void checkXmf(const std::string &dir, const std::vector<FieldFrame> &frames)
{
  const std::size_t num_frames = frames.size();
  const XmlCheck x = scanXml(readText(dir + "/fields.xmf"));
  ASSERT_TRUE(x.well_formed) << x.error;
  EXPECT_EQ(std::size_t(x.uniform_grids), num_frames);
  EXPECT_EQ(std::size_t(x.tag_count.at("Grid")), num_frames + 1); // + the temporal collection
  EXPECT_EQ(x.times.size(), num_frames);
  for (std::size_t k = 0; k < x.times.size() && k < num_frames; ++k)
    EXPECT_EQ(std::strtod(x.times[k].c_str(), nullptr), frames[k].time) << x.times[k];
  const hid_t file = H5Fopen((dir + "/fields.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  for (const auto &item : x.data_items)
  {
    ASSERT_EQ(item.second.rfind("fields.h5:/", 0), 0u) << item.second;
    const std::string path = item.second.substr(10);
    ASSERT_GT(H5Oexists_by_name(file, path.c_str(), H5P_DEFAULT), 0) << path;
    std::vector<hsize_t> dims;
    readDataset(file, path, &dims);
    std::ostringstream shape;
    for (std::size_t i = 0; i < dims.size(); ++i)
      shape << (i ? " " : "") << dims[i];
    EXPECT_EQ(shape.str(), item.first) << path;
  }
  H5Fclose(file);
}

std::vector<FieldFrame> writeFrames(const std::string &dir, const FieldMeshDesc &m, bool with_u)
{
  std::vector<FieldFrame> frames;
  FieldWriter w(dir, m);
  for (int k = 0; k < 3; ++k)
  {
    frames.push_back(makeFrame(m, k, with_u));
    w.write(frames.back());
  }
  w.close();
  return frames;
}

} // namespace

TEST(FieldWriter, MixedHexTetReadsBackExactly)
{
  const std::string dir = workDir("hextet");
  const FieldMeshDesc m = hexTetMesh();
  const auto frames = writeFrames(dir, m, false);
  // Mixed: XDMF code 9 (hex) + 8 nodes, code 6 (tet) + 4 nodes.
  checkH5(dir, m, frames, {9, 0, 1, 2, 3, 4, 5, 6, 7, 6, 4, 5, 6, 8}, {14});
  checkXmf(dir, frames);
  const std::string xmf = readText(dir + "/fields.xmf");
  EXPECT_NE(xmf.find("TopologyType=\"Mixed\" NumberOfElements=\"2\""), std::string::npos);
  EXPECT_NE(xmf.find("AttributeType=\"Tensor6\" Center=\"Cell\""), std::string::npos);
}

TEST(FieldWriter, QuadMeshWithGivenDisplacement)
{
  const std::string dir = workDir("quad");
  const FieldMeshDesc m = quadMesh();
  const auto frames = writeFrames(dir, m, true);
  checkH5(dir, m, frames, {0, 1, 4, 3, 1, 2, 5, 4}, {2, 4});
  checkXmf(dir, frames);
  const std::string xmf = readText(dir + "/fields.xmf");
  EXPECT_NE(xmf.find("TopologyType=\"Quadrilateral\" NumberOfElements=\"2\""), std::string::npos);
  // The frame's own displacement is used, not a second derived one.
  std::size_t count = 0;
  for (std::size_t p = 0; (p = xmf.find("Name=\"displacement\"", p)) != std::string::npos; ++p)
    ++count;
  EXPECT_EQ(count, 3u);
}

TEST(FieldWriter, PolylineUniformAndInMixedTopology)
{
  FieldMeshDesc m;
  m.dim = 1;
  m.coords0 = {0, 0, 0, 1, 0, 0, 2, 0, 0};
  m.cell_types = {0, 0};
  m.connectivity = {0, 1, 1, 2};
  const auto frames = writeFrames(workDir("line"), m, false);
  checkH5(workDir("line"), m, frames, {0, 1, 1, 2}, {2, 2});
  checkXmf(workDir("line"), frames);
  EXPECT_NE(readText(workDir("line") + "/fields.xmf")
                .find("TopologyType=\"Polyline\" NumberOfElements=\"2\" NodesPerElement=\"2\""),
            std::string::npos);

  // Mixed line + quad: the Polyline code 2 is followed by its node count 2.
  FieldMeshDesc mixed = quadMesh();
  mixed.cell_types = {0, 1};
  mixed.connectivity = {0, 1, 1, 2, 5, 4};
  const auto frames2 = writeFrames(workDir("linequad"), mixed, false);
  checkH5(workDir("linequad"), mixed, frames2, {2, 2, 0, 1, 5, 1, 2, 5, 4}, {9});
  checkXmf(workDir("linequad"), frames2);
}

TEST(FieldWriter, KilledWriterLeavesReadableFiles)
{
  // A child writes two frames and dies without close(): what it wrote must stay readable.
  const std::string dir = workDir("crash");
  const FieldMeshDesc m = hexTetMesh();
  std::fflush(nullptr);
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0)
  {
    FieldWriter w(dir, m);
    w.write(makeFrame(m, 0, false));
    w.write(makeFrame(m, 1, false));
    _exit(0); // no destructor, no H5Fclose: like a crash after the second frame
  }
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  const std::vector<FieldFrame> written = {makeFrame(m, 0, false), makeFrame(m, 1, false)};
  checkH5(dir, m, written, {9, 0, 1, 2, 3, 4, 5, 6, 7, 6, 4, 5, 6, 8}, {14});
  checkXmf(dir, written);
}

TEST(FieldWriter, ErrorsNameThePathOrField)
{
  const std::string blocker = workDir("blocker");
  std::ofstream(blocker) << "a file where a directory is wanted";
  try
  {
    FieldWriter w(blocker + "/sub", quadMesh());
    FAIL() << "no exception for an uncreatable directory";
  }
  catch (const std::runtime_error &e)
  {
    EXPECT_NE(std::string(e.what()).find(blocker + "/sub"), std::string::npos) << e.what();
  }

  FieldMeshDesc bad = quadMesh();
  bad.connectivity.pop_back();
  EXPECT_THROW(FieldWriter(workDir("bad"), bad), std::invalid_argument);
  bad = quadMesh();
  bad.connectivity[0] = 6; // node 6 does not exist
  EXPECT_THROW(FieldWriter(workDir("bad"), bad), std::invalid_argument);

  FieldWriter w(workDir("badframe"), quadMesh());
  FieldFrame f = makeFrame(quadMesh(), 0, false);
  f.cell_scalars[0].second.pop_back();
  EXPECT_THROW(w.write(f), std::invalid_argument);
  f = makeFrame(quadMesh(), 0, false);
  f.node_scalars[0].first = "velocity"; // same name as a node vector
  EXPECT_THROW(w.write(f), std::invalid_argument);
  f.node_scalars[0].first = "a/b";
  EXPECT_THROW(w.write(f), std::invalid_argument);
  EXPECT_EQ(w.framesWritten(), 0); // rejected frames leave nothing behind
  const std::vector<FieldFrame> good = {makeFrame(quadMesh(), 0, false)};
  w.write(good[0]);
  w.close();
  EXPECT_THROW(w.write(makeFrame(quadMesh(), 1, false)), std::logic_error);
  checkXmf(workDir("badframe"), good);
}

TEST(FieldWriter, MeshioTimeSeriesReaderOpensIt)
{
  if (std::system("/usr/bin/python3 -c 'import meshio' > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "meshio not installed for /usr/bin/python3 (Debian python3-meshio)";
  const std::string dir = workDir("meshio");
  const FieldMeshDesc m = hexTetMesh();
  const auto frames = writeFrames(dir, m, false);
  // meshio takes points/cells from the first frame, then per-frame time and attributes.
  const std::string script = dir + "/check.py";
  std::ofstream(script)
      << "import sys, meshio\n"
      << "with meshio.xdmf.TimeSeriesReader(sys.argv[1]) as r:\n"
      << "    pts, cells = r.read_points_cells()\n"
      << "    assert pts.shape == (9, 3), pts.shape\n"
      << "    assert [(c.type, len(c.data)) for c in cells] == [('hexahedron', 1), ('tetra', 1)]\n"
      << "    assert r.num_steps == 3\n"
      << "    t, pd, cd = r.read_data(2)\n"
      << "    assert t == " << std::setprecision(17) << frames[2].time << ", t\n"
      << "    assert pd['displacement'].shape == (9, 3) and pd['temperature'].shape == (9,)\n"
      << "    assert [len(a) for a in cd['stress']] == [1, 1]\n";
  EXPECT_EQ(std::system(("/usr/bin/python3 " + script + " " + dir + "/fields.xmf").c_str()), 0);
}

TEST(FieldWriter, ReadableByAnotherProcessWhileOpen)
{
  // Watching a running simulation: ParaView/h5py open fields.h5 while the solver holds it.
  if (std::system("/usr/bin/python3 -c 'import h5py' > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "h5py not installed for /usr/bin/python3 (Debian python3-h5py)";
  const std::string dir = workDir("live");
  const FieldMeshDesc m = quadMesh();
  FieldWriter w(dir, m);
  const FieldFrame f = makeFrame(m, 1, false);
  w.write(f);
  std::ostringstream cmd;
  cmd << "/usr/bin/python3 -c \"import h5py; f = h5py.File('" << dir
      << "/fields.h5', 'r'); assert f['frames/0/coords'][2, 0] == " << std::setprecision(17)
      << f.coords[6] << "\"";
  EXPECT_EQ(std::system(cmd.str().c_str()), 0) << cmd.str();
  w.write(makeFrame(m, 2, false)); // the reader did not disturb the writer
  w.close();
}

TEST(FieldWriter, ParaViewReadersOpenIt)
{
  // ParaView is the reader that matters; its Debian package is large and optional here.
  std::string ci_failure;
  if (!havePvbatch(&ci_failure))
  {
    if (!ci_failure.empty())
      FAIL() << ci_failure;
    GTEST_SKIP() << "pvbatch not installed (Debian paraview + python3-paraview)";
  }
  const std::string dir = workDir("paraview");
  const FieldMeshDesc m = hexTetMesh();
  const auto frames = writeFrames(dir, m, false);
  // Last frame, hex: Voigt 2001..2006 -> XDMF3 keeps Tensor6 (xx xy xz yy yz zz); the legacy
  // XDMF reader expands it to the full symmetric 3x3. VTK cell types: 12 hex, 10 tet.
  const std::string script = dir + "/check_pv.py";
  std::ofstream(script)
      << std::setprecision(17) << "import sys\nfrom paraview.simple import *\n"
      << "times = [" << frames[0].time << ", " << frames[1].time << ", " << frames[2].time << "]\n"
      << "for name in ['XDMFReader', 'Xdmf3ReaderS']:\n"
      << "    fn = [sys.argv[1]]\n"
      << "    r = XDMFReader(FileNames=fn) if name == 'XDMFReader' else Xdmf3ReaderS(FileName=fn)\n"
      << "    assert list(r.TimestepValues) == times, (name, list(r.TimestepValues))\n"
      << "    r.UpdatePipeline(times[2])\n"
      << "    d = servermanager.Fetch(r)\n"
      << "    assert d.GetNumberOfPoints() == 9 and d.GetNumberOfCells() == 2, name\n"
      << "    assert [d.GetCellType(0), d.GetCellType(1)] == [12, 10], name\n"
      << "    assert abs(d.GetPoint(2)[0] - " << frames[2].coords[6] << ") < 1e-15, name\n"
      << "    s = d.GetCellData().GetArray('stress')\n"
      << "    got = [s.GetComponent(0, c) for c in range(s.GetNumberOfComponents())]\n"
      << "    want = [2001, 2004, 2006, 2002, 2005, 2003] if name != 'XDMFReader' else \\\n"
      << "           [2001, 2004, 2006, 2004, 2002, 2005, 2006, 2005, 2003]\n"
      << "    assert got == want, (name, got)\n"
      << "    u = d.GetPointData().GetArray('displacement')\n"
      << "    assert u.GetNumberOfComponents() == 3, name\n"
      << "print('paraview ok')\n";
  EXPECT_EQ(std::system(("pvbatch " + script + " " + dir + "/fields.xmf").c_str()), 0);
}

namespace
{
/// Frames of 3, 0 (the placeholder point) and 5 points; returns the point count of each.
std::vector<int> writePointFrames(const std::string &dir)
{
  scpdyn::PointSetWriter w(dir, "contacts");
  std::vector<int> counts;
  for (int n : {3, 0, 5})
  {
    scpdyn::PointFrame f;
    f.time = 1e-6 * double(counts.size());
    f.cycle = long(counts.size());
    std::vector<double> area;
    for (int p = 0; p < n; ++p)
    {
      f.points.insert(f.points.end(), {0.1 * p, 0.2, 0.0});
      area.push_back(1.0 + p);
    }
    f.scalars = {{"area", area}};
    w.write(f);
    counts.push_back(n == 0 ? 1 : n);
  }
  w.close();
  return counts;
}
} // namespace

TEST(PointSetWriter, MeshioReadsEveryFrameAsVertices)
{
  if (std::system("/usr/bin/python3 -c 'import meshio' > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "meshio not installed for /usr/bin/python3 (Debian python3-meshio)";
  const std::string dir = workDir("points_meshio");
  const auto counts = writePointFrames(dir);
  // meshio's time-series reader takes the mesh from one grid: pointed at each frame in turn
  std::ostringstream cmd;
  cmd << "/usr/bin/python3 -c \"import meshio\n"
      << "with meshio.xdmf.TimeSeriesReader('" << dir << "/contacts.xmf') as r:\n"
      << "    got = []\n"
      << "    for k in range(r.num_steps):\n"
      << "        r.mesh_grid = r.collection[k]\n"
      << "        p, c = r.read_points_cells()\n"
      << "        t, pd, cd = r.read_data(k)\n"
      << "        assert [x.type for x in c] == ['vertex'] and len(c[0].data) == len(p), k\n"
      << "        assert len(pd['area']) == len(p), k\n"
      << "        got.append(len(p))\n"
      << "    assert got == [" << counts[0] << ", " << counts[1] << ", " << counts[2]
      << "], got\n\"";
  EXPECT_EQ(std::system(cmd.str().c_str()), 0) << cmd.str();
}

TEST(PointSetWriter, ParaViewReadersDrawOneCellPerPoint)
{
  std::string ci_failure;
  if (!havePvbatch(&ci_failure))
  {
    if (!ci_failure.empty())
      FAIL() << ci_failure;
    GTEST_SKIP() << "pvbatch not installed (Debian paraview + python3-paraview)";
  }
  const std::string dir = workDir("points_paraview");
  const auto counts = writePointFrames(dir);
  const std::string script = dir + "/check_pv.py";
  std::ofstream(script) << "import sys\nfrom paraview.simple import *\n"
                        << "counts = [" << counts[0] << ", " << counts[1] << ", " << counts[2]
                        << "]\n"
                        << "for name in ['XDMFReader', 'Xdmf3ReaderS']:\n"
                        << "    fn = [sys.argv[1]]\n"
                        << "    r = XDMFReader(FileNames=fn) if name == 'XDMFReader' else "
                           "Xdmf3ReaderS(FileName=fn)\n"
                        << "    for t, n in zip(r.TimestepValues, counts):\n"
                        << "        r.UpdatePipeline(t)\n"
                        << "        d = servermanager.Fetch(r)\n"
                        << "        got = (d.GetNumberOfPoints(), d.GetNumberOfCells())\n"
                        << "        assert got == (n, n), (name, t, got)\n"
                        << "print('paraview ok')\n";
  EXPECT_EQ(std::system(("pvbatch " + script + " " + dir + "/contacts.xmf").c_str()), 0);
}
