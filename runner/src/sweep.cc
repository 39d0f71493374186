// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// `mjformation sweep`: runs an experiment over the Cartesian product of parameter values and,
// with --seeds N, N seeds per grid cell (Monte Carlo); one run directory per run; the tables
// sweep.csv / sweep.json (per run, or with --seeds per cell: mean, standard deviation and 95 %
// Student-t confidence interval of every metric, the runs in sweep_runs.csv).
// Runs go to worker threads, or under mpirun to MPI ranks (sweep_mpi.h). The tables are written
// atomically (temporary file + rename) and carry a completeness flag: an interrupted sweep keeps
// its finished runs and marks the others "not run"; --resume reruns only runs that are missing
// or incomplete, recognised by the config hash in their summary.json.
#include <dlfcn.h>
#include <fmt/format.h>
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <thread>

#include "mjformation/runner/cli.hpp"
#include "mjformation/runner/interrupt.hpp"
#include "mjformation/runner/output.hpp"
#include "mjformation/runner/run.hpp"
#include "mjformation/runner/sweep_mpi.h"
#include "mjformation/runner/sweep_stats.hpp"

namespace mjf::runner {
namespace {

using Json = nlohmann::ordered_json;

struct Axis {
  std::string key;                  // section.key
  std::vector<std::string> values;  // TOML values
};

// "formation.q=1,2.5,4.5" -> {formation.q, [1, 2.5, 4.5]}. Commas inside [], {} or quotes do
// not split: "wind.mean=[3,0,0],[6,0,0]" or "sensors={preset=\"typical\", scale=3.0},{...}".
Axis ParseAxis(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size()) {
    throw ConfigError("--vary '" + text + "': expected section.key=v1,v2,...");
  }
  Axis axis{text.substr(0, eq), {}};
  const std::string rest = text.substr(eq + 1);
  int depth = 0;
  bool quoted = false;
  std::string value;
  for (size_t i = 0; i <= rest.size(); ++i) {
    const char ch = i < rest.size() ? rest[i] : ',';
    if (ch == '"') quoted = !quoted;
    if (!quoted && (ch == '[' || ch == '{')) ++depth;
    if (!quoted && (ch == ']' || ch == '}')) --depth;
    if (ch == ',' && depth == 0 && !quoted) {
      if (value.empty()) throw ConfigError("--vary '" + text + "': empty value");
      axis.values.push_back(value);
      value.clear();
    } else {
      value += ch;
    }
  }
  if (depth != 0 || quoted) throw ConfigError("--vary '" + text + "': unbalanced [ { or \"");
  return axis;
}

// A CSV field: as is, or quoted (RFC 4180) when it holds a comma, quote or newline.
std::string CsvField(const std::string& v) {
  if (v.find_first_of(",\"\n") == std::string::npos) return v;
  std::string out = "\"";
  for (char ch : v) out += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return out + "\"";
}

// A name for a point's run directory: key values joined, safe for a file name.
std::string PointName(const std::vector<Axis>& axes, const std::vector<size_t>& index) {
  std::string name;
  for (size_t a = 0; a < axes.size(); ++a) {
    std::string key = axes[a].key.substr(axes[a].key.rfind('.') + 1);
    name += (a ? "_" : "") + key + "=" + axes[a].values[index[a]];
  }
  for (char& c : name) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '=' || c == '.' || c == '-' ||
          c == '_')) {
      c = '_';
    }
  }
  return name;
}

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

