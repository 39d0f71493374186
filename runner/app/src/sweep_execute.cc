// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The runs of a sweep, on worker threads or under mpirun on MPI ranks (sweep_mpi.h), and
// --resume: a run is done again only when it is missing or incomplete, recognised by the
// config hash in its summary.json.
#include <dlfcn.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <thread>

#include "mjformation/app/sweep_mpi.h"
#include "mjformation/config/paths.hpp"
#include "mjformation/record/output.hpp"
#include "mjformation/run/interrupt.hpp"
#include "mjformation/run/run.hpp"
#include "sweep.hpp"

namespace mjf::runner::sweep {

std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "";
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

namespace {

// --resume: a run counts as done when its summary.json is there, was written for the same
// configuration (config_sha256) and the run finished: complete, or stopped by its own failure
// (diverged, plugin error: rerunning gives the same), but not one that was interrupted.
bool FinishedBefore(const SweepPlan& plan, const RunSpec& run, RunOutcome* outcome) {
  const std::string text = ReadText(plan.out + "/" + run.name + "/summary.json");
  if (text.empty()) return false;
  Json summary;
  try {
    summary = Json::parse(text);
  } catch (const std::exception&) {
    return false;
  }
  if (!summary.contains("config_sha256") ||
      summary["config_sha256"] != Sha256Hex(ConfigEcho(run.config)) ||
      !summary.contains("complete") || !summary["complete"].is_boolean()) {
    return false;
  }
  const bool complete = summary["complete"].get<bool>();
  const std::string error = summary.contains("error") && summary["error"].is_string()
                                ? summary["error"].get<std::string>()
                                : "";
  if (!complete && (error.empty() || error.find("nterrupt") != std::string::npos ||
                    error.find("signal") != std::string::npos)) {
    return false;
  }
  outcome->state = RunOutcome::kFinished;
  outcome->error = complete ? "" : (error.empty() ? "incomplete" : error);
  outcome->summary = std::move(summary);
  return true;
}

ExperimentConfig WithThreads(ExperimentConfig config, int threads) {
  config.threads = threads;
  return config;
}

// `max_threads`: the physics partitions one run may use ([run] threads above it is lowered to
// it: the results are the same bit for bit, docs/PERFORMANCE.md).
RunOutcome ExecuteRun(const SweepPlan& plan, const RunSpec& run, bool render,
                      int max_threads = 1 << 30) {
  RunOutcome outcome;
  RunOptions options;
  options.out_dir = plan.out + "/" + run.name;
  options.overwrite = true;  // the sweep directory was checked (or is being resumed)
  options.render = render;
  try {
    const RunResult r = run.config.threads <= max_threads
                            ? RunExperiment(run.config, options)
                            : RunExperiment(WithThreads(run.config, max_threads), options);
    outcome.summary = r.summary;
    if (!r.complete) outcome.error = r.error.empty() ? "incomplete" : r.error;
  } catch (const std::exception& e) {
    outcome.error = e.what();
  }
  // A run cut short by Ctrl-C / SIGTERM / SIGHUP is not finished: --resume runs it again.
  outcome.state =
      !outcome.error.empty() && InterruptRequested() ? RunOutcome::kNotRun : RunOutcome::kFinished;
  return outcome;
}

// Outcome <-> text, for MPI messages: the summary's numbers survive the round trip exactly
// (nlohmann prints the shortest text that reads back to the same double).
std::string OutcomeText(const RunOutcome& o) {
  return Json{
      {"finished", o.state == RunOutcome::kFinished}, {"summary", o.summary}, {"error", o.error}}
      .dump();
}
RunOutcome OutcomeFromText(const std::string& text) {
  RunOutcome o;
  const Json j = Json::parse(text);
  o.state = j["finished"].get<bool>() ? RunOutcome::kFinished : RunOutcome::kNotRun;
  o.summary = j["summary"];
  o.error = j["error"].get<std::string>();
  return o;
}

}  // namespace

namespace {

namespace fs = std::filesystem;

// Written first into every sweep directory: what --overwrite and --resume check before they
// touch a folder (as .mjformation-run guards a run directory).
constexpr const char* kSweepMarker = ".mjformation-sweep";

// The sweep's own files: its marker, its tables, and leftovers of an interrupted atomic write.
bool IsSweepFile(const fs::directory_entry& e) {
  const std::string name = e.path().filename().string();
  if (e.is_symlink() || !e.is_regular_file()) return false;
  return name == kSweepMarker || name == "sweep.csv" || name == "sweep.json" ||
         name == "sweep_runs.csv" ||
         (name.size() > 4 && name.compare(name.size() - 4, 4, ".tmp") == 0);
}

// A run folder cut before its marker was written: empty, or only an empty snapshots/.
bool IsUnmarkedRunStart(const fs::path& dir) {
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.path().filename() != "snapshots" || e.is_symlink() || !e.is_directory() ||
        !fs::is_empty(e.path())) {
      return false;
    }
  }
  return true;
}

