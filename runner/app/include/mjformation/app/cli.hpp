// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The command-line interface, as a library so tests drive exactly what users run.
#ifndef MJFORMATION_APP_CLI_HPP_
#define MJFORMATION_APP_CLI_HPP_

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace mjf::runner {

struct CliCommands {
  CLI::App* run = nullptr;
  CLI::App* check = nullptr;
  CLI::App* plugins = nullptr;
  CLI::App* bench = nullptr;
  CLI::App* sweep = nullptr;
  CLI::App* keys = nullptr;  // `keys [SECTION]`: the experiment file's key reference
  std::string keys_section;
  std::string experiment;
  std::string out;
  std::vector<std::string> overrides;
  std::vector<std::string> plugin_path;
  bool overwrite = false;
  bool no_render = false;
  bool quiet = false;
  int run_threads = 0;          // --threads (0: the file's [run] threads)
  double checkpoint_every = 0;  // --checkpoint-every S (0: none)
  bool resume = false;          // --resume
  // bench
  std::vector<int> bench_followers;
  double bench_duration = 0;
  std::string bench_json;
  bool bench_render = false;
  bool bench_memory = false;
  std::vector<int> bench_threads;  // --threads 1,2: time the full pipeline at each
  // sweep
  std::vector<std::string> sweep_vary;
  int sweep_jobs = 2;
  // replay (replay.cc) and view (viewer_cli.cc)
  CLI::App* replay = nullptr;
  CLI::App* view = nullptr;
  CLI::App* export_scene = nullptr;  // `export`: a scene flown by the native MuJoCo plugins
  CLI::App* benchmark = nullptr;     // `benchmark`: analysis/benchmark.py (benchmark_cli.cc)
  std::string replay_dir, replay_video, replay_out;
  std::string replay_video_size;  // --video-size WxH; empty: the run's snapshot size
  std::vector<double> replay_snapshots;
  int sweep_seeds = 0;        // --seeds N: N seeds per grid cell; 0: the config's seed
  bool sweep_resume = false;  // --resume: rerun only runs missing or incomplete
};

// The validator of every integer option: "--threads: an integer >= 1, got 0" (or "an integer in
// [1, 1024]" when `max` is a real bound) for a number out of range and for any text that is not
// a whole decimal number, instead of CLI11's floating-point range message.
CLI::Validator IntegerOption(long long min, long long max);

// An option of comma-separated integers in [min, max] ("2,4,8", also repeated), appended to
// *values. CLI11's own delimiter drops an empty item ("2,,4" would read as 2,4), so each value
// is split here and one with an empty item is refused, naming the value.
CLI::Option* AddIntegerListOption(CLI::App* app, const std::string& name, std::vector<int>* values,
                                  const std::string& description, long long min, long long max);

// Nothing of the user's is replaced: the commands that write a file the user names (replay's
// --video and snapshots, bench --json) have no --overwrite, so a file that exists already (or
// its ".tmp" sibling, which the PNG writer renames into place) is refused before any work, with
// a ConfigError naming it. The write itself then creates the file exclusively (O_EXCL).
void RefuseExistingFiles(const std::vector<std::string>& paths);
// A file the command writes when its work is done (bench --json) goes into a folder that exists
// and may be written to: checked before the work, with a ConfigError naming the folder.
void RequireWritableFolderOf(const std::string& path);

void AddCommands(CLI::App& app, CliCommands* commands);
// Runs the chosen subcommand; returns the process exit code:
// 0 ok, 1 bad input (nothing run), 2 usage, 3 the run stopped early (partial results kept).
int Dispatch(const CLI::App& app, const CliCommands& commands);

// The whole command line as `mjformation` runs it (main and the tests call this): parses argv,
// maps --help/--version to 0 and every parser error to 2, then dispatches. argv[0] is the
// program name.
int RunCommandLine(int argc, const char* const* argv);

// `mjformation bench` (runner/app/src/bench.cc).
void AddBenchCommand(CLI::App& app, CliCommands* commands);
int BenchCommand(const CliCommands& commands);

// `mjformation benchmark` (runner/app/src/benchmark_cli.cc): starts analysis/benchmark.py.
void AddBenchmarkCommand(CLI::App& app, CliCommands* commands);
int BenchmarkCommand(const CliCommands& commands);

// `mjformation sweep` (runner/app/src/sweep.cc).
void AddSweepCommand(CLI::App& app, CliCommands* commands);
int SweepCommand(const CliCommands& commands);

// `mjformation replay` (runner/app/src/replay_cli.cc) and `mjformation view`: both windows are
// drawn by the separate executable mjformation-view (GLFW), which the runner does not link.
void AddReplayCommand(CLI::App& app, CliCommands* commands);
int ReplayCommand(const CliCommands& commands);
void AddViewCommand(CLI::App& app, CliCommands* commands);
int ViewCommand(const CliCommands& commands);

}  // namespace mjf::runner

#endif  // MJFORMATION_APP_CLI_HPP_
