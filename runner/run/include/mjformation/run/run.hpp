// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// run_experiment as a library: the CLI's `run` and the tests call the same function.
#ifndef MJFORMATION_RUN_RUN_HPP_
#define MJFORMATION_RUN_RUN_HPP_

#include <nlohmann/json.hpp>
#include <string>

#include "mjformation/config/experiment.hpp"

namespace mjf::runner {

struct RunOptions {
  std::string out_dir;          // the run directory; empty: write nothing (benchmarks)
  bool overwrite = false;       // replace an existing run directory
  bool progress = false;        // progress line on stderr
  bool render = true;           // snapshots and video as configured
  bool record = true;           // timeseries.csv
  bool warnings = false;        // the setup's warnings (torque authority) on stderr before the run
  double checkpoint_every = 0;  // s of simulated time between checkpoints; 0: none
  bool resume = false;          // continue from out_dir's checkpoint (checkpoint.hpp)
};

struct RunResult {
  bool complete = false;
  std::string error;          // why the run stopped early
  int signal = 0;             // SIGINT / SIGTERM / SIGHUP when the run was interrupted, else 0
  std::string summary_error;  // summary.json could not be written (e.g. a full disk)
  double wall_time_s = 0;     // stepping loop only
  double sim_time_s = 0;
  int64_t steps = 0;
  nlohmann::ordered_json summary;  // what summary.json holds
};

// Runs one experiment end to end. Input errors (config, scene, plugins, a run directory that
// may not be replaced) throw before anything is written; from then on nothing is thrown: any
// failure or interrupt returns complete = false with everything recorded so far kept and
// summary.json saying so (or summary_error when even that could not be written).
RunResult RunExperiment(const ExperimentConfig& config, const RunOptions& options);

// The project's version string and MuJoCo's.
std::string VersionString();

}  // namespace mjf::runner

#endif  // MJFORMATION_RUN_RUN_HPP_