// Throws OutputError (nothing touched) unless `out` is a sweep directory holding nothing but
// what a sweep wrote: the marker, the tables and run directories that hold only a run's files.
void CheckSweepDirectory(const std::string& out, const char* flag) {
  const fs::path marker = fs::path(out) / kSweepMarker;
  if (fs::is_symlink(marker) || !fs::is_regular_file(marker)) {
    throw OutputError(out + ": not a mjformation sweep directory (no " + kSweepMarker +
                      " marker): " + flag +
                      " touches only sweep directories; nothing was deleted or written. Choose "
                      "another --out.");
  }
  std::string foreign;
  for (const auto& e : fs::directory_iterator(out)) {
    if (IsSweepFile(e)) continue;
    if (!e.is_symlink() && e.is_directory()) {
      if (IsUnmarkedRunStart(e.path())) continue;
      try {
        CheckRunDirectory(e.path().string());
        continue;
      } catch (const OutputError& why) {
        throw OutputError(out + ": " + flag +
                          " refused, nothing was deleted or written: " + why.what());
      }
    }
    foreign += (foreign.empty() ? "" : ", ") + e.path().filename().string();
  }
  if (!foreign.empty()) {
    throw OutputError(out + ": holds files a sweep did not write (" + foreign + "); " + flag +
                      " touches only a sweep's own files, so nothing was deleted or written. Move "
                      "them or choose another --out.");
  }
}

// Creates the sweep directory, or checks an existing one (and with --overwrite empties it).
void PrepareSweepDirectory(const std::string& out, const CliCommands& c) {
  std::error_code ec;
  if (fs::exists(out, ec) && !fs::is_directory(out, ec)) {
    throw OutputError(out + ": exists and is not a directory; choose another --out");
  }
  if (fs::exists(out, ec) && !fs::is_empty(out, ec)) {
    if (!c.overwrite && !c.sweep_resume) {
      throw OutputError(out +
                        ": the sweep directory exists and is not empty; choose another --out, "
                        "pass --resume to finish it or --overwrite to replace it");
    }
    CheckSweepDirectory(out, c.sweep_resume ? "--resume" : "--overwrite");
    if (!c.sweep_resume) {
      // remove_all removes a symbolic link itself, never what it points to.
      std::vector<fs::path> entries;
      for (const auto& e : fs::directory_iterator(out)) entries.push_back(e.path());
      for (const fs::path& e : entries) {
        if (e.filename() != kSweepMarker) fs::remove_all(e, ec);
        if (ec) throw OutputError(e.string() + ": cannot remove: " + ec.message());
      }
    }
  }
  fs::create_directories(out, ec);
  if (ec) throw OutputError(out + ": cannot create directory: " + ec.message());
  if (access(out.c_str(), W_OK) != 0) {
    throw OutputError(out + ": cannot write to the sweep directory");
  }
  if (!fs::exists(fs::path(out) / kSweepMarker)) {
    WriteTextFile(out + "/" + kSweepMarker,
                  "This folder is a mjformation sweep directory; `mjformation sweep --overwrite`\n"
                  "may replace it. Delete this file to protect the folder from that.\n");
  }
}

}  // namespace

