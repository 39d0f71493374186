// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// One run end to end, with one failure contract (docs/ARCHITECTURE.md, "Failure contract"):
// input errors throw before the run directory exists; from then on nothing escapes: an
// exception, an engine error, a plugin failure or a signal ends the run with everything recorded
// kept and summary.json saying complete = false, why, and the simulated time reached.
#include "mjformation/run/run.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <memory>
#include <optional>

#include "mjformation/config/config_error.hpp"
#include "mjformation/record/engine_identity.hpp"
#include "mjformation/record/metrics.hpp"
#include "mjformation/record/output.hpp"
#include "mjformation/record/recorders.hpp"
#include "mjformation/render.hpp"
#include "mjformation/run/checkpoint.hpp"
#include "mjformation/run/interrupt.hpp"
#include "mjformation/run/summary.hpp"
#include "mjformation/sim/simulation.hpp"
#include "mjformation/time_steps.hpp"

#ifndef MJF_VERSION
#define MJF_VERSION "0.0.0"
#endif

namespace mjf::runner {
namespace {

using Clock = std::chrono::steady_clock;

class ProgressLine {
 public:
  ProgressLine(bool enabled, std::string name, double duration)
      : enabled_(enabled && isatty(STDERR_FILENO)), name_(std::move(name)), duration_(duration) {}
  void Update(double t, double sigma_f, Clock::time_point start) {
    if (!enabled_) return;
    const auto now = Clock::now();
    if (now - last_ < std::chrono::milliseconds(250)) return;
    last_ = now;
    const double wall = std::chrono::duration<double>(now - start).count();
    std::fprintf(stderr, "\r[%s] t = %6.2f / %.2f s (%3.0f%%)  %6.1fx real time  sigma_f = %-9.4g",
                 name_.c_str(), t, duration_, 100.0 * t / duration_, wall > 0 ? t / wall : 0.0,
                 sigma_f);
    std::fflush(stderr);
  }
  void Finish() {
    if (enabled_) std::fprintf(stderr, "\n");
  }

 private:
  bool enabled_;
  std::string name_;
  double duration_;
  Clock::time_point last_{};
};

// A video is encoded by ffmpeg, started at the first frame: without it the run would stop
// there, its folder written and in the way of the next attempt.
void RequireVideoEncoder(const ExperimentConfig& config, const RunOptions& options) {
  if (options.out_dir.empty() || !options.render || !config.render.video) return;
  if (render::FfmpegPath().empty()) {
    throw ConfigError("[render] video = true: " + render::FfmpegMissing() +
                      " (render.video=false or --no-render)");
  }
}

std::string SignalName(int signal) {
  switch (signal) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    case SIGHUP:
      return "SIGHUP";
    default:
      return std::to_string(signal);
  }
}

// The step loop: controls, frames for the recorders that want them, integration. Throws
// whatever a step or a recorder throws; stops early (returns) on an interrupt request.
// A resumed run starts at its checkpoint's step; checkpoints are taken between steps, before
// the controls of the step they are due at.
void StepLoop(Simulation& sim, std::vector<std::unique_ptr<Recorder>>& recorders,
              OnlineMetrics& metrics, ProgressLine& progress, const CheckpointPlan& plan,
              RunResult* result) {
  const int64_t record_every = NearestSteps(1.0 / sim.config().record_rate, sim.config().timestep);
  std::vector<double> slots(2 * static_cast<size_t>(sim.n_vehicles()));
  const auto start = Clock::now();
  for (int64_t step = sim.step_index(); step <= sim.total_steps(); ++step) {
    if (InterruptRequested()) {
      result->signal = InterruptSignal();
      result->error = "interrupted by " + SignalName(result->signal);
      return;
    }
    KillPointForTests(step);
    if (CheckpointDue(plan, sim, step)) WriteCheckpoint(plan, sim, metrics, recorders);
    sim.ComputeControls();
    for (const auto& r : recorders) r->OnStep(sim);
    const bool record_tick = step % record_every == 0 || step == sim.total_steps();
    bool wanted = record_tick;
    for (const auto& r : recorders) wanted = wanted || r->Wants(step);
    if (wanted) {
      const double sigma_f = metrics.Sample(sim, &slots, record_tick);
      const Frame frame{sim, step, sigma_f, slots};
      for (const auto& r : recorders) {
        if (r->Wants(step)) r->Record(frame);
      }
      progress.Update(sim.time(), sigma_f, start);
    }
    metrics.StepControls(sim);
    if (step < sim.total_steps()) sim.Integrate();
  }
  result->complete = true;
}

// Runs `action`; an exception becomes the run's error (the first one is kept) and
// complete = false. Nothing escapes.
template <typename Action>
void Guarded(RunResult* result, Action action) {
  try {
    action();
  } catch (const std::exception& e) {
    if (result->error.empty()) result->error = e.what();
    result->complete = false;
  } catch (...) {
    if (result->error.empty()) result->error = "unknown exception";
    result->complete = false;
  }
}

// What a run records into: the online metrics and the recorders (made and loaded before the
// run directory is written to when the run resumes).
struct Recording {
  explicit Recording(const Simulation& sim) : metrics(sim) {}
  OnlineMetrics metrics;
  std::vector<std::unique_ptr<Recorder>> recorders;
};

// The recorders of a resumed run, with the checkpoint's metrics and recorder states loaded to
// its end. Throws (ConfigError: the checkpoint is not this run's) before any file is changed.
void LoadResumedRecording(const Simulation& sim, const RunDirectory* dir, const RunOptions& options,
                          const CheckpointPlan& plan, StateArchive& checkpoint,
                          Recording* recording) {
  recording->recorders = MakeRecorders(sim, dir, {options.record, options.render, true});
  ResumeRecording(plan, checkpoint, recording->metrics, recording->recorders);
}

// Everything after the run directory exists: recorders, steps, closing. Never throws.
void RunInDirectory(Simulation& sim, const RunDirectory* dir, const RunOptions& options,
                    const CheckpointPlan& plan, Recording& recording, RunResult* result,
                    nlohmann::ordered_json* recorder_summary) {
  auto& recorders = recording.recorders;
  OnlineMetrics& metrics = recording.metrics;
  ProgressLine progress(options.progress, sim.config().name, sim.config().duration);
  const auto start = Clock::now();
  Guarded(result, [&] {
    if (!plan.resume) recorders = MakeRecorders(sim, dir, {options.record, options.render, false});
    StepLoop(sim, recorders, metrics, progress, plan, result);
  });
  progress.Finish();
  result->wall_time_s = std::chrono::duration<double>(Clock::now() - start).count();
  result->sim_time_s = sim.time();
  result->steps = sim.step_index();
  // Each recorder is closed even when another failed: every row recorded is kept.
  for (auto& r : recorders) Guarded(result, [&] { r->Finish(); });
  for (const auto& r : recorders) r->Summarize(recorder_summary);
  (*recorder_summary)["metrics"] = metrics.Summary(sim);
}

// What --checkpoint-every and --resume ask for; refused before anything runs when a stage
// cannot be saved.
CheckpointPlan MakeCheckpointPlan(const Simulation& sim, const RunOptions& options) {
  CheckpointPlan plan{options.checkpoint_every, options.resume, "", ""};
  if (plan.every_s <= 0 && !plan.resume) return plan;
  if (options.out_dir.empty()) throw ConfigError("checkpoints need a run directory (--out)");
  RequireCheckpointable(sim, options.render);
  plan.path = options.out_dir + "/" + kCheckpointFile;
  plan.config_sha256 = Sha256Hex(ConfigEcho(sim.config()));
  return plan;
}

}  // namespace

