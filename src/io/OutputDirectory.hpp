#pragma once
/// \file OutputDirectory.hpp
/// \brief The output directory of a run: a lock that keeps two runs out of one directory, and
/// the removal of a previous run's files, so that a directory only ever holds one run's
/// outputs. Host-only, POSIX.
#include <string>
#include <vector>

namespace scpdyn
{

/// \brief Holds `dir/scpdyn.lock` (text: "<pid> <host>") while it lives, and removes it on
/// destruction. The lock is taken with an exclusive create, so of two runs starting together
/// exactly one gets it.
class OutputDirectoryLock
{
public:
  static constexpr const char *kFileName = "scpdyn.lock";

  /// \brief Takes the lock of the existing directory `dir`. A lock whose process is alive (or
  /// that names another host, where liveness cannot be checked) throws std::runtime_error
  /// naming the directory, the pid and the host; a lock left by a dead process of this host is
  /// taken over, and warning() says so.
  explicit OutputDirectoryLock(const std::string &dir);
  ~OutputDirectoryLock();
  OutputDirectoryLock(const OutputDirectoryLock &) = delete;
  OutputDirectoryLock &operator=(const OutputDirectoryLock &) = delete;

  const std::string &path() const { return _path; }
  /// \brief Empty, or one line about a stale lock that was taken over.
  const std::string &warning() const { return _warning; }

private:
  std::string _path;
  std::string _text; ///< what this process wrote, so only its own lock is removed
  std::string _warning;
};

/// \brief This host's name (as gethostname).
std::string hostName();

/// \brief Removes those of `names` that exist in `dir` (plain files only) and returns the
/// names removed. Throws std::runtime_error naming the file and the cause when one cannot be
/// removed.
std::vector<std::string> removeFiles(const std::string &dir, const std::vector<std::string> &names);

} // namespace scpdyn
