#pragma once
/// \file Hdf5Util.hpp
/// \brief Internal to src/io: the HDF5 (C API) helpers shared by the field writer and the
/// contact point-set writer. Host-only.
#include <hdf5.h>
#include <mpi.h>

#include <algorithm>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace scpdyn
{
namespace h5detail
{

/// HDF5 prints its whole error stack on every failure (some 200 lines on a full disk, none of
/// them saying so plainly); the writers report one line instead, with failureCause().
inline void silenceErrorStack() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

/// The cause of the HDF5 call that has just failed, read from its error stack: the system
/// error the file driver recorded ("errno = 28, error message = ..." -> strerror(28)), else
/// the innermost message. Call it before any other HDF5 call, which would clear the stack.
inline std::string failureCause()
{
  struct Found
  {
    int system_error = 0;
    std::string innermost;
  } found;
  auto visit = [](unsigned n, const H5E_error2_t *e, void *data) -> herr_t {
    Found &f = *static_cast<Found *>(data);
    const std::string desc = e && e->desc ? e->desc : "";
    if (n == 0)
      f.innermost = desc;
    const auto at = desc.find("errno = ");
    if (f.system_error == 0 && at != std::string::npos)
      f.system_error = std::atoi(desc.c_str() + at + 8);
    return 0;
  };
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, visit, &found);
  if (found.system_error > 0)
    return std::strerror(found.system_error);
  return found.innermost.empty() ? std::string("unknown HDF5 error") : found.innermost;
}

/// File-access list: POSIX sec2 driver for a serial run, MPI-IO for a decomposed one.
/// File locking is off: with it (the 1.10.7+ default) ParaView and h5py cannot open the file
/// of a running simulation at all. Readers are safe between frames because every frame is
/// flushed before fields.xmf names it.
/// With `comm` (a decomposed run) the list selects MPI-IO on that communicator.
inline hid_t makeFileAccessList(const MPI_Comm *comm = nullptr)
{
  const hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  const herr_t driver = fapl < 0 ? -1
                        : comm   ? H5Pset_fapl_mpio(fapl, *comm, MPI_INFO_NULL)
                                 : H5Pset_fapl_sec2(fapl);
  if (driver < 0)
    throw std::runtime_error("FieldWriter: cannot create an HDF5 file-access property list");
#if (H5_VERS_MAJOR == 1 && H5_VERS_MINOR == 10 && H5_VERS_RELEASE >= 7) || H5_VERSION_GE(1, 12, 1)
  H5Pset_file_locking(fapl, false, true);
#endif
  return fapl;
}

/// The one place that creates the field file, for whatever driver `fapl` selects.
inline hid_t createFieldFile(const std::string &path, hid_t fapl)
{
  silenceErrorStack();
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
  if (file < 0)
    throw std::runtime_error("cannot create '" + path + "': " + failureCause());
  return file;
}

/// Closes an HDF5 object on scope exit, so an exception in the middle leaks no handle.
class Handle
{
public:
  Handle(hid_t id, herr_t (*closer)(hid_t)) : _id(id), _closer(closer) {}
  ~Handle()
  {
    if (_id >= 0)
      _closer(_id);
  }
  Handle(const Handle &) = delete;
  Handle &operator=(const Handle &) = delete;
  operator hid_t() const { return _id; }
  /// Closes now and returns HDF5's status: closing a dataset writes it out, so a full disk
  /// shows here rather than in the destructor, which cannot report it.
  herr_t close()
  {
    const herr_t status = _id >= 0 ? _closer(_id) : 0;
    _id = -1;
    return status;
  }

private:
  hid_t _id;
  herr_t (*_closer)(hid_t);
};

/// One line for a failed HDF5 call: the file, the cause, and what HDF5 was doing.
inline void check(herr_t status, const std::string &what, const std::string &path)
{
  if (status < 0)
    throw std::runtime_error("cannot write '" + path + "': " + failureCause() +
                             " (HDF5 failed to " + what + ")");
}

/// Releases an open file and its transfer list without checks (after a failure), leaving -1.
inline void releaseFile(hid_t &file, hid_t &dxpl)
{
  H5Fclose(file);
  if (dxpl >= 0)
    H5Pclose(dxpl);
  file = dxpl = -1;
}

/// The one place that opens an output file: created (truncated) with the driver of
/// makeFileAccessList(comm), or with `existing` the file a previous run wrote opened for
/// writing (a restarted run continuing its outputs), and its dataset transfer list,
/// collective with `comm`.
inline void openFile(const std::string &path, const MPI_Comm *comm, hid_t &file, hid_t &dxpl,
                     bool existing = false)
{
  silenceErrorStack();
  {
    Handle fapl(makeFileAccessList(comm), H5Pclose);
    if (!existing)
      file = createFieldFile(path, fapl);
    else if ((file = H5Fopen(path.c_str(), H5F_ACC_RDWR, fapl)) < 0)
      throw std::runtime_error("cannot open '" + path + "' to continue it: " + failureCause());
  }
  dxpl = H5Pcreate(H5P_DATASET_XFER);
  try
  {
    check(dxpl < 0 ? -1 : 0, "create a transfer property list", path);
    if (comm)
      check(H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE), "select collective transfers", path);
  }
  catch (...)
  {
    releaseFile(file, dxpl);
    throw;
  }
}

