/// \file TextOutput.cpp
/// \brief CSV, JSON and directory helpers declared in TextOutput.hpp.
#include "io/TextOutput.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <stdexcept>
#include <system_error>
#include <unistd.h>

namespace scpdyn
{

void ensureDirectory(const std::string &path)
{
  namespace fs = std::filesystem;
  if (path.empty())
    throw std::runtime_error("ensureDirectory: empty path");
  std::error_code ec;
  fs::create_directories(path, ec);
  // create_directories reports no error for an existing regular file on some libstdc++
  // versions, hence the explicit check afterwards.
  if (ec || !fs::is_directory(path))
    throw std::runtime_error("cannot create directory '" + path +
                             "': " + (ec ? ec.message() : std::string("not a directory")));
}

std::string formatDouble(double value)
{
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", value);
  return buf;
}

// ---------------------------------------------------------------------------------------
// CSV

namespace
{
std::string csvField(const std::string &s)
{
  if (s.find_first_of(",\"\r\n") == std::string::npos)
    return s;
  std::string out = "\"";
  for (char c : s)
    out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}
} // namespace

CsvWriter::CsvWriter(const std::string &path, std::vector<std::string> columns, int flush_every)
    : CsvWriter(path, std::move(columns), ContinueRows{}, flush_every)
{
}

CsvWriter::CsvWriter(const std::string &path, std::vector<std::string> columns,
                     const ContinueRows &continued, int flush_every)
    : _path(path), _columns(std::move(columns)), _flush_every(flush_every < 1 ? 1 : flush_every)
{
  if (_columns.empty())
    throw std::invalid_argument("CsvWriter: no columns for '" + path + "'");
  std::string header;
  for (std::size_t i = 0; i < _columns.size(); ++i)
    header += (i ? "," : "") + csvField(_columns[i]);
  header += "\n";
  if (continued.rows < 0)
  {
    _fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (_fd < 0)
      throw std::runtime_error("cannot open '" + path + "': " + std::strerror(errno));
    _buffer = header;
    flush(); // the header alone already tells a crashed run's reader what was measured
    return;
  }
  _fd = ::open(path.c_str(), O_RDWR | O_CLOEXEC);
  if (_fd < 0)
    throw std::runtime_error("cannot open '" + path + "' to continue it: " + std::strerror(errno));
  std::string text;
  char buf[65536];
  for (ssize_t n; (n = ::read(_fd, buf, sizeof buf)) != 0;)
    if (n > 0)
      text.append(buf, size_t(n));
    else if (errno != EINTR)
      break;
  const std::string cannot = "cannot continue '" + path + "': ";
  std::string error;
  size_t end = header.size(), last = end;
  if (text.compare(0, header.size(), header) != 0)
    error = cannot + "its header is not this run's columns";
  for (long r = 0; error.empty() && r < continued.rows; ++r)
  {
    const size_t eol = text.find('\n', end);
    if (eol == std::string::npos)
    {
      error = cannot + "it holds " + std::to_string(r) + " rows, the restart file's run had " +
              "written " + std::to_string(continued.rows);
      break;
    }
    last = end;
    end = eol + 1;
  }
  if (error.empty() && continued.rows > 0 &&
      std::strtod(text.c_str() + last, nullptr) != continued.last_time)
    error = cannot + "its row " + std::to_string(continued.rows) + " is not at the time of the " +
            "restart file's (another run's outputs)";
  if (error.empty() &&
      (::ftruncate(_fd, off_t(end)) != 0 || ::lseek(_fd, off_t(end), SEEK_SET) < 0))
    error = cannot + std::strerror(errno);
  if (!error.empty())
  {
    ::close(_fd);
    _fd = -1;
    throw std::runtime_error(error);
  }
  _size = static_cast<long long>(end);
}

CsvWriter::~CsvWriter()
{
  try
  {
    close();
  }
  catch (...)
  {
    // A destructor must not throw; call close() explicitly to see the error.
  }
}

void CsvWriter::row(const std::vector<double> &values)
{
  if (_fd < 0)
    throw std::logic_error("CsvWriter: row() after close() on '" + _path + "'");
  if (values.size() != _columns.size())
    throw std::invalid_argument("CsvWriter: row of " + std::to_string(values.size()) +
                                " values for " + std::to_string(_columns.size()) + " columns in '" +
                                _path + "'");
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    if (i)
      _buffer += ',';
    _buffer += formatDouble(values[i]);
  }
  _buffer += '\n';
  if (++_pending >= _flush_every)
    flush();
}

void CsvWriter::flush()
{
  if (_fd < 0 || _buffer.empty())
    return;
  _pending = 0;
  std::size_t done = 0;
  while (done < _buffer.size())
  {
    const ssize_t n = ::write(_fd, _buffer.data() + done, _buffer.size() - done);
    if (n < 0 && errno == EINTR)
      continue;
    if (n <= 0)
    {
      const int cause = n < 0 ? errno : ENOSPC;
      // whatever part of a row got through is cut off: a reader sees whole rows only
      if (done > 0 && ::ftruncate(_fd, off_t(_size)) == 0)
        ::lseek(_fd, off_t(_size), SEEK_SET);
      _buffer.clear();
      throw std::runtime_error("cannot write '" + _path + "': " + std::strerror(cause));
    }
    done += std::size_t(n);
  }
  _size += static_cast<long long>(_buffer.size());
  _buffer.clear();
}

