// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// What a run keeps, behind one interface: the time series (timeseries.csv), snapshots (PNG) and
// video (mp4). The step loop samples the formation metrics (OnlineMetrics: sigma_f, slots) on
// the steps some recorder wants and hands every recorder that wants it the same frame. A new
// output is one new Recorder, added in MakeRecorders.
#ifndef MJFORMATION_RECORD_RECORDERS_HPP_
#define MJFORMATION_RECORD_RECORDERS_HPP_

#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mjformation/config/experiment.hpp"
#include "mjformation/config/state_archive.hpp"

namespace mjf::runner {

class Simulation;
class RunDirectory;

// One sampled step: the simulation after ComputeControls, and the formation metrics of it.
struct Frame {
  const Simulation& sim;
  int64_t step;
  double sigma_f;                    // NaN without a formation
  const std::vector<double>& slots;  // [2 * vehicle]: desired x, y
};

class Recorder {
 public:
  virtual ~Recorder() = default;
  // Every step, after the controls are computed (cheap bookkeeping only).
  virtual void OnStep(const Simulation& sim) { (void)sim; }
  // True when this recorder needs the frame of `step`.
  virtual bool Wants(int64_t step) const = 0;
  virtual void Record(const Frame& frame) = 0;
  // Flushes and closes; throws (OutputError, std::runtime_error) when that fails. Never called
  // twice; destructors release quietly and never throw.
  virtual void Finish() {}
  // Adds what it wrote to summary.json (e.g. the snapshot files).
  virtual void Summarize(nlohmann::ordered_json* summary) const { (void)summary; }
  // What it carries from one step to the next (accumulators, the length of its file), both
  // ways, for checkpoints (run --checkpoint-every, --resume). Loading touches no file (a
  // checkpoint that fails further on leaves the run directory as it was). A recorder that
  // cannot be saved throws; the run refuses it at startup.
  virtual void VisitState(StateArchive& archive);
  // After a checkpoint was loaded whole: continues the files from where it left them (a file is
  // cut back to the length it recorded).
  virtual void ResumeFiles() {}
};

struct RecorderOptions {
  bool record = true;   // timeseries.csv
  bool render = true;   // snapshots and video as configured
  bool resume = false;  // continue the files of a checkpointed run (VisitState then loads)
};

// The recorders the experiment asks for, writing into `dir` (none when dir is null).
std::vector<std::unique_ptr<Recorder>> MakeRecorders(const Simulation& sim, const RunDirectory* dir,
                                                     const RecorderOptions& options);

// Each vehicle's bounding radius about its body origin (the safety monitor's collision radii),
// from the model's geometry.
std::vector<double> VehicleRadii(const Simulation& sim);

}  // namespace mjf::runner

#endif  // MJFORMATION_RECORD_RECORDERS_HPP_