std::vector<size_t> PrepareOutput(const SweepPlan& plan, const CliCommands& c,
                                  std::vector<RunOutcome>* outcomes) {
  PrepareSweepDirectory(plan.out, c);
  outcomes->assign(plan.runs.size(), RunOutcome{});
  std::vector<size_t> todo;
  for (size_t i = 0; i < plan.runs.size(); ++i) {
    if (!(c.sweep_resume && FinishedBefore(plan, plan.runs[i], &(*outcomes)[i]))) {
      todo.push_back(i);
    }
  }
  if (c.sweep_resume) {
    std::fprintf(stderr, "sweep: resuming, %zu of %zu runs done before\n",
                 plan.runs.size() - todo.size(), plan.runs.size());
  }
  return todo;
}

namespace {
// "42 s", "3 min 05 s", "2 h 07 min": the progress line's times.
std::string Duration(double seconds) {
  const auto s = static_cast<int64_t>(std::llround(std::max(0.0, seconds)));
  if (s < 60) return fmt::format("{} s", s);
  if (s < 3600) return fmt::format("{} min {:02d} s", s / 60, s % 60);
  return fmt::format("{} h {:02d} min", s / 3600, (s % 3600) / 60);
}
}  // namespace

void Progress::Done(size_t i, RunOutcome outcome) {
  std::lock_guard<std::mutex> lock(mutex_);
  (*outcomes_)[i] = std::move(outcome);
  const RunOutcome& o = (*outcomes_)[i];
  const auto now = std::chrono::steady_clock::now();
  ++done_;
  // ETA from the mean wall time per finished run so far (runs of a sweep cost about the same;
  // with -j K they finish K at a time, which the mean over elapsed time already reflects).
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double eta = elapsed / static_cast<double>(done_) * static_cast<double>(todo_ - done_);
  std::fprintf(stderr, "  [%zu/%zu] %s%s%s\n", done_, todo_, plan_.runs[i].name.c_str(),
               o.complete() ? "" : (": " + o.error).c_str(),
               done_ < todo_
                   ? fmt::format(" (elapsed {}, ETA {})", Duration(elapsed), Duration(eta)).c_str()
                   : fmt::format(" (done in {})", Duration(elapsed)).c_str());
  if (now - last_write_ > std::chrono::seconds(1)) {
    WriteTables(plan_, *outcomes_);
    last_write_ = now;
  }
}

// -j runs at once, each with up to `threads` physics partitions: the runs keep the cores they
// asked for (-j is the cheaper parallelism: runs share nothing), the partitions get what is left,
// so runs x partitions never exceeds the machine's cores (and at least one partition per run).
int ThreadsPerRun(const SweepPlan& plan, int jobs) {
  int asked = 1;
  for (const RunSpec& r : plan.runs) asked = std::max(asked, r.config.threads);
  const int cores = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  const int per_run = std::max(1, cores / jobs);
  if (asked > per_run) {
    std::fprintf(stderr,
                 "sweep: [run] threads = %d lowered to %d per run (%d at a time on %d cores; same "
                 "results)\n",
                 asked, per_run, jobs, cores);
  }
  return per_run;
}

void RunThreaded(const SweepPlan& plan, const CliCommands& c, const std::vector<size_t>& todo,
                 Progress* progress) {
  const int jobs = std::max(1, std::min<int>(c.sweep_jobs, static_cast<int>(todo.size())));
  std::fprintf(stderr, "sweep: %s, %d at a time, into %s\n", RunCount(todo.size()).c_str(), jobs,
               plan.out.c_str());
  const int max_threads = ThreadsPerRun(plan, jobs);
  std::atomic<size_t> next{0};
  auto worker = [&] {
    for (size_t k; !InterruptRequested() && (k = next++) < todo.size();) {
      progress->Done(todo[k], ExecuteRun(plan, plan.runs[todo[k]], !c.no_render, max_threads));
    }
  };
  std::vector<std::thread> threads;
  for (int j = 0; j < jobs; ++j) threads.emplace_back(worker);
  for (auto& t : threads) t.join();
}