void CsvWriter::close()
{
  if (_fd < 0)
    return;
  std::string error;
  try
  {
    flush();
  }
  catch (const std::runtime_error &e)
  {
    error = e.what();
  }
  if (::close(_fd) != 0 && error.empty())
    error = "cannot write '" + _path + "': " + std::strerror(errno);
  _fd = -1;
  if (!error.empty())
    throw std::runtime_error(error);
}

// ---------------------------------------------------------------------------------------
// JSON

std::string jsonEscape(const std::string &s)
{
  std::string out;
  out.reserve(s.size());
  for (const char ch : s)
  {
    const auto c = static_cast<unsigned char>(ch);
    switch (c)
    {
    case '"':
      out += "\\\"";
      break;
    case '\\':
      out += "\\\\";
      break;
    case '\b':
      out += "\\b";
      break;
    case '\f':
      out += "\\f";
      break;
    case '\n':
      out += "\\n";
      break;
    case '\r':
      out += "\\r";
      break;
    case '\t':
      out += "\\t";
      break;
    default:
      if (c < 0x20)
      {
        char buf[8];
        std::snprintf(buf, sizeof buf, "\\u%04x", unsigned(c));
        out += buf;
      }
      else
        out += ch;
    }
  }
  return out;
}

namespace
{
std::string jsonNumber(double v) { return std::isfinite(v) ? formatDouble(v) : "null"; }
} // namespace

JsonObject &JsonObject::set(const std::string &key, std::string text,
                            std::shared_ptr<JsonObject> obj)
{
  for (Entry &e : _entries)
    if (e.key == key)
    {
      e.text = std::move(text);
      e.object = std::move(obj);
      return *this;
    }
  _entries.push_back({key, std::move(text), std::move(obj)});
  return *this;
}

JsonObject &JsonObject::add(const std::string &key, double value)
{
  return set(key, jsonNumber(value), nullptr);
}
JsonObject &JsonObject::add(const std::string &key, int value)
{
  return set(key, std::to_string(value), nullptr);
}
JsonObject &JsonObject::add(const std::string &key, long value)
{
  return set(key, std::to_string(value), nullptr);
}
JsonObject &JsonObject::add(const std::string &key, long long value)
{
  return set(key, std::to_string(value), nullptr);
}
JsonObject &JsonObject::add(const std::string &key, unsigned value)
{
  return set(key, std::to_string(value), nullptr);
}
JsonObject &JsonObject::add(const std::string &key, unsigned long value)
{
  return set(key, std::to_string(value), nullptr);
}
JsonObject &JsonObject::add(const std::string &key, bool value)
{
  return set(key, value ? "true" : "false", nullptr);
}
JsonObject &JsonObject::add(const std::string &key, const std::string &value)
{
  return set(key, "\"" + jsonEscape(value) + "\"", nullptr);
}
JsonObject &JsonObject::add(const std::string &key, const char *value)
{
  return add(key, std::string(value ? value : ""));
}
JsonObject &JsonObject::add(const std::string &key, const JsonObject &value)
{
  return set(key, std::string(), std::make_shared<JsonObject>(value));
}
JsonObject &JsonObject::add(const std::string &key, const std::vector<double> &values)
{
  std::string text = "[";
  for (std::size_t i = 0; i < values.size(); ++i)
    text += (i ? ", " : "") + jsonNumber(values[i]);
  return set(key, text + "]", nullptr);
}

void JsonObject::dumpTo(std::string &out, int indent, int level) const
{
  if (_entries.empty())
  {
    out += "{}";
    return;
  }
  const bool pretty = indent > 0;
  const std::string pad = pretty ? std::string(std::size_t(indent * (level + 1)), ' ') : "";
  out += pretty ? "{\n" : "{";
  for (std::size_t i = 0; i < _entries.size(); ++i)
  {
    const Entry &e = _entries[i];
    out += pad + "\"" + jsonEscape(e.key) + (pretty ? "\": " : "\":");
    if (e.object)
      e.object->dumpTo(out, indent, level + 1);
    else
      out += e.text;
    if (i + 1 < _entries.size())
      out += ",";
    if (pretty)
      out += "\n";
  }
  if (pretty)
    out += std::string(std::size_t(indent * level), ' ');
  out += "}";
}

std::string JsonObject::dump(int indent) const
{
  std::string out;
  dumpTo(out, indent, 0);
  return out;
}

void replaceFile(const std::string &path, const std::string &text)
{
  const std::string tmp = path + ".tmp";
  std::FILE *fp = std::fopen(tmp.c_str(), "w");
  if (!fp)
    throw std::runtime_error("cannot create '" + tmp + "': " + std::strerror(errno));
  int cause = 0;
  errno = 0;
  if (std::fwrite(text.data(), 1, text.size(), fp) != text.size())
    cause = errno ? errno : EIO;
  // stdio writes most of the text at fclose: its error is the one a full disk gives
  errno = 0;
  if (std::fclose(fp) != 0 && cause == 0)
    cause = errno ? errno : EIO;
  if (cause == 0 && std::rename(tmp.c_str(), path.c_str()) != 0)
  {
    const int rename_cause = errno;
    std::remove(tmp.c_str());
    throw std::runtime_error("cannot rename '" + tmp + "' to '" + path +
                             "': " + std::strerror(rename_cause));
  }
  if (cause != 0)
  {
    std::remove(tmp.c_str()); // a half-written temporary helps no reader
    throw std::runtime_error("cannot write '" + tmp + "': " + std::strerror(cause));
  }
}

void writeJson(const std::string &path, const JsonObject &object, int indent)
{
  replaceFile(path, object.dump(indent) + "\n");
}

} // namespace scpdyn
