#include "io/RestartFile.hpp"

#include "core/InputError.hpp"
#include "io/Hdf5Util.hpp"
#include "parallel/Mpi.hpp"

#include <cstdio>
#include <filesystem>

namespace scpdyn
{
using namespace h5detail;

namespace
{
void writeStringAttribute(hid_t loc, const char *name, const std::string &value,
                          const std::string &path)
{
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  herr_t status = type < 0 ? -1 : H5Tset_size(type, std::max<size_t>(value.size(), 1));
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attr(status < 0 ? -1 : H5Acreate2(loc, name, type, space, H5P_DEFAULT, H5P_DEFAULT),
              H5Aclose);
  status = attr < 0 ? -1 : H5Awrite(attr, type, value.c_str());
  if (status >= 0)
    status = attr.close();
  check(status, std::string("write attribute '") + name + "'", path);
}

bool readStringAttribute(hid_t loc, const char *name, std::string &value)
{
  if (H5Aexists(loc, name) <= 0)
    return false;
  Handle attr(H5Aopen(loc, name, H5P_DEFAULT), H5Aclose);
  Handle type(attr < 0 ? -1 : H5Aget_type(attr), H5Tclose);
  if (type < 0 || H5Tget_class(type) != H5T_STRING || H5Tis_variable_str(type) > 0)
    return false;
  std::vector<char> buf(H5Tget_size(type) + 1, '\0');
  if (H5Aread(attr, type, buf.data()) < 0)
    return false;
  value.assign(buf.data());
  return true;
}

bool readLongAttribute(hid_t loc, const char *name, long &value)
{
  if (H5Aexists(loc, name) <= 0)
    return false;
  Handle attr(H5Aopen(loc, name, H5P_DEFAULT), H5Aclose);
  return attr >= 0 && H5Aread(attr, H5T_NATIVE_LONG, &value) >= 0;
}
} // namespace

std::string textHash(const std::string &text)
{
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char c : text)
  {
    h ^= c;
    h *= 1099511628211ull;
  }
  char out[17];
  std::snprintf(out, sizeof out, "%016llx", static_cast<unsigned long long>(h));
  return out;
}

RestartWriter::RestartWriter(const std::string &path, const std::string &deck_hash, MPI_Comm comm)
    : _path(path), _tmp(path + ".tmp"), _comm(comm)
{
  if (comm != MPI_COMM_NULL && mpiRank(comm) != 0)
    return;
  try
  {
    hid_t file = -1, dxpl = -1;
    openFile(_tmp, nullptr, file, dxpl);
    _file = file;
    _dxpl = dxpl;
    writeScalarAttribute<long>(file, "format_version", kRestartFormatVersion, _tmp);
    writeStringAttribute(file, "deck_hash", deck_hash, _tmp);
  }
  catch (const std::runtime_error &e)
  {
    _error = e.what();
  }
}

RestartWriter::~RestartWriter()
{
  if (_file < 0)
    return;
  hid_t file = hid_t(_file), dxpl = hid_t(_dxpl);
  releaseFile(file, dxpl);
  std::error_code ec;
  std::filesystem::remove(_tmp, ec);
}

void RestartWriter::write(const std::string &name, const void *values, size_t count, bool real)
{
  // a failure is kept for commit(): the other ranks go on gathering, none is left waiting
  if (_file < 0 || !_error.empty())
    return;
  try
  {
    if (real)
      writeDataset(hid_t(_file), name, {hsize_t(count)}, static_cast<const double *>(values),
                   hid_t(_dxpl), _tmp);
    else
      writeDataset(hid_t(_file), name, {hsize_t(count)}, static_cast<const int *>(values),
                   hid_t(_dxpl), _tmp);
  }
  catch (const std::runtime_error &e)
  {
    _error = e.what();
  }
}

void RestartWriter::put(const std::string &name, const std::vector<double> &values)
{
  write(name, values.data(), values.size(), true);
}

void RestartWriter::put(const std::string &name, const std::vector<int> &values)
{
  write(name, values.data(), values.size(), false);
}

