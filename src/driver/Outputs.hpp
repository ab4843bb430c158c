#pragma once
/// \file Outputs.hpp
/// \brief Step 13's outputs: field frames (HDF5 + XDMF), history.csv, gauges.csv,
/// summary.json, the resolved deck and a progress line on stderr. Decomposed runs: every
/// member is collective; rank 0 writes the files, in the serial layout.
#include "driver/OutputGather.hpp"
#include "io/FieldWriter.hpp"
#include "io/TextOutput.hpp"

#include <chrono>
#include <memory>
#include <string>

namespace scpdyn
{

class Solver;

class Outputs
{
public:
  Outputs(const Solver &solver, const std::string &dir);
  ~Outputs();
  /// \brief Writes the resolved deck and the initial frame and rows.
  void begin();
  /// \brief Writes whatever is due after a cycle; prints progress.
  void afterCycle();
  /// \brief Final frame and rows, summary.json; `error` non-empty when the run failed.
  void finish(const std::string &error);

private:
  void writeFrame();
  void writeRows();
  void writeContactFrame();
  bool root() const;

  const Solver &_solver;
  std::string _dir;
  std::unique_ptr<FieldWriter> _fields;
  std::unique_ptr<PointSetWriter> _contacts; ///< contacts.xmf/h5, with contact surfaces only
  bool _has_contacts = false;
  std::vector<int> _material_used; ///< per material: used by an element on any rank
  std::unique_ptr<CsvWriter> _history, _gauges;
  double _next_field = 0, _next_history = 0;
  long _last_frame_cycle = -1, _last_row_cycle = -1;
  double _max_balance_error = 0, _last_balance_error = 0;
  std::chrono::steady_clock::time_point _start, _last_progress;
};

} // namespace scpdyn
