#pragma once
/// \file RestartFile.hpp
/// \brief A restart file: named arrays of doubles and ints in one HDF5 file, with the file-format
/// version and the hash of the deck that wrote it. The writer writes `<path>.tmp` and renames it
/// to `<path>` once it is complete and closed, so a crash never leaves a file under the final
/// name that a restart would take for a whole one. The reader throws an InputError of one line
/// naming the file and the cause (another deck, another version, a truncated or corrupt file).
/// Host-only. A decomposed run gathers its arrays to rank 0 in global order, which alone writes
/// the file (the writer is collective); every rank reads the whole file and takes its part, so
/// a file read at any rank count gives every rank the same checks and the same errors.
#include <mpi.h>

#include <cstdint>
#include <string>
#include <vector>

namespace scpdyn
{

/// \brief The version of the layout Solver::saveState() writes; raise it when that changes.
constexpr long kRestartFormatVersion = 6;

class RestartWriter
{
public:
  /// \brief Collective over `comm` (MPI_COMM_NULL: one rank): rank 0 opens the file, put() on
  /// the other ranks does nothing.
  RestartWriter(const std::string &path, const std::string &deck_hash,
                MPI_Comm comm = MPI_COMM_NULL);
  ~RestartWriter();
  RestartWriter(const RestartWriter &) = delete;
  RestartWriter &operator=(const RestartWriter &) = delete;
  void put(const std::string &name, const std::vector<double> &values);
  void put(const std::string &name, const std::vector<int> &values);
  /// \brief Closes the .tmp file and renames it to the final path (collective: a failure of
  /// rank 0's, here or in a put(), is thrown on every rank).
  void commit();

private:
  void write(const std::string &name, const void *values, size_t count, bool real);
  std::string _path, _tmp, _error;
  MPI_Comm _comm = MPI_COMM_NULL;
  long long _file = -1, _dxpl = -1;
};

class RestartReader
{
public:
  /// \brief Opens `path` and checks its version and its deck hash against `deck_hash`.
  RestartReader(const std::string &path, const std::string &deck_hash);
  ~RestartReader();
  RestartReader(const RestartReader &) = delete;
  RestartReader &operator=(const RestartReader &) = delete;
  /// \brief The array `name`; with `expected` >= 0 its length must be that.
  std::vector<double> reals(const std::string &name, long expected = -1) const;
  std::vector<int> ints(const std::string &name, long expected = -1) const;
  const std::string &path() const { return _path; }

private:
  template <class T>
  std::vector<T> read(const std::string &name, long expected) const;
  std::string _path;
  long long _file = -1;
};

/// \brief FNV-1a hash of `text`, as 16 hex digits.
std::string textHash(const std::string &text);

} // namespace scpdyn