void RestartWriter::commit()
{
  if (_file >= 0 && _error.empty())
    try
    {
      // a marker written last: a file cut short before it is not a complete restart file
      writeScalarAttribute<long>(hid_t(_file), "complete", 1, _tmp);
      hid_t file = hid_t(_file), dxpl = hid_t(_dxpl);
      _file = _dxpl = -1;
      closeFile(file, dxpl, _tmp);
      std::error_code ec;
      std::filesystem::rename(_tmp, _path, ec);
      if (ec)
        _error =
            "cannot write '" + _path + "': " + ec.message() + " (renaming the complete .tmp file)";
    }
    catch (const std::runtime_error &e)
    {
      _error = e.what();
    }
  const std::string error = _comm != MPI_COMM_NULL ? firstErrorOfAnyRank(_error, _comm) : _error;
  if (!error.empty())
    throw std::runtime_error(error);
}

RestartReader::RestartReader(const std::string &path, const std::string &deck_hash) : _path(path)
{
  const std::string where = "restart file '" + path + "': ";
  if (!std::filesystem::exists(path))
    throw InputError(where + "no such file");
  silenceErrorStack();
  if (H5Fis_hdf5(path.c_str()) <= 0)
    throw InputError(where + "not an HDF5 file, or truncated or corrupt");
  Handle fapl(makeFileAccessList(nullptr), H5Pclose);
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl);
  if (file < 0)
    throw InputError(where + "truncated or corrupt (" + failureCause() + ")");
  _file = file;
  long version = -1, complete = 0;
  std::string hash;
  if (!readLongAttribute(file, "format_version", version))
    throw InputError(where + "truncated or corrupt (no format_version)");
  if (version != kRestartFormatVersion)
    throw InputError(where + "file-format version " + std::to_string(version) +
                     ", this scpdyn reads version " + std::to_string(kRestartFormatVersion));
  if (!readLongAttribute(file, "complete", complete) || complete != 1)
    throw InputError(where + "truncated or corrupt (incomplete)");
  if (!readStringAttribute(file, "deck_hash", hash))
    throw InputError(where + "truncated or corrupt (no deck_hash)");
  if (hash != deck_hash)
    throw InputError(where + "written by another deck (deck hash " + hash + ", this deck's " +
                     deck_hash + ")");
}

RestartReader::~RestartReader()
{
  if (_file >= 0)
    H5Fclose(hid_t(_file));
}

template <class T>
std::vector<T> RestartReader::read(const std::string &name, long expected) const
{
  const std::string where = "restart file '" + _path + "': ";
  const hid_t file = hid_t(_file);
  if (H5Lexists(file, name.c_str(), H5P_DEFAULT) <= 0)
    throw InputError(where + "truncated or corrupt (no dataset '" + name + "')");
  Handle dset(H5Dopen2(file, name.c_str(), H5P_DEFAULT), H5Dclose);
  Handle space(dset < 0 ? -1 : H5Dget_space(dset), H5Sclose);
  const hssize_t n = space < 0 ? -1 : H5Sget_simple_extent_npoints(space);
  if (n < 0)
    throw InputError(where + "truncated or corrupt (dataset '" + name + "')");
  if (expected >= 0 && n != expected)
    throw InputError(where + "dataset '" + name + "' has " + std::to_string(n) +
                     " values, the model needs " + std::to_string(expected) +
                     " (another mesh or deck)");
  std::vector<T> out(static_cast<size_t>(n));
  const hid_t type = std::is_same<T, double>::value ? H5T_NATIVE_DOUBLE : H5T_NATIVE_INT;
  if (n > 0 && H5Dread(dset, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0)
    throw InputError(where + "truncated or corrupt (reading dataset '" + name + "')");
  return out;
}

std::vector<double> RestartReader::reals(const std::string &name, long expected) const
{
  return read<double>(name, expected);
}

std::vector<int> RestartReader::ints(const std::string &name, long expected) const
{
  return read<int>(name, expected);
}

} // namespace scpdyn