std::string VersionString() {
  return fmt::format("mjformation {} (MuJoCo {}, plugin ABI {})", MJF_VERSION,
                     RunningEngine().version, MJF_ABI_VERSION);
}

RunResult RunExperiment(const ExperimentConfig& config, const RunOptions& options) {
  // Everything that can be wrong with the input fails here, before a file is written.
  RequireVideoEncoder(config, options);
  Simulation sim(config);
  if (options.warnings) {
    for (const auto& w : sim.warnings())
      std::fprintf(stderr, "mjformation: warning: %s\n", w.c_str());
  }
  const CheckpointPlan plan = MakeCheckpointPlan(sim, options);
  // A resume reads the whole checkpoint before anything is written: a checkpoint that is
  // damaged, foreign or not this run's changes nothing.
  std::optional<StateArchive> checkpoint;
  if (plan.resume) {
    checkpoint = ReadCheckpoint(plan);
    ResumeSimulation(plan, *checkpoint, sim);
  }
  std::unique_ptr<RunDirectory> dir;
  if (!options.out_dir.empty()) {
    dir = std::make_unique<RunDirectory>(options.out_dir, options.overwrite, options.resume);
  }
  Recording recording(sim);
  if (checkpoint) {
    LoadResumedRecording(sim, dir.get(), options, plan, *checkpoint, &recording);
    for (auto& r : recording.recorders) r->ResumeFiles();
  }
  RunResult result;
  nlohmann::ordered_json recorded = nlohmann::ordered_json::object();
  Guarded(&result, [&] {
    if (!dir) return;
    dir->WriteText("config.toml", ConfigEcho(config));
    dir->WriteText("scene.xml", sim.scene_xml());
  });
  if (result.error.empty()) {
    RunInDirectory(sim, dir.get(), options, plan, recording, &result, &recorded);
  }
  result.summary = BuildSummary(sim, result, recorded);
  try {
    if (dir) dir->WriteText("summary.json", result.summary.dump(2) + "\n");
  } catch (const std::exception& e) {
    result.summary_error = e.what();
    result.complete = false;
  }
  return result;
}

}  // namespace mjf::runner
