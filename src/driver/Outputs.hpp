#pragma once
/// \file Outputs.hpp
/// \brief Step 13's outputs: field frames (HDF5 + XDMF), history.csv, gauges.csv (with
/// gauges), rcforc.csv, spcforc.csv and matsum.csv at history.csv's rows (RunHistories.hpp),
/// summary.json, the resolved deck, restart files (output.restart_interval) and a
/// progress line on stderr. Before the first
/// cycle: an estimate of the run's cycles and output size (refused above the deck's limits)
/// in the pre-flight block (driver/Preflight.hpp), the lock of the output directory and the
/// removal of a previous run's files. Decomposed runs: every member is collective; rank 0 locks
/// the directory and writes the files, in the serial layout.
#include "driver/OutputGather.hpp"
#include "driver/RunHistories.hpp"
#include "io/FieldWriter.hpp"
#include "io/OutputDirectory.hpp"
#include "io/TextOutput.hpp"

#include <chrono>
#include <deque>
#include <memory>
#include <string>

namespace scpdyn
{

class Solver;
struct Deck;
class RestartReader;

/// \brief What a run will do, estimated before its first cycle from the end time, the first
/// time step, time.max_cycles, the output intervals and the model's size.
struct RunEstimate
{
  double first_dt = 0;     ///< s
  double cycles = 0;       ///< end time / first dt (rounded up), at most time.max_cycles
  double history_rows = 0; ///< rows of history.csv (and gauges.csv)
  double frames = 0;       ///< field frames (and contact frames)
  double row_bytes = 0;    ///< one row of history.csv, gauges.csv and RunHistories' files
  double frame_bytes = 0;  ///< one field frame plus one contact frame, with their XDMF text
  double bytes = 0;        ///< all outputs
};

/// \brief "%.3g" of a byte count with its decimal unit (kB, MB, GB, TB).
std::string formatBytes(double bytes);

/// \brief The estimate of `solver`'s run (collective: the same numbers on every rank).
RunEstimate estimateRun(const Solver &solver);

/// \brief Empty, or the refusal of a run whose estimate exceeds time.max_estimated_cycles or
/// output.max_output_bytes, naming the key.
std::string estimateRefusal(const Deck &deck, const RunEstimate &estimate);

/// \brief The time a periodic output is next due after writing at time `t`: `next` advanced
/// by whole intervals past t + eps, or, when the interval is too small to get there in a few
/// steps (below the time step, or below the round-off of `next`), the first representable time
/// past t + eps, so the output is written once per cycle at most.
double nextOutputTime(double next, double interval, double t, double eps);

class Outputs
{
public:
  /// \brief Estimates the run (an InputError above the deck's limits), prints the pre-flight
  /// block on stdout, locks `dir` and removes a previous run's outputs from it (an InputError
  /// naming the directory when another live run holds it). With `restart` and a `dir` that
  /// holds history.csv, the run continues the outputs there instead: begin() keeps the rows
  /// and frames the run that wrote the restart file had written when it wrote it and drops the
  /// later ones.
  Outputs(const Solver &solver, const std::string &dir, const RestartReader *restart = nullptr);
  ~Outputs();
  /// \brief Writes the resolved deck and the initial frame and rows; with `restart` (the run
  /// continues from that file) no initial frame and rows, the output times go on from the
  /// file's, and the files the constructor found go on after the file's rows and frames.
  void begin(const RestartReader *restart = nullptr);
  /// \brief Whether this run continues the outputs of `dir` (see the constructor).
  bool continuesOutputs() const { return _continued.rows >= 0; }
  /// \brief restart_<cycle>.h5 of the state now (the solver's and these outputs' times), then
  /// the oldest of this run's restart files beyond output.restart_keep removed.
  void writeRestart();
  /// \brief Writes whatever is due after a cycle; prints progress.
  void afterCycle();
  /// \brief Final frame and rows, summary.json; `error` non-empty when the run failed.
  void finish(const std::string &error);
  /// \brief finish() of a run stopped before its end by `signal` ("SIGTERM"): summary.json
  /// says `"status": "interrupted"` and names the signal.
  void finishInterrupted(const std::string &signal);

private:
  void finishWith(const std::string &status, const std::string &error, const std::string &signal);
  void startTimes(const RestartReader *restart);
  void openRootWriters();
  void writeFrame();
  void writeRows();
  void writeContactFrame();
  bool root() const;

  const Solver &_solver;
  std::string _dir;
  JsonObject _preflight;                      ///< summary.json's `preflight` (driver/Preflight.hpp)
  std::unique_ptr<OutputDirectoryLock> _lock; ///< rank 0; released after the writers close
  std::unique_ptr<FieldWriter> _fields;
  std::unique_ptr<PointSetWriter> _contacts; ///< contacts.xmf/h5, with contact surfaces only
  bool _has_contacts = false;
  bool _has_sleepy = false;        ///< history.csv counts the sleepy CPs that have failed
  std::vector<int> _material_used; ///< per material: used by an element on any rank
  std::unique_ptr<CsvWriter> _history, _gauges;
  std::unique_ptr<RunHistories> _run_histories;
  std::unique_ptr<CsvWriter> _rcforc, _spcforc, _matsum; ///< rank 0, when they have columns
  double _next_field = 0, _next_history = 0, _next_restart = 0;
  std::deque<std::string> _restart_files; ///< written by this run, oldest first
  // rows and frames in the directory's files, and the time of the last of each: the counts a
  // restart file records, so that a restart continues those files after them
  long _rows = 0, _frames = 0;
  double _last_row_time = 0, _last_frame_time = 0;
  ContinueRows _continued;
  ContinueFrames _continued_frames;
  long _last_frame_cycle = -1, _last_row_cycle = -1;
  double _max_balance_error = 0, _last_balance_error = 0;
  std::chrono::steady_clock::time_point _start, _last_progress;
};

} // namespace scpdyn