// Every run's configuration, parsed and checked before anything runs.
SweepPlan PlanSweep(const CliCommands& c) {
  SweepPlan plan;
  for (const auto& v : c.sweep_vary) plan.axes.push_back(ParseAxis(v));
  if (c.sweep_seeds < 0 || (c.sweep->count("--seeds") && c.sweep_seeds == 0)) {
    throw ConfigError("sweep: --seeds must be >= 1 (seeds per grid cell)");
  }
  plan.seeds = c.sweep_seeds;
  if (plan.axes.empty() && plan.seeds == 0) {
    throw ConfigError("sweep: give --vary section.key=v1,v2,... and/or --seeds N");
  }
  plan.cells.assign(1, {});
  for (const Axis& axis : plan.axes) {
    std::vector<std::vector<size_t>> next;
    for (const auto& p : plan.cells) {
      for (size_t k = 0; k < axis.values.size(); ++k) {
        next.push_back(p);
        next.back().push_back(k);
      }
    }
    plan.cells = std::move(next);
  }
  for (size_t cell = 0; cell < plan.cells.size(); ++cell) {
    std::vector<std::string> overrides = c.overrides;
    for (size_t a = 0; a < plan.axes.size(); ++a) {
      overrides.push_back(plan.axes[a].key + "=" + plan.axes[a].values[plan.cells[cell][a]]);
    }
    ExperimentConfig base = LoadExperiment(c.experiment, overrides);
    const std::string point = PointName(plan.axes, plan.cells[cell]);
    for (int k = 0; k < std::max(1, plan.seeds); ++k) {
      RunSpec run;
      run.cell = cell;
      run.seed = base.seed + k;  // recorded in the run's config.toml and summary.json
      if (plan.seeds == 0) {
        run.config = base;
        run.name = point;
      } else {
        std::vector<std::string> seeded = overrides;
        seeded.push_back("run.seed=" + std::to_string(run.seed));
        run.config = LoadExperiment(c.experiment, seeded);
        run.name = (point.empty() ? "" : point + "_") + "seed=" + std::to_string(run.seed);
      }
      for (const auto& path : c.plugin_path) run.config.plugin_path.push_back(path);
      plan.runs.push_back(std::move(run));
    }
  }
  std::set<std::string> names;
  for (const RunSpec& run : plan.runs) {
    if (!names.insert(run.name).second) {
      throw ConfigError("sweep: two runs would share the directory '" + run.name +
                        "' (values that differ only in punctuation); write them apart");
    }
  }
  plan.out = c.out.empty() ? "runs/" + plan.runs.front().config.name + "_sweep" : c.out;
  return plan;
}

std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "";
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

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
  // A run cut short by Ctrl-C / SIGTERM is not finished: --resume runs it again.
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

const char* const kMainMetrics[] = {
    "sigma_f_mean",    "sigma_f_final",     "max_final_slot_error_m",         "min_separation_m",
    "reaching_time_s", "saturation_time_s", "max_follower_tilt_deg_in_window"};

std::string MetricText(const Json& s, const std::string& key) {
  if (!s.is_object() || !s.contains("metrics") || !s["metrics"].contains(key) ||
      !s["metrics"][key].is_number()) {
    return "";
  }
  return fmt::format("{:.6g}", s["metrics"][key].get<double>());
}

std::string CsvSafe(std::string text) {
  for (char& ch : text) {
    if (ch == ',' || ch == '\n') ch = ';';
  }
  return text;
}

std::string NumberText(double v) { return std::isfinite(v) ? fmt::format("{:.6g}", v) : ""; }

std::string RunStatus(const RunOutcome& o) {
  return o.state == RunOutcome::kNotRun ? "not run (sweep interrupted)" : CsvSafe(o.error);
}

// Per-run table: one row per run in plan order (whatever the completion order).
std::string RunsCsv(const SweepPlan& plan, const std::vector<RunOutcome>& outcomes) {
  std::string csv;
  for (const Axis& axis : plan.axes) csv += axis.key + ",";
  if (plan.seeds) csv += "seed,";
  csv += "complete";
  for (const char* m : kMainMetrics) csv += std::string(",") + m;
  csv += ",run,error\n";
  for (size_t i = 0; i < plan.runs.size(); ++i) {
    const RunSpec& run = plan.runs[i];
    for (size_t a = 0; a < plan.axes.size(); ++a) {
      csv += CsvField(plan.axes[a].values[plan.cells[run.cell][a]]) + ",";
    }
    if (plan.seeds) csv += std::to_string(run.seed) + ",";
    csv += outcomes[i].complete() ? "true" : "false";
    for (const char* m : kMainMetrics) csv += "," + MetricText(outcomes[i].summary, m);
    csv += "," + run.name + "," + (outcomes[i].complete() ? "" : RunStatus(outcomes[i])) + "\n";
  }
  return csv;
}