// ---- MPI: the transport lives in libmjf_sweep_mpi.so, loaded only under mpirun ----

bool UnderMpiLauncher() {
  for (const char* var : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MPI_LOCALNRANKS"}) {
    if (std::getenv(var)) return true;
  }
  return false;
}

namespace {

// The first of MpiModuleSearchPath() that loads.
void* LoadMpiModule(std::string* tried) {
  for (const auto& path : MpiModuleSearchPath()) {
    // RTLD_GLOBAL: Open MPI's own components, loaded later, resolve their symbols against libmpi.
    if (void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_GLOBAL)) return handle;
    *tried += "\n  " + path + ": " + dlerror();
  }
  return nullptr;
}

struct MpiContext {
  const SweepPlan* plan;
  const CliCommands* c;
  std::vector<RunOutcome>* outcomes;
  std::unique_ptr<Progress> progress;
  std::vector<int> todo;
  std::string last;  // the text `run` returned last
};

}  // namespace

int RunMpi(const SweepPlan& plan, const CliCommands& c, std::vector<RunOutcome>* outcomes) {
  std::string tried;
  void* module = LoadMpiModule(&tried);
  if (!module) {
    throw ConfigError(
        "sweep: started by an MPI launcher, but the MPI transport libmjf_sweep_mpi.so cannot be "
        "loaded (build with libopenmpi-dev installed: scripts/setup.sh); tried:" +
        tried);
  }
  auto sweep_fn = reinterpret_cast<mjfMpiSweepFn>(dlsym(module, "mjf_mpi_sweep"));
  if (!sweep_fn) throw ConfigError("sweep: libmjf_sweep_mpi.so lacks mjf_mpi_sweep");
  MpiContext ctx{&plan, &c, outcomes, nullptr, {}, {}};
  mjfMpiSweep s{};
  s.user = &ctx;
  s.prepare = [](void* user, const int** todo, int* n, char* error, int size) -> int {
    auto* x = static_cast<MpiContext*>(user);
    try {
      for (size_t i : PrepareOutput(*x->plan, *x->c, x->outcomes)) {
        x->todo.push_back(static_cast<int>(i));
      }
    } catch (const std::exception& e) {
      std::snprintf(error, size, "%s", e.what());
      return 1;
    }
    x->progress = std::make_unique<Progress>(*x->plan, x->outcomes, x->todo.size());
    *todo = x->todo.data();
    *n = static_cast<int>(x->todo.size());
    return 0;
  };
  s.run = [](void* user, int index) -> const char* {
    auto* x = static_cast<MpiContext*>(user);
    x->last = OutcomeText(ExecuteRun(*x->plan, x->plan->runs[index], !x->c->no_render));
    return x->last.c_str();
  };
  s.collect = [](void* user, int index, const char* text) {
    auto* x = static_cast<MpiContext*>(user);
    x->progress->Done(index, OutcomeFromText(text));
  };
  s.stop_requested = [](void*) -> int { return InterruptRequested(); };
  int rank = 0, size = 0;
  char error[2048] = {0};
  const int rc = sweep_fn(&s, &rank, &size, error, sizeof(error));
  if (rc != 0)
    throw OutputError(std::string("sweep (MPI rank ") + std::to_string(rank) + "): " + error);
  if (rank == 0) {
    std::fprintf(stderr, "sweep: %s over %d MPI ranks\n", RunCount(ctx.todo.size()).c_str(), size);
  }
  return rank;
}

}  // namespace mjf::runner::sweep
