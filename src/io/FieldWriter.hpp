#pragma once
/// \file FieldWriter.hpp
/// \brief Field output (step 13): one HDF5 file with every frame plus an XDMF sidecar that
/// ParaView (XDMF and XDMF3 readers) and meshio open as a time series.
///
/// Layout of `fields.h5`:
///   /mesh/coords0 (n,3) f64, /mesh/cell_types (ne) i32, /mesh/connectivity (flat) i32,
///   /mesh/topology   the XDMF topology array (ne, npe) for one cell type, else the flat
///                    Mixed array with XDMF type codes (written once, referenced by each frame)
///   /frames/<k>      attributes `time` (s) and `cycle`; datasets `coords` (n,3) and
///                    `point_data/<name>`, `cell_data/<name>`; tensors are stored in XDMF
///                    Tensor6 order xx xy xz yy yz zz (converted from Voigt).
/// Every frame carries a nodal "displacement" (x - x0 unless the frame supplies one), so a
/// reader that takes the mesh from the first frame only (meshio) can still warp it.
/// Host-only: the solver copies Views to host and hands plain vectors over.
#include <mpi.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace scpdyn
{

/// \brief Mesh description fixed for the whole run.
struct FieldMeshDesc
{
  int dim = 3;                   ///< 1, 2, 3 (geometry is written with 3 components anyway)
  std::vector<double> coords0;   ///< n_nodes*3, initial coordinates (m)
  std::vector<int> cell_types;   ///< per element: ElementType as int (0 Line2 .. 3 Tet4)
  std::vector<int> connectivity; ///< flattened, nodesPerElement(type) ids per element
};

/// \brief A decomposed run's share of the field file. Every rank holds its local nodes and
/// cells; `node_rows[i]` is the global row of local node i, or -1 where another rank owns the
/// node (and writes it); `cell_rows[c]` the global row of local cell c. The mesh itself
/// (FieldMeshDesc) is given in full on rank 0 and empty on the others.
struct FieldDistribution
{
  MPI_Comm comm = MPI_COMM_NULL;
  std::vector<long> node_rows;
  std::vector<long> cell_rows;
};

/// \brief Named field; the vector length is fixed by its kind (see FieldFrame).
using NamedField = std::pair<std::string, std::vector<double>>;

/// \brief One output time. Names must be non-empty, without '/', unique per centring.
struct FieldFrame
{
  double time = 0.0; ///< s
  long cycle = 0;
  std::vector<double> coords;            ///< current (deformed) n_nodes*3 (m)
  std::vector<NamedField> node_vectors;  ///< n_nodes*3 each ("displacement", "velocity")
  std::vector<NamedField> node_scalars;  ///< n_nodes each
  std::vector<NamedField> cell_scalars;  ///< n_cells each ("pressure", "part")
  std::vector<NamedField> cell_tensors6; ///< n_cells*6, Voigt xx yy zz xy yz zx ("stress")
};

/// \brief A restarted run continuing the frame files a previous run wrote into its directory:
/// the first `frames` frames are kept as they are (the last of them must be at `last_time`,
/// else the files are another run's), the later ones removed, and new frames come after them.
struct ContinueFrames
{
  int frames = -1; ///< -1: new files
  double last_time = 0;
};

/// \brief Appends frames to `dir/fields.h5` and keeps `dir/fields.xmf` valid after each one.
///
/// Serial runs write through the sec2 driver; decomposed runs (FieldDistribution) open the
/// same file through MPI-IO and write every dataset collectively, each rank its own rows.
class FieldWriter
{
public:
  /// \brief Creates `dir` (mkdir -p), truncates `dir/fields.h5`, writes /mesh and an empty
  /// `dir/fields.xmf`. Throws std::runtime_error naming the path on I/O failure and
  /// std::invalid_argument on an inconsistent mesh.
  FieldWriter(const std::string &dir, const FieldMeshDesc &mesh,
              const ContinueFrames &continued = {});
  /// \brief The collective version for a decomposed run: every rank of `dist.comm` constructs
  /// it, each frame is written by all ranks at once (MPI-IO, collective transfers, each rank
  /// its own rows), so no rank ever holds a global frame. Frames then carry the rank's local
  /// nodes and cells, every node field including "displacement". Only rank 0 writes the XDMF.
  FieldWriter(const std::string &dir, const FieldMeshDesc &mesh, const FieldDistribution &dist,
              const ContinueFrames &continued = {});
  ~FieldWriter();
  FieldWriter(const FieldWriter &) = delete;
  FieldWriter &operator=(const FieldWriter &) = delete;

  /// \brief Appends frame k = framesWritten() as /frames/<k>, flushes the HDF5 file and
  /// rewrites fields.xmf completely (via a temporary file and rename, so a crash leaves
  /// the previous complete sidecar). Throws std::invalid_argument on wrong field sizes.
  void write(const FieldFrame &frame);
  /// \brief Flushes and closes the HDF5 file; idempotent. write() afterwards throws.
  void close();

  int framesWritten() const { return int(_grids.size()); }
  const std::string &h5Path() const { return _h5_path; }
  const std::string &xmfPath() const { return _xmf_path; }

private:
  /// XDMF description of one attribute of a written frame (kept to regenerate the XML).
  struct AttributeInfo
  {
    std::string name;
    bool on_cells = false;
    int components = 1; ///< 1 scalar, 3 vector, 6 tensor6
  };
  struct FrameInfo
  {
    double time;
    long cycle;
    std::vector<AttributeInfo> attributes;
  };
  /// The XDMF grid of frame k (written once, kept to regenerate the document).
  std::string frameXml(std::size_t k, const FrameInfo &f) const;

  /// This rank's rows of a decomposed run, ascending, and where each comes from locally.
  struct RowPlan
  {
    std::vector<long> local; ///< local index of each written row, in ascending row order
    std::vector<unsigned long long> start, length; ///< the rows as runs
  };
  void open(const std::string &dir, const ContinueFrames &continued);
  void writeMesh();
  template <class T>
  void writeRows(std::int64_t loc, const std::string &name, const RowPlan *plan, std::size_t rows,
                 int comps, const T *data);
  bool root() const { return _rank == 0; }
  void writeXdmf() const;
  std::string topologyXml() const;

  std::string _h5_path, _xmf_path;
  FieldMeshDesc _mesh;
  int _num_nodes = 0, _num_cells = 0;
  int _uniform_type = -1; ///< the single cell type, or -1 when the mesh mixes types
  std::size_t _topology_length = 0;
  std::int64_t _file = -1;         ///< hid_t of the open file (int64 in HDF5 1.10), -1 when closed
  std::int64_t _dxpl = -1;         ///< dataset transfer list (collective in a decomposed run)
  std::vector<std::string> _grids; ///< per frame written: its XDMF grid
  bool _distributed = false;
  MPI_Comm _comm = MPI_COMM_NULL;
  int _rank = 0;
  RowPlan _node_plan, _cell_plan;
  std::size_t _local_nodes = 0, _local_cells = 0, _connectivity_length = 0;
};

/// \brief One output time of a point set (e.g. the contact points, one per common plane). The
/// number of points may change from frame to frame.
struct PointFrame
{
  double time = 0.0; ///< s
  long cycle = 0;
  std::vector<double> points;      ///< n_points*3 (m)
  std::vector<NamedField> scalars; ///< n_points each
};

/// \brief Appends point frames to `dir/<name>.h5` and keeps `dir/<name>.xmf` (an XDMF temporal
/// collection of Polyvertex grids, one vertex cell per point) valid after each one; ParaView
/// (XDMF and XDMF3 readers) and meshio's time-series reader open it. A frame
/// without points is written as one placeholder point at the origin whose scalars are all
/// `empty_value`, because XDMF readers reject empty grids.
/// Layout: /frames/<k> with attributes `time`, `cycle`; datasets `points` (n, 3), `vertices`
/// (n, 1) = 0 .. n-1 (the topology) and `point_data/<name>`.
class PointSetWriter
{
public:
  PointSetWriter(const std::string &dir, const std::string &name, double empty_value = -1.0,
                 const ContinueFrames &continued = {});
  ~PointSetWriter();
  PointSetWriter(const PointSetWriter &) = delete;
  PointSetWriter &operator=(const PointSetWriter &) = delete;

  /// \brief Appends one frame, flushes, rewrites the XDMF sidecar. Throws
  /// std::invalid_argument on inconsistent sizes or names, std::runtime_error on I/O errors.
  void write(const PointFrame &frame);
  void close();
  int framesWritten() const { return int(_grids.size()); }
  const std::string &xmfPath() const { return _xmf_path; }

private:
  struct FrameInfo
  {
    double time;
    long cycle;
    std::size_t count;
    std::vector<std::string> names;
  };
  std::string frameXml(std::size_t k, const FrameInfo &f) const;
  void writeXdmf() const;

  std::string _h5_name, _h5_path, _xmf_path;
  double _empty_value;
  std::int64_t _file = -1;
  std::int64_t _dxpl = -1;
  std::vector<std::string> _grids; ///< per frame written: its XDMF grid
};

} // namespace scpdyn
