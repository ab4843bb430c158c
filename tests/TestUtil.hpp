#pragma once
// Helpers shared by the tests: run decks in-process or through the binary, read CSV files.
#include "core/InputError.hpp"
#include "driver/Solver.hpp"
#include "input/Deck.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <utility>
#include <vector>

namespace scpdyn::test
{

/// \brief Columns of a CSV file written by scpdyn (header line, then numbers).
inline std::map<std::string, std::vector<double>> readCsv(const std::string &path)
{
  std::ifstream in(path);
  std::string line;
  std::vector<std::string> names;
  std::map<std::string, std::vector<double>> cols;
  if (!std::getline(in, line))
    return cols;
  std::stringstream hs(line);
  for (std::string n; std::getline(hs, n, ',');)
    names.push_back(n);
  while (std::getline(in, line))
  {
    std::stringstream ls(line);
    size_t k = 0;
    for (std::string v; std::getline(ls, v, ',') && k < names.size(); ++k)
      cols[names[k]].push_back(std::strtod(v.c_str(), nullptr));
  }
  return cols;
}

/// \brief The whole text of a file ("" if it cannot be read).
inline std::string readText(const std::string &path)
{
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// \brief Runs the scpdyn binary; returns its exit status, stderr text in `err` and stdout
/// text in `out`.
inline int runBinary(const std::string &args, std::string *err = nullptr,
                     const std::string &env = "", std::string *out = nullptr)
{
  const std::string key = std::to_string(std::hash<std::string>()(args + env)) + ".txt";
  const std::string err_file = std::string(SCPDYN_TEST_WORKDIR) + "/stderr_" + key;
  const std::string out_file = std::string(SCPDYN_TEST_WORKDIR) + "/stdout_" + key;
  const std::string cmd = env + " " + SCPDYN_BINARY + " " + args + " > " +
                          (out ? out_file : std::string("/dev/null")) + " 2> " + err_file;
  const int rc = std::system(cmd.c_str());
  if (err)
    *err = readText(err_file);
  if (out)
    *out = readText(out_file);
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

/// \brief Writes text to a file in the test work directory; returns its path.
inline std::string writeWorkFile(const std::string &name, const std::string &text)
{
  const std::string path = std::string(SCPDYN_TEST_WORKDIR) + "/" + name;
  std::ofstream(path) << text;
  return path;
}

/// \brief The InputError message of calling f (parsing or setting up a deck), or "accepted".
template <class F>
std::string inputErrorOf(F &&f)
{
  try
  {
    f();
  }
  catch (const InputError &e)
  {
    return e.what();
  }
  return "accepted";
}

/// \brief Deck parsed from YAML text (the path names it in messages).
inline Deck deckFromText(const std::string &yaml, const std::string &name)
{
  return parseDeckString(yaml, name + ".yaml");
}

/// \brief The lines of a text file (none if it cannot be read).
inline std::vector<std::string> lines(const std::string &path)
{
  std::vector<std::string> out;
  std::ifstream in(path);
  for (std::string l; std::getline(in, l);)
    out.push_back(l);
  return out;
}

/// \brief The restart files (restart_<cycle>.h5) in `dir`, by ascending cycle.
inline std::vector<std::string> restartFiles(const std::string &dir)
{
  std::vector<std::pair<long, std::string>> found;
  const std::regex name(R"(restart_([0-9]+)\.h5)");
  for (const auto &e : std::filesystem::directory_iterator(dir))
  {
    std::smatch m;
    const std::string f = e.path().filename().string();
    if (std::regex_match(f, m, name))
      found.push_back({std::stol(m[1].str()), e.path().string()});
  }
  std::sort(found.begin(), found.end());
  std::vector<std::string> out;
  for (const auto &f : found)
    out.push_back(f.second);
  return out;
}

} // namespace scpdyn::test