// Every scalar numeric metric any run reported, in order of first appearance (plan order).
std::vector<std::string> MetricKeys(const std::vector<RunOutcome>& outcomes) {
  std::vector<std::string> keys;
  for (const RunOutcome& o : outcomes) {
    if (!o.summary.is_object() || !o.summary.contains("metrics")) continue;
    for (const auto& [k, v] : o.summary["metrics"].items()) {
      if (v.is_number() && std::find(keys.begin(), keys.end(), k) == keys.end()) keys.push_back(k);
    }
  }
  return keys;
}

// Per-cell statistics over the complete runs of the cell.
std::vector<std::vector<SampleStats>> CellStats(const SweepPlan& plan,
                                                const std::vector<RunOutcome>& outcomes,
                                                const std::vector<std::string>& keys,
                                                std::vector<int>* completed) {
  std::vector<std::vector<std::vector<double>>> samples(
      plan.cells.size(), std::vector<std::vector<double>>(keys.size()));
  completed->assign(plan.cells.size(), 0);
  for (size_t i = 0; i < plan.runs.size(); ++i) {
    if (!outcomes[i].complete()) continue;
    const size_t cell = plan.runs[i].cell;
    ++(*completed)[cell];
    const Json& metrics = outcomes[i].summary["metrics"];
    for (size_t k = 0; k < keys.size(); ++k) {
      if (metrics.contains(keys[k]) && metrics[keys[k]].is_number()) {
        samples[cell][k].push_back(metrics[keys[k]].get<double>());
      }
    }
  }
  std::vector<std::vector<SampleStats>> stats(plan.cells.size());
  for (size_t cell = 0; cell < plan.cells.size(); ++cell) {
    for (const auto& s : samples[cell]) stats[cell].push_back(Describe(s));
  }
  return stats;
}

void WriteAtomic(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) throw OutputError(tmp + ": cannot write: " + std::strerror(errno));
  const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  if (std::fclose(f) != 0 || !ok || std::rename(tmp.c_str(), path.c_str()) != 0) {
    throw OutputError(path + ": cannot write: " + std::strerror(errno));
  }
}

