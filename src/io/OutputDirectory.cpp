/// \file OutputDirectory.cpp
/// \brief The output-directory lock and the removal of a previous run's files
/// (OutputDirectory.hpp).
#include "io/OutputDirectory.hpp"

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <sys/types.h>
#include <system_error>
#include <thread>
#include <unistd.h>

namespace scpdyn
{
namespace
{
std::string readWhole(const std::string &path)
{
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The holder a lock file names; pid 0 when the text is not "<pid> <host>".
struct LockHolder
{
  long pid = 0;
  std::string host;
};

LockHolder parseHolder(const std::string &text)
{
  LockHolder h;
  std::istringstream in(text);
  if (!(in >> h.pid >> h.host) || h.pid <= 0)
    h = LockHolder();
  return h;
}

bool processAlive(long pid)
{
  // EPERM: the process exists but belongs to another user
  return ::kill(pid_t(pid), 0) == 0 || errno == EPERM;
}
} // namespace

std::string hostName()
{
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0)
    return "unknown-host";
  return name;
}

OutputDirectoryLock::OutputDirectoryLock(const std::string &dir) : _path(dir + "/" + kFileName)
{
  const std::string host = hostName();
  _text = std::to_string(long(::getpid())) + " " + host + "\n";
  // a stale lock is removed and the exclusive create tried again; a run that takes it over
  // at the same moment wins that create, and this one then finds a live holder
  for (int attempt = 0; attempt < 4; ++attempt)
  {
    const int fd = ::open(_path.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
    if (fd >= 0)
    {
      const ssize_t written = ::write(fd, _text.data(), _text.size());
      const int write_errno = errno;
      const bool closed = ::close(fd) == 0;
      if (written != ssize_t(_text.size()) || !closed)
      {
        ::unlink(_path.c_str());
        throw std::runtime_error("cannot write the lock file '" + _path +
                                 "': " + std::strerror(written < 0 ? write_errno : ENOSPC));
      }
      return;
    }
    if (errno != EEXIST)
      throw std::runtime_error("cannot create the lock file '" + _path +
                               "': " + std::strerror(errno));
    LockHolder holder = parseHolder(readWhole(_path));
    if (holder.pid == 0)
    { // a run that has just created the file may not have written it yet
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      holder = parseHolder(readWhole(_path));
    }
    if (holder.pid != 0 && holder.host != host)
      throw std::runtime_error("output directory '" + dir + "' is locked by pid " +
                               std::to_string(holder.pid) + " on host " + holder.host +
                               ", which cannot be checked from " + host + " (" + _path +
                               "); remove the lock file if that run is over");
    if (holder.pid != 0 && processAlive(holder.pid))
      throw std::runtime_error("output directory '" + dir + "' is in use by the run of pid " +
                               std::to_string(holder.pid) + " on " + host + " (" + _path +
                               "); wait for it to end or give another directory with -o");
    _warning = holder.pid != 0 ? "took over the stale lock of pid " + std::to_string(holder.pid) +
                                     " (no such process) in '" + dir + "'"
                               : "took over the unreadable lock file '" + _path + "'";
    if (::unlink(_path.c_str()) != 0 && errno != ENOENT)
      throw std::runtime_error("cannot remove the stale lock file '" + _path +
                               "': " + std::strerror(errno));
  }
  throw std::runtime_error("cannot take the lock file '" + _path +
                           "': other runs keep taking it over");
}

OutputDirectoryLock::~OutputDirectoryLock()
{
  if (readWhole(_path) == _text)
    ::unlink(_path.c_str());
}

std::vector<std::string> removeFiles(const std::string &dir, const std::vector<std::string> &names)
{
  namespace fs = std::filesystem;
  std::vector<std::string> removed;
  for (const std::string &name : names)
  {
    const fs::path p = fs::path(dir) / name;
    std::error_code ec;
    if (!fs::is_regular_file(fs::symlink_status(p, ec)))
      continue;
    if (!fs::remove(p, ec) || ec)
      throw std::runtime_error("cannot remove the previous run's '" + p.string() +
                               "': " + (ec ? ec.message() : std::string("not removed")));
    removed.push_back(name);
  }
  return removed;
}

} // namespace scpdyn
