// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The pieces of `mjformation sweep`, private to it: the plan (every run's configuration,
// checked before anything runs: sweep_plan.cc), the execution on threads or MPI ranks with
// --resume (sweep_execute.cc), and the tables (sweep_tables.cc); sweep.cc is the command.
#ifndef MJFORMATION_APP_SRC_SWEEP_HPP_
#define MJFORMATION_APP_SRC_SWEEP_HPP_

#include <chrono>
#include <cstdint>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mjformation/app/cli.hpp"
#include "mjformation/config/config_error.hpp"
#include "mjformation/config/experiment.hpp"

namespace mjf::runner::sweep {

using Json = nlohmann::ordered_json;

struct Axis {
  std::string key;                  // section.key
  std::vector<std::string> values;  // TOML values
};

// One run of the sweep: grid cell, seed and its parsed configuration.
struct RunSpec {
  size_t cell = 0;
  uint64_t seed = 0;
  std::string name;  // run directory under the sweep directory
  ExperimentConfig config;
};

struct SweepPlan {
  std::vector<Axis> axes;
  std::vector<std::vector<size_t>> cells;  // value index per axis
  int seeds = 0;                           // --seeds; 0: one run per cell at the config's seed
  std::vector<RunSpec> runs;               // cell-major, then seed
  std::string out;
};

// What became of a run. `state` kNotRun: never started (interrupted sweep).
struct RunOutcome {
  enum State { kNotRun, kFinished } state = kNotRun;
  Json summary;       // summary.json of the run (null if it never wrote one)
  std::string error;  // why it is not complete; empty when complete
  bool complete() const { return state == kFinished && error.empty(); }
};

// "formation.q=1,2.5,4.5" -> {formation.q, [1, 2.5, 4.5]}; throws ConfigError naming the
// --vary argument when it is not section.key=v1,v2,... .
Axis ParseAxis(const std::string& text);
// Every --vary argument parsed; a key varied twice is refused.
std::vector<Axis> ParseAxes(const std::vector<std::string>& texts);

// The run directory name of a grid point (`index`: a value index per axis), e.g.
// "altitude=3.0,turbulence=none", "mean=6.0_0.0_0.0": no value can add a separator, a path
// component or a shell metacharacter. `legacy`: the older %XX form of brackets and commas.
std::string PointName(const std::vector<Axis>& axes, const std::vector<size_t>& index,
                      bool legacy = false);

// Every run's configuration, parsed and checked before anything runs.
SweepPlan PlanSweep(const CliCommands& c);

// A --vary value as a reader wants it in a table: a plain TOML string ("none") without its
// quotes (none); numbers, arrays and tables as written.
std::string DisplayValue(const std::string& toml);

// "1 run", "3 runs": a count of runs as the messages write it.
inline std::string RunCount(size_t n) { return std::to_string(n) + (n == 1 ? " run" : " runs"); }

// A CSV field: as is, or quoted (RFC 4180) when it holds a comma, quote, CR or LF.
std::string CsvField(const std::string& v);

// The file's bytes; empty when it cannot be read.
std::string ReadText(const std::string& path);

// Creates the sweep directory (or checks it for --resume) and lists the runs still to do; the
// others' outcomes are filled from their run directories.
std::vector<size_t> PrepareOutput(const SweepPlan& plan, const CliCommands& c,
                                  std::vector<RunOutcome>* outcomes);

// sweep.csv, sweep.json (and sweep_runs.csv with --seeds). `complete`: every run finished.
void WriteTables(const SweepPlan& plan, const std::vector<RunOutcome>& outcomes);

// The short summary a sweep prints on stdout: per cell (with --seeds) or per run, sigma_f_mean
// with its 95 % interval (none for a constant), incomplete runs and safety events; at most 20
// lines, the full table being in sweep.csv.
std::string SummaryText(const SweepPlan& plan, const std::vector<RunOutcome>& outcomes);

// Keeps the tables current while runs finish, at most once a second, so a sweep that dies
// leaves tables marked incomplete rather than none (the final write comes after all runs).
class Progress {
 public:
  Progress(const SweepPlan& plan, std::vector<RunOutcome>* outcomes, size_t todo)
      : plan_(plan), outcomes_(outcomes), todo_(todo) {}
  void Done(size_t i, RunOutcome outcome);

 private:
  const SweepPlan& plan_;
  std::vector<RunOutcome>* outcomes_;
  size_t todo_, done_ = 0;
  std::mutex mutex_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::chrono::steady_clock::time_point last_write_ = start_;
};

// The runs of `todo` on c.sweep_jobs threads.
void RunThreaded(const SweepPlan& plan, const CliCommands& c, const std::vector<size_t>& todo,
                 Progress* progress);

// True when started by mpirun / an MPI launcher.
bool UnderMpiLauncher();

// The runs over MPI ranks (libmjf_sweep_mpi.so); returns this process's rank (0 writes the
// tables).
int RunMpi(const SweepPlan& plan, const CliCommands& c, std::vector<RunOutcome>* outcomes);

}  // namespace mjf::runner::sweep

#endif  // MJFORMATION_APP_SRC_SWEEP_HPP_