// sweep.csv, sweep.json (and sweep_runs.csv with --seeds). `complete`: every run finished.
void WriteTables(const SweepPlan& plan, const std::vector<RunOutcome>& outcomes) {
  bool complete = true;
  Json runs = Json::array();
  for (size_t i = 0; i < plan.runs.size(); ++i) {
    const RunSpec& run = plan.runs[i];
    const RunOutcome& o = outcomes[i];
    complete = complete && o.state == RunOutcome::kFinished;
    Json entry;
    for (size_t a = 0; a < plan.axes.size(); ++a) {
      entry[plan.axes[a].key] = plan.axes[a].values[plan.cells[run.cell][a]];
    }
    if (plan.seeds) entry["seed"] = run.seed;
    entry["complete"] = o.complete();
    entry["finished"] = o.state == RunOutcome::kFinished;
    entry["run"] = run.name;
    entry["error"] = o.complete() ? Json(nullptr) : Json(RunStatus(o));
    entry["metrics"] = o.summary.is_object() && o.summary.contains("metrics") ? o.summary["metrics"]
                                                                              : Json(nullptr);
    runs.push_back(entry);
  }
  Json table = {{"complete", complete}, {"seeds", plan.seeds}, {"runs", runs}};
  const std::string runs_csv = RunsCsv(plan, outcomes);
  if (!plan.seeds) {
    WriteAtomic(plan.out + "/sweep.csv", runs_csv);
  } else {
    const std::vector<std::string> keys = MetricKeys(outcomes);
    std::vector<int> completed;
    const auto stats = CellStats(plan, outcomes, keys, &completed);
    std::string csv;
    for (const Axis& axis : plan.axes) csv += axis.key + ",";
    csv += "seeds,complete_runs";
    for (const auto& k : keys) {
      csv += fmt::format(",{0}_mean,{0}_std,{0}_ci95_low,{0}_ci95_high", k);
    }
    csv += "\n";
    Json cells = Json::array();
    for (size_t cell = 0; cell < plan.cells.size(); ++cell) {
      Json entry;
      for (size_t a = 0; a < plan.axes.size(); ++a) {
        csv += CsvField(plan.axes[a].values[plan.cells[cell][a]]) + ",";
        entry[plan.axes[a].key] = plan.axes[a].values[plan.cells[cell][a]];
      }
      csv += fmt::format("{},{}", plan.seeds, completed[cell]);
      entry["seeds"] = plan.seeds;
      entry["complete_runs"] = completed[cell];
      Json metrics = Json::object();
      for (size_t k = 0; k < keys.size(); ++k) {
        const SampleStats& s = stats[cell][k];
        csv += "," + NumberText(s.mean) + "," + NumberText(s.std) + "," + NumberText(s.ci95_low) +
               "," + NumberText(s.ci95_high);
        metrics[keys[k]] = {{"n", s.n},
                            {"mean", JsonNumber(s.mean)},
                            {"std", JsonNumber(s.std)},
                            {"ci95", {JsonNumber(s.ci95_low), JsonNumber(s.ci95_high)}}};
      }
      csv += "\n";
      entry["metrics"] = metrics;
      cells.push_back(entry);
    }
    table["cells"] = cells;
    WriteAtomic(plan.out + "/sweep_runs.csv", runs_csv);
    WriteAtomic(plan.out + "/sweep.csv", csv);
  }
  WriteAtomic(plan.out + "/sweep.json", table.dump(2) + "\n");
}

// Creates the sweep directory (or checks it for --resume) and lists the runs still to do; the
// others' outcomes are filled from their run directories.
std::vector<size_t> PrepareOutput(const SweepPlan& plan, const CliCommands& c,
                                  std::vector<RunOutcome>* outcomes) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const bool exists = fs::exists(plan.out, ec) && !fs::is_empty(plan.out, ec);
  if (exists && !c.sweep_resume) {
    if (!c.overwrite) {
      throw OutputError(plan.out +
                        ": the sweep directory exists and is not empty; choose another --out, "
                        "pass --resume to finish it or --overwrite to replace it");
    }
    fs::remove_all(plan.out, ec);
    if (ec) throw OutputError(plan.out + ": cannot remove: " + ec.message());
  }
  fs::create_directories(plan.out, ec);
  if (ec) throw OutputError(plan.out + ": cannot create directory: " + ec.message());
  if (access(plan.out.c_str(), W_OK) != 0) {
    throw OutputError(plan.out + ": cannot write to the sweep directory");
  }
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

// Keeps the tables current while runs finish, at most once a second, so a sweep that dies
// leaves tables marked incomplete rather than none (the final write comes after all runs).
class Progress {
 public:
  Progress(const SweepPlan& plan, std::vector<RunOutcome>* outcomes, size_t todo)
      : plan_(plan), outcomes_(outcomes), todo_(todo) {}
  void Done(size_t i, RunOutcome outcome) {
    std::lock_guard<std::mutex> lock(mutex_);
    (*outcomes_)[i] = std::move(outcome);
    const RunOutcome& o = (*outcomes_)[i];
    std::fprintf(stderr, "  [%zu/%zu] %s%s\n", ++done_, todo_, plan_.runs[i].name.c_str(),
                 o.complete() ? "" : (": " + o.error).c_str());
    const auto now = std::chrono::steady_clock::now();
    if (now - last_write_ > std::chrono::seconds(1)) {
      WriteTables(plan_, *outcomes_);
      last_write_ = now;
    }
  }