/// Flushes and closes the file and releases its transfer list (nothing when closed already);
/// throws when the flush or the close failed.
inline void closeFile(hid_t &file, hid_t &dxpl, const std::string &path)
{
  if (file < 0)
    return;
  const herr_t flushed = H5Fflush(file, H5F_SCOPE_GLOBAL);
  const std::string flush_cause = flushed < 0 ? failureCause() : std::string();
  const herr_t closed = H5Fclose(file);
  const std::string close_cause = closed < 0 ? failureCause() : std::string();
  H5Pclose(dxpl);
  file = dxpl = -1;
  if (flushed < 0 || closed < 0)
    throw std::runtime_error("cannot write '" + path +
                             "': " + (flushed < 0 ? flush_cause : close_cause) +
                             " (HDF5 failed to close the file)");
}

inline hid_t createGroup(hid_t loc, const std::string &name, const std::string &path)
{
  const hid_t g = H5Gcreate2(loc, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  if (g < 0)
    throw std::runtime_error("cannot write '" + path + "': " + failureCause() +
                             " (HDF5 failed to create group '" + name + "')");
  return g;
}

inline hid_t openGroup(hid_t loc, const std::string &name, const std::string &path)
{
  const hid_t g = H5Gopen2(loc, name.c_str(), H5P_DEFAULT);
  if (g < 0)
    throw std::runtime_error("cannot read '" + path + "': " + failureCause() +
                             " (HDF5 failed to open group '" + name + "')");
  return g;
}

/// Every dataset goes through here, so switching to a collective transfer is one `dxpl`.
template <class T>
void writeDataset(hid_t loc, const std::string &name, const std::vector<hsize_t> &dims,
                  const T *data, hid_t dxpl, const std::string &path)
{
  const bool is_real = std::is_same<T, double>::value;
  const hid_t mem_type = is_real ? H5T_NATIVE_DOUBLE : H5T_NATIVE_INT;
  const hid_t file_type = is_real ? H5T_IEEE_F64LE : H5T_STD_I32LE;
  Handle space(H5Screate_simple(int(dims.size()), dims.data(), nullptr), H5Sclose);
  Handle dset(space < 0 ? -1
                        : H5Dcreate2(loc, name.c_str(), file_type, space, H5P_DEFAULT, H5P_DEFAULT,
                                     H5P_DEFAULT),
              H5Dclose);
  herr_t status = dset < 0 ? -1 : H5Dwrite(dset, mem_type, H5S_ALL, H5S_ALL, dxpl, data);
  if (status >= 0)
    status = dset.close();
  check(status, "write dataset '" + name + "'", path);
}

/// \brief Rows of a dataset one rank writes: ascending, disjoint runs [start, start + length).
struct RowRuns
{
  std::vector<hsize_t> start, length;
  hsize_t rows = 0; ///< sum of the lengths
  /// \brief All `n` rows (n > 0), or none.
  static RowRuns all(hsize_t n)
  {
    RowRuns r;
    if (n > 0)
      r.start = {0}, r.length = {n}, r.rows = n;
    return r;
  }
};

/// \brief Part of a dataset of global shape `dims` (rows x optional components): this rank's
/// `runs.rows` rows, packed in `data` in ascending row order. Collective over the file's
/// communicator when `dxpl` is collective (every rank calls it, with or without rows).
template <class T>
void writeDatasetRows(hid_t loc, const std::string &name, const std::vector<hsize_t> &dims,
                      const RowRuns &runs, const T *data, hid_t dxpl, const std::string &path)
{
  const bool is_real = std::is_same<T, double>::value;
  const hid_t mem_type = is_real ? H5T_NATIVE_DOUBLE : H5T_NATIVE_INT;
  const hid_t file_type = is_real ? H5T_IEEE_F64LE : H5T_STD_I32LE;
  const hsize_t comps = dims.size() > 1 ? dims[1] : 1;
  Handle space(H5Screate_simple(int(dims.size()), dims.data(), nullptr), H5Sclose);
  Handle dset(space < 0 ? -1
                        : H5Dcreate2(loc, name.c_str(), file_type, space, H5P_DEFAULT, H5P_DEFAULT,
                                     H5P_DEFAULT),
              H5Dclose);
  herr_t status = dset < 0 ? -1 : 0;
  if (status >= 0 && runs.rows == 0)
    status = H5Sselect_none(space);
  for (size_t k = 0; status >= 0 && k < runs.start.size(); ++k)
  {
    const hsize_t start[2] = {runs.start[k], 0}, count[2] = {runs.length[k], comps};
    status = H5Sselect_hyperslab(space, k == 0 ? H5S_SELECT_SET : H5S_SELECT_OR, start, nullptr,
                                 count, nullptr);
  }
  const hsize_t mem_dims[1] = {std::max<hsize_t>(runs.rows * comps, 1)};
  Handle mem(H5Screate_simple(1, mem_dims, nullptr), H5Sclose);
  if (status >= 0 && runs.rows == 0)
    status = H5Sselect_none(mem);
  if (status >= 0)
    status = H5Dwrite(dset, mem_type, mem, space, dxpl, data);
  if (status >= 0)
    status = dset.close();
  check(status, "write dataset '" + name + "'", path);
}

template <class T>
void writeScalarAttribute(hid_t loc, const char *name, T value, const std::string &path)
{
  const bool is_real = std::is_same<T, double>::value;
  const hid_t mem_type = is_real ? H5T_NATIVE_DOUBLE : H5T_NATIVE_LONG;
  const hid_t file_type = is_real ? H5T_IEEE_F64LE : H5T_STD_I64LE;
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attr(H5Acreate2(loc, name, file_type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  herr_t status = attr < 0 ? -1 : H5Awrite(attr, mem_type, &value);
  if (status >= 0)
    status = attr.close();
  check(status, std::string("write attribute '") + name + "'", path);
}

/// \brief A restarted run continuing a frame file (/frames/<k>, attribute `time`): checks
/// that the file holds at least `keep` frames and that the last of them is at `last_time` (the
/// count alone could match another run's file), and removes the frames after it, which the
/// run that wrote the restart file had not written yet when it wrote it. Collective over the
/// file's communicator (every rank makes the same calls).
inline void keepFrames(hid_t file, int keep, double last_time, const std::string &path)
{
  Handle frames(openGroup(file, "frames", path), H5Gclose);
  H5G_info_t info;
  if (H5Gget_info(frames, &info) < 0)
    throw std::runtime_error("cannot read '" + path + "': " + failureCause());
  const std::string cannot = "cannot continue '" + path + "': ";
  if (info.nlinks < hsize_t(keep))
    throw std::runtime_error(cannot + "it holds " + std::to_string(info.nlinks) +
                             " frames, the restart file's run had written " + std::to_string(keep));
  if (keep > 0)
  {
    double t = 0;
    const std::string last = std::to_string(keep - 1);
    Handle attr(H5Aopen_by_name(frames, last.c_str(), "time", H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
    if (attr < 0 || H5Aread(attr, H5T_NATIVE_DOUBLE, &t) < 0 || t != last_time)
      throw std::runtime_error(cannot + "its frame " + last + " is not at the time of the " +
                               "restart file's (another run's outputs)");
  }
  for (hsize_t k = hsize_t(keep); k < info.nlinks; ++k)
    check(H5Ldelete(frames, std::to_string(k).c_str(), H5P_DEFAULT),
          "remove frame " + std::to_string(k), path);
}

/// \brief The writers' XDMF document: a temporal collection `name` of frame grids, each the
/// text xdmfFrameGrids() finds again.
inline std::string xdmfCollection(const std::string &name, const std::vector<std::string> &grids)
{
  // Version 3.0 for meshio's reader; the XDMF2-style keys (TopologyType, NumberType, ...)
  // are read by both ParaView readers (XDMF and XDMF3).
  std::string x = "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
                  "<Xdmf Version=\"3.0\">\n  <Domain>\n    <Grid Name=\"" +
                  name + "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const std::string &g : grids)
    x += g;
  return x + "    </Grid>\n  </Domain>\n</Xdmf>\n";
}

constexpr const char *kXdmfGridStart = "      <Grid Name=\"frame_";
constexpr const char *kXdmfGridEnd = "      </Grid>\n";

/// \brief The first `keep` frame grids of the XDMF document xdmfCollection() wrote to `path`,
/// as its text, for a restarted run that continues it; throws when it holds fewer.
inline std::vector<std::string> xdmfFrameGrids(const std::string &path, size_t keep)
{
  std::FILE *fp = std::fopen(path.c_str(), "rb");
  std::string text;
  if (fp)
  {
    char buf[65536];
    for (size_t n; (n = std::fread(buf, 1, sizeof buf, fp)) > 0;)
      text.append(buf, n);
    std::fclose(fp);
  }
  std::vector<std::string> grids;
  for (size_t at = text.find(kXdmfGridStart); grids.size() < keep && at != std::string::npos;
       at = text.find(kXdmfGridStart, at))
  {
    const size_t end = text.find(kXdmfGridEnd, at);
    if (end == std::string::npos)
      break;
    const size_t next = end + std::strlen(kXdmfGridEnd);
    grids.push_back(text.substr(at, next - at));
    at = next;
  }
  if (grids.size() < keep)
    throw std::runtime_error("cannot continue '" + path + "': " +
                             (fp ? "it holds " + std::to_string(grids.size()) + " frames, the " +
                                       "restart file's run had written " + std::to_string(keep)
                                 : std::string("no such file")));
  return grids;
}

inline std::string xmlEscape(const std::string &s)
{
  std::string out;
  for (char c : s)
  {
    switch (c)
    {
    case '&':
      out += "&amp;";
      break;
    case '<':
      out += "&lt;";
      break;
    case '>':
      out += "&gt;";
      break;
    case '"':
      out += "&quot;";
      break;
    case '\'':
      out += "&apos;";
      break;
    default:
      out += c;
    }
  }
  return out;
}

} // namespace h5detail
} // namespace scpdyn
