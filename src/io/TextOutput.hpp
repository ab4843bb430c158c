#pragma once
/// \file TextOutput.hpp
/// \brief Small text outputs: CSV time histories (gauges, energies), a JSON writer for
/// summary.json, and mkdir -p. Host-only.
///
/// Numbers are printed with "%.17g": 17 significant digits are the fewest that make every
/// IEEE double round-trip exactly through strtod, and gauges are compared between runs at
/// 1e-10 relative, which "%.10e" (11 digits) could not resolve.
#include <cstdio>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace scpdyn
{

/// \brief Creates `path` and its missing parents (mkdir -p). Throws std::runtime_error
/// naming the path if it cannot be created or exists as something else than a directory.
void ensureDirectory(const std::string &path);

/// \brief A double as "%.17g" (round-trips bit for bit through strtod).
std::string formatDouble(double value);

/// \brief Replaces `path` with `text` through `path.tmp` and a rename, so readers only ever
/// see a complete file. On failure the temporary is removed and std::runtime_error names the
/// file and the cause (strerror: "No space left on device", ...).
void replaceFile(const std::string &path, const std::string &text);

/// \brief A restarted run continuing a CSV file a previous run wrote into its directory: the
/// header (which must be this writer's) and the first `rows` rows are kept byte for byte (the
/// last of them must begin with `last_time`, else the file is another run's), the later rows
/// removed, and new rows come after them.
struct ContinueRows
{
  long rows = -1; ///< -1: a new file
  double last_time = 0;
};

/// \brief CSV file: one header line, then one line per row() with "%.17g" numbers.
///
/// Rows are flushed to the OS every `flush_every` rows and at flush()/close()/destruction,
/// so a run that dies loses at most flush_every-1 rows. The file only ever ends with whole
/// rows: a write that fails part-way (a full disk) is cut back to the last whole row, and the
/// error names the file and the cause.
class CsvWriter
{
public:
  /// \brief Creates (truncates) `path` and writes the header. Column names containing a
  /// comma, quote or newline are quoted as in RFC 4180. Throws std::runtime_error naming
  /// the path if it cannot be opened.
  CsvWriter(const std::string &path, std::vector<std::string> columns, int flush_every = 16);
  /// \brief With `continued.rows` >= 0: continues the existing `path` (ContinueRows); throws
  /// std::runtime_error naming the path when it is not a file this run can continue.
  CsvWriter(const std::string &path, std::vector<std::string> columns,
            const ContinueRows &continued, int flush_every = 16);
  ~CsvWriter();
  CsvWriter(const CsvWriter &) = delete;
  CsvWriter &operator=(const CsvWriter &) = delete;

  /// \brief Appends one row; throws std::invalid_argument if values.size() != columns.
  void row(const std::vector<double> &values);
  /// \brief Pushes buffered rows to the OS; throws std::runtime_error naming the file and the
  /// cause on a write error (the rows not written are dropped, the file keeps whole rows).
  void flush();
  /// \brief Flushes and closes; idempotent. row() afterwards throws std::logic_error.
  void close();

  const std::string &path() const { return _path; }
  std::size_t numColumns() const { return _columns.size(); }

private:
  std::string _path;
  std::vector<std::string> _columns;
  int _flush_every;
  int _pending = 0;
  int _fd = -1;        ///< the open file, -1 when closed
  std::string _buffer; ///< rows not yet written
  long long _size = 0; ///< bytes of whole rows in the file
};

/// \brief Escapes a string for use inside JSON double quotes (", \, control characters);
/// UTF-8 bytes pass through unchanged.
std::string jsonEscape(const std::string &s);

/// \brief Ordered JSON object, enough for summary.json. Keys keep insertion order; adding an
/// existing key replaces its value in place. Non-finite doubles are written as null.
class JsonObject
{
public:
  JsonObject &add(const std::string &key, double value);
  JsonObject &add(const std::string &key, int value);
  JsonObject &add(const std::string &key, long value);
  JsonObject &add(const std::string &key, long long value);
  JsonObject &add(const std::string &key, unsigned value);
  JsonObject &add(const std::string &key, unsigned long value);
  JsonObject &add(const std::string &key, bool value);
  JsonObject &add(const std::string &key, const std::string &value);
  /// Without this overload a string literal would silently convert to bool.
  JsonObject &add(const std::string &key, const char *value);
  JsonObject &add(const std::string &key, const JsonObject &value);
  /// \brief A flat array of numbers (e.g. a gauge position); non-finite entries -> null.
  JsonObject &add(const std::string &key, const std::vector<double> &values);

  bool empty() const { return _entries.empty(); }
  std::size_t size() const { return _entries.size(); }

  /// \brief The object as JSON text: indent > 0 pretty-prints with that many spaces per
  /// level, indent <= 0 gives one line without spaces.
  std::string dump(int indent = 2) const;

private:
  struct Entry
  {
    std::string key;
    std::string text;                   ///< pre-rendered scalar or array, if no object
    std::shared_ptr<JsonObject> object; ///< nested object, rendered at dump time
  };
  JsonObject &set(const std::string &key, std::string text, std::shared_ptr<JsonObject> obj);
  void dumpTo(std::string &out, int indent, int level) const;

  std::vector<Entry> _entries;
};

/// \brief Writes `object.dump(indent)` plus a newline to `path` (truncating), via a
/// temporary file and rename so readers never see a partial file. Throws
/// std::runtime_error naming the path on failure.
void writeJson(const std::string &path, const JsonObject &object, int indent = 2);

} // namespace scpdyn