 private:
  const SweepPlan& plan_;
  std::vector<RunOutcome>* outcomes_;
  size_t todo_, done_ = 0;
  std::mutex mutex_;
  std::chrono::steady_clock::time_point last_write_ = std::chrono::steady_clock::now();
};

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
  std::fprintf(stderr, "sweep: %zu runs, %d at a time, into %s\n", todo.size(), jobs,
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

// ---- MPI (issue 11): the transport lives in libmjf_sweep_mpi.so, loaded only under mpirun ----

bool UnderMpiLauncher() {
  for (const char* var : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MPI_LOCALNRANKS"}) {
    if (std::getenv(var)) return true;
  }
  return false;
}

// $MJF_MPI_MODULE, else the build tree's, else the installed one.
void* LoadMpiModule(std::string* tried) {
  std::vector<std::string> candidates;
  if (const char* env = std::getenv("MJF_MPI_MODULE")) candidates.push_back(env);
  candidates.push_back(MJF_MPI_MODULE_BUILD_PATH);
  candidates.push_back(MJF_MPI_MODULE_INSTALL_PATH);
  for (const auto& path : candidates) {
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
    std::fprintf(stderr, "sweep: %zu runs over %d MPI ranks\n", ctx.todo.size(), size);
  }
  return rank;
}

}  // namespace

int SweepCommand(const CliCommands& c) {
  InstallInterruptHandlers();
  const SweepPlan plan = PlanSweep(c);
  std::vector<RunOutcome> outcomes;
  if (UnderMpiLauncher()) {
    if (RunMpi(plan, c, &outcomes) != 0) return 0;  // worker ranks: rank 0 writes the tables
  } else {
    const std::vector<size_t> todo = PrepareOutput(plan, c, &outcomes);
    Progress progress(plan, &outcomes, todo.size());
    RunThreaded(plan, c, todo, &progress);
  }
  WriteTables(plan, outcomes);
  int failures = 0, not_run = 0;
  for (const RunOutcome& o : outcomes) {
    failures += o.state == RunOutcome::kFinished && !o.complete();
    not_run += o.state == RunOutcome::kNotRun;
  }
  std::printf("%s", ReadText(plan.out + "/sweep.csv").c_str());
  std::fprintf(
      stderr, "sweep: table in %s/sweep.csv%s%s\n", plan.out.c_str(),
      failures ? fmt::format(" ({} runs failed or stopped early)", failures).c_str() : "",
      not_run ? fmt::format("; interrupted: {} runs not run, finish with --resume", not_run).c_str()
              : "");
  if (not_run) return InterruptRequested() ? InterruptExitCode() : 3;
  return failures ? 3 : 0;
}

void AddSweepCommand(CLI::App& app, CliCommands* c) {
  c->sweep = app.add_subcommand(
      "sweep", "Run an experiment over a grid of parameter values and seeds, several at once");
  c->sweep->add_option("experiment", c->experiment, "experiment file (TOML)")->required();
  c->sweep
      ->add_option("--vary", c->sweep_vary,
                   "a swept parameter: section.key=v1,v2,... (repeat for a grid)")
      ->allow_extra_args(false);
  c->sweep->add_option("--seeds", c->sweep_seeds,
                       "Monte Carlo: N runs per grid cell with seeds run.seed + 0..N-1; "
                       "sweep.csv then holds per cell mean, std and 95 % CI of every metric");
  c->sweep->add_option("--set", c->overrides, "fixed override: section.key=value");
  c->sweep->add_option("--out,-o", c->out, "sweep directory (default: runs/<run.name>_sweep)");
  c->sweep->add_option("--jobs,-j", c->sweep_jobs, "simulations at once (threads)")
      ->capture_default_str();
  c->sweep->add_option("--plugin-path", c->plugin_path, "extra folder to search for plugins");
  c->sweep->add_flag("--overwrite", c->overwrite, "replace an existing sweep directory");
  c->sweep->add_flag("--resume", c->sweep_resume,
                     "finish an interrupted sweep: rerun only runs missing or incomplete");
  c->sweep->add_flag("--no-render", c->no_render, "skip snapshots and video");
}

}  // namespace mjf::runner
