#pragma once
// Driver tests that start the scpdyn binary as a child process and signal it.
#include <sys/wait.h>
#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

extern char **environ;

namespace scpdyn
{
namespace test
{
/// A process started with its stdout and stderr in files.
struct Started
{
  pid_t pid = -1;
  std::string out, err;
};

/// Starts `argv` (argv[0] a path) with this process's environment, less the variables named in
/// `unset` and with `set` ("NAME=value") added, SIGINT and SIGTERM at their default actions.
inline Started start(const std::vector<std::string> &argv, const std::string &logs,
                     const std::vector<std::string> &unset, const std::vector<std::string> &set)
{
  std::vector<std::string> env;
  for (char **e = environ; *e; ++e)
  {
    const std::string v = *e;
    bool keep = true;
    for (const std::string &u : unset)
      keep = keep && v.rfind(u + "=", 0) != 0;
    for (const std::string &s : set)
      keep = keep && v.rfind(s.substr(0, s.find('=') + 1), 0) != 0;
    if (keep)
      env.push_back(v);
  }
  env.insert(env.end(), set.begin(), set.end());
  std::vector<char *> args, envp;
  for (const std::string &a : argv)
    args.push_back(const_cast<char *>(a.c_str()));
  args.push_back(nullptr);
  for (const std::string &e : env)
    envp.push_back(const_cast<char *>(e.c_str()));
  envp.push_back(nullptr);
  Started s{-1, logs + ".out", logs + ".err"};
  s.pid = fork();
  if (s.pid == 0)
  { // only async-signal-safe calls until exec
    const int out = open(s.out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = open(s.err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(out, 1);
    dup2(err, 2);
    signal(SIGINT, SIG_DFL);
    signal(SIGTERM, SIG_DFL);
    sigset_t none;
    sigemptyset(&none);
    sigprocmask(SIG_SETMASK, &none, nullptr);
    execve(args[0], args.data(), envp.data());
    _exit(127);
  }
  return s;
}

/// Waits up to `seconds` for `path` to exist while `pid` runs; false if it ended or timed out.
inline bool waitForFile(pid_t pid, const std::string &path, double seconds)
{
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < until)
  {
    if (std::filesystem::exists(path))
      return true;
    if (waitpid(pid, nullptr, WNOHANG) == pid)
      return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

/// The wait status of `pid` within `seconds`; past that it is killed and -1 returned.
inline int waitForExit(pid_t pid, double seconds)
{
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  int status = 0;
  while (std::chrono::steady_clock::now() < until)
  {
    if (waitpid(pid, &status, WNOHANG) == pid)
      return status;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  kill(pid, SIGKILL);
  waitpid(pid, &status, 0);
  return -1;
}

} // namespace test
} // namespace scpdyn
