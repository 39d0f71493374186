// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/app/cli.hpp"

#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <limits>

#include "mjformation/config/config.hpp"
#include "mjformation/config/key_reference.hpp"
#include "mjformation/config/nearest_word.hpp"
#include "mjformation/config/paths.hpp"
#include "mjformation/config/source_location.hpp"
#include "mjformation/control/plugin_host.hpp"
#include "mjformation/export/export.hpp"
#include "mjformation/record/engine_identity.hpp"
#include "mjformation/record/output.hpp"
#include "mjformation/run/run.hpp"
#include "mjformation/run/summary.hpp"
#include "mjformation/scene/scene.hpp"
#include "mjformation/sim/simulation.hpp"

namespace mjf::runner {
namespace {

// How bad an event is, for the closing line: a lost vehicle before a touch before a warning.
int EventSeverity(const std::string& kind) {
  static const char* const kWorstFirst[] = {"flip", "ground_impact", "collision", "left_region"};
  for (int rank = 0; rank < 4; ++rank)
    if (kind == kWorstFirst[rank]) return 4 - rank;
  return 0;  // near_miss
}

// "; follower 6 flipped at 34.19 s (tilt 179.9 deg); 2 more events in summary.json", or "".
// The event named is the earliest of the most severe kind, so a flip is never hidden behind an
// earlier near miss.
std::string EventsText(const nlohmann::ordered_json& summary) {
  if (!summary.contains("events")) return "";
  const auto& events = summary["events"];
  const auto& list = events["list"];
  if (list.empty()) return "";
  const nlohmann::ordered_json* worst = &list[0];
  for (const auto& e : list) {  // the list is in time order: keep the first of each severity
    if (EventSeverity(e["kind"].get<std::string>()) >
        EventSeverity((*worst)["kind"].get<std::string>()))
      worst = &e;
  }
  std::string text = "; " + (*worst)["what"].get<std::string>();
  const int64_t more = events["count"].get<int64_t>() - 1;
  if (more > 0)
    text += fmt::format("; {} more safety event{} in summary.json", more, more > 1 ? "s" : "");
  return text;
}

int RunCommand(const CliCommands& c) {
  ExperimentConfig config =
      LoadExperiment(c.experiment, c.overrides, ExperimentChecks::Rendering(!c.no_render));
  for (const auto& p : c.plugin_path) config.plugin_path.push_back(p);
  if (c.run_threads > 0) {
    // How to run, not what: the results are the same, so config.toml keeps the file's text.
    config.threads = c.run_threads;
    config.threads_origin = {0, "--threads " + std::to_string(c.run_threads)};
  }
  RunOptions options;
  options.out_dir = c.out.empty() ? "runs/" + config.name : c.out;
  options.overwrite = c.overwrite;
  options.progress = !c.quiet;
  options.render = !c.no_render;
  options.warnings = true;
  options.checkpoint_every = c.checkpoint_every;
  options.resume = c.resume;
  const RunResult r = RunExperiment(config, options);
  const auto& m = r.summary["metrics"];
  const std::string sigma = m.is_object() && m["sigma_f_mean"].is_number()
                                ? fmt::format("{:.4f}", m["sigma_f_mean"].get<double>())
                                : std::string("n/a");
  if (!r.summary_error.empty()) {
    std::fprintf(stderr, "mjformation: %s: %s\n  summary.json could not be written: %s\n",
                 config.name.c_str(), r.error.empty() ? "run finished" : r.error.c_str(),
                 r.summary_error.c_str());
    return r.signal ? 128 + r.signal : 3;
  }
  if (!r.complete) {
    std::fprintf(
        stderr,
        "mjformation: %s: the run stopped early: %s%s\n  what was recorded up to t = "
        "%.3f s is kept in %s (summary.json says \"complete\": false)\n",
        config.name.c_str(), EscapeControl(r.error).c_str(),
        r.error.find("safety event") == std::string::npos ? EventsText(r.summary).c_str() : "",
        r.sim_time_s, options.out_dir.c_str());
    return r.signal ? 128 + r.signal : 3;
  }
  if (!c.quiet) {
    std::printf(
        "%s: complete%s, %.1f s simulated in %.2f s (%.1fx real time); mean sigma_f on "
        "[%g, %g] s = %s; results in %s\n",
        config.name.c_str(), EventsText(r.summary).c_str(), r.sim_time_s, r.wall_time_s,
        r.wall_time_s > 0 ? r.sim_time_s / r.wall_time_s : 0.0, config.metric_window[0],
        config.metric_window[1], sigma.c_str(), options.out_dir.c_str());
    const std::string assumption = Assumption1Text(r.summary);
    if (!assumption.empty()) std::printf("  note: %s\n", assumption.c_str());
  }
  return 0;
}

int CheckCommand(const CliCommands& c) {
  ExperimentConfig config = LoadExperiment(c.experiment, c.overrides);
  for (const auto& p : c.plugin_path) config.plugin_path.push_back(p);
  Simulation sim(config);
  std::printf(
      "%s: OK (%d followers, model %s, %d bodies, leader '%s', formation '%s', attitude "
      "'%s')\n",
      c.experiment.c_str(), config.followers, config.model_path.c_str(),
      static_cast<int>(sim.model()->nbody), config.leader.plugin.c_str(),
      config.formation.plugin.c_str(), config.attitude.plugin.c_str());
  for (const auto& note : sim.vehicle_notes()) std::printf("  vehicle model: %s\n", note.c_str());
  std::printf("  %s\n", AuthorityText(sim.torque_authority()).c_str());
  const AttitudeDemand& d = sim.attitude_demand();
  if (d.att_bw > 0 && d.tilt_max > 0) {
    std::printf(
        "  attitude loop: att_bw %.3g rad/s (unlimited %.3g), tilt_max %.3g rad: asks for %.3g "
        "rad/s^2 (att_bw^2 x tilt_max, of the unlimited loop)\n",
        d.att_bw, d.Reference(), d.tilt_max, DemandedTiltAcceleration(d.Reference(), d.tilt_max));
  }
  for (const auto& w : sim.warnings()) std::printf("  warning: %s\n", w.c_str());
  return 0;
}

// What --version adds to the version line: where this runner looks for plugins and models
// (an installed one: only its own prefix, docs/ARCHITECTURE.md "Installed layout").
std::string VersionText() {
  const std::string prefix = InstalledPrefix();
  const EngineIdentity& engine = RunningEngine();
  std::string text =
      VersionString() + "\n" + "MuJoCo library: " + engine.library_path + " (sha256 " +
      engine.library_sha256 + ")\n" +
      (prefix.empty() ? "running from the build tree\n" : "installed in " + prefix + "\n");
  text += "plugin search path:";
  for (const auto& dir : PluginSearchPath({})) text += " " + dir;
  text += "\nmodel search path:";
  for (const auto& dir : ModelSearchPath()) text += " " + dir;
  return text;
}

void PrintSearchPath(const char* title, const std::vector<std::string>& dirs) {
  std::printf("%s:\n", title);
  for (const auto& dir : dirs) {
    std::printf("  %s%s\n", dir.c_str(), IsDirectory(dir) ? "" : "  (absent)");
  }
}

int PluginsCommand(const CliCommands& c) {
  PluginRegistry registry(PluginSearchPath(c.plugin_path));
  PrintSearchPath("Plugin search path", registry.search_path());
  PrintSearchPath("Model search path", ModelSearchPath());
  for (mjfKind kind : {MJF_KIND_GUIDANCE, MJF_KIND_FORMATION, MJF_KIND_FORMATION_AGENT,
                       MJF_KIND_ATTITUDE, MJF_KIND_ESTIMATOR}) {
    std::printf("\n%s plugins:\n", KindName(kind));
    for (const auto& p : registry.plugins()) {
      const mjfPlugin& d = *p.descriptor;
      if (d.kind != kind) continue;
      std::printf("  %s  -  %s\n    library: %s\n", d.name, d.doc ? d.doc : "", p.library.c_str());
      if (d.n_actuators > 0) {
        std::string names;
        for (int k = 0; k < d.n_actuators; ++k)
          names += std::string(k ? ", " : "") + d.actuators[k];
        std::printf("    drives actuators: %s\n", names.c_str());
      }
      for (int k = 0; k < d.n_attributes; ++k) {
        const mjfAttribute& a = d.attributes[k];
        std::printf("    %-16s %-22s %s\n", a.key,
                    a.default_value ? ("= " + std::string(a.default_value)).c_str() : "(required)",
                    a.doc ? a.doc : "");
      }
    }
  }
  if (!registry.problems().empty()) {
    std::printf("\nNot loaded:\n");
    for (const auto& p : registry.problems()) std::printf("  %s\n", p.c_str());
  }
  return 0;
}

int KeysCommand(const CliCommands& c) {
  std::fputs(KeyReferenceMarkdown(c.keys_section).c_str(), stdout);
  return 0;
}

}  // namespace

void RefuseExistingFiles(const std::vector<std::string>& paths) {
  for (const std::string& path : paths) {
    for (const std::string& file : {path, path + ".tmp"}) {
      struct stat st {};
      if (lstat(file.c_str(), &st) == 0) {
        throw ConfigError(file +
                          ": exists; this command never replaces a file (it has no "
                          "--overwrite): remove it or choose another name");
      }
    }
  }
}

void RequireWritableFolderOf(const std::string& path) {
  const auto slash = path.find_last_of('/');
  const std::string folder = slash == std::string::npos ? "."
                             : slash == 0               ? "/"
                                                        : path.substr(0, slash);
  struct stat st {};
  if (stat(folder.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) {
    throw ConfigError(path + ": the folder " + folder +
                      " does not exist; create it or choose another path");
  }
  if (access(folder.c_str(), W_OK | X_OK) != 0) {
    throw ConfigError(path + ": the folder " + folder + " is not writable (" +
                      std::strerror(errno) + "); choose another path");
  }
}

CLI::Validator IntegerOption(long long min, long long max) {
  const bool bounded = max < std::numeric_limits<int>::max();
  const std::string what = bounded ? fmt::format("an integer in [{}, {}]", min, max)
                                   : fmt::format("an integer >= {}", min);
  return CLI::Validator(
      [=](std::string& text) {
        errno = 0;
        char* end = nullptr;
        const long long v = std::strtoll(text.c_str(), &end, 10);
        const bool whole = !text.empty() && end == text.c_str() + text.size() && errno == 0;
        if (whole && v >= min && v <= max) return std::string();
        return what + ", got '" + EscapeControl(text) + "'";
      },
      what);
}

namespace {

// The items of a comma-separated list, empty ones kept.
std::vector<std::string> CommaItems(const std::string& text) {
  std::vector<std::string> items;
  size_t start = 0;
  for (size_t comma; (comma = text.find(',', start)) != std::string::npos; start = comma + 1) {
    items.push_back(text.substr(start, comma - start));
  }
  items.push_back(text.substr(start));
  return items;
}

}  // namespace

CLI::Option* AddIntegerListOption(CLI::App* app, const std::string& name, std::vector<int>* values,
                                  const std::string& description, long long min, long long max) {
  const CLI::Validator item = IntegerOption(min, max);
  const CLI::Validator list(
      [item](std::string& text) {
        const bool several = text.find(',') != std::string::npos;
        for (std::string part : CommaItems(text)) {
          if (part.empty()) {
            return "an empty item in '" + EscapeControl(text) +
                   "' (each item: " + item.get_description() + ")";
          }
          const std::string why = item(part);
          if (!why.empty()) return several ? why + " in '" + EscapeControl(text) + "'" : why;
        }
        return std::string();
      },
      item.get_description() + ", comma-separated");
  return app
      ->add_option_function<std::vector<std::string>>(
          name,
          [values](const std::vector<std::string>& texts) {
            for (const std::string& text : texts) {
              for (const std::string& part : CommaItems(text)) values->push_back(std::stoi(part));
            }
          },
          description)
      ->check(list);
}

int ExportCommand(const CliCommands& c) {
  ExportOptions options;
  options.overrides = c.overrides;
  options.plugin_path = c.plugin_path;
  options.overwrite = c.overwrite;
  const ExportResult result = ExportExperiment(c.experiment, c.out, options);
  for (const std::string& note : result.notes) std::fprintf(stderr, "note: %s\n", note.c_str());
  std::printf("%s\n", result.scene_path.c_str());
  return 0;
}

void AddExportCommand(CLI::App& app, CliCommands* c) {
  c->export_scene =
      app.add_subcommand("export",
                         "Write the experiment as a MuJoCo scene flown by the native plugins "
                         "(libmjformation_mujoco.so; docs/PLUGINS.md). Stock MuJoCo must load "
                         "that library before it compiles the scene: in Python `import "
                         "mjformation` first, in C mj_loadPluginLibrary");
  c->export_scene->add_option("experiment", c->experiment, "experiment file (TOML)")->required();
  c->export_scene
      ->add_option("--out,-o", c->out,
                   "output directory: scene.xml and a copy of every file it names (the folder "
                   "can be moved)")
      ->required();
  c->export_scene->add_option("--set", c->overrides, "override a value: section.key=value");
  c->export_scene
      ->add_option("--plugin-path", c->plugin_path,
                   "extra folder to search for plugins (carried into the scene)")
      ->check(CLI::ExistingDirectory);
  c->export_scene->add_flag("--overwrite", c->overwrite,
                            "write into an existing non-empty directory (replaces scene.xml and "
                            "the files export wrote there, never another file)");
}

namespace {

// A finite number of seconds > 0. CLI::PositiveNumber lets NaN through (a period that is never
// due: no checkpoint is ever written) and names its range in 309 digits.
CLI::Validator PositiveSecondsOption() {
  const std::string what = "a finite number of seconds > 0";
  return CLI::Validator(
      [=](std::string& text) {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        const bool whole = !text.empty() && end == text.c_str() + text.size();
        if (whole && std::isfinite(v) && v > 0) return std::string();
        return what + ", got '" + EscapeControl(text) + "'";
      },
      what);
}

// run --checkpoint-every S, --resume (docs/ARCHITECTURE.md, "Checkpoint and resume").
void AddCheckpointOptions(CLI::App* run, CliCommands* c) {
  run->add_option("--checkpoint-every", c->checkpoint_every,
                  "write a checkpoint every S simulated seconds into the run directory "
                  "(checkpoint.mjfstate, replaced atomically, with its SHA-256): MuJoCo's "
                  "state, every plugin's, the partitions' (threads > 1), the per-agent "
                  "network's, the sensors, estimator, wind, metrics and outputs; video "
                  "([render] video = true) is refused at startup: run with --no-render")
      ->check(PositiveSecondsOption());
  run->add_flag("--resume", c->resume,
                "continue a killed run from the last checkpoint in its run directory (the same "
                "experiment file and --set options: the config's sha256 is checked); the output "
                "files end byte for byte as an uninterrupted run's. A damaged checkpoint, or one "
                "of another run or build, is refused and changes nothing")
      ->excludes("--overwrite");
}

}  // namespace

void AddCommands(CLI::App& app, CliCommands* c) {
  app.set_version_flag("--version", VersionText);
  app.require_subcommand(1);
  c->run = app.add_subcommand("run", "Run an experiment file and write its run directory");
  c->run->add_option("experiment", c->experiment, "experiment file (TOML)")->required();
  c->run->add_option("--out,-o", c->out, "run directory (default: runs/<run.name>)");
  c->run->add_option(
      "--set", c->overrides,
      "override a value: section.key=value (TOML value), e.g. formation.rho=0.1, or replace a "
      "section's keys, keeping its sub-tables: 'attitude={plugin=\"pointmass_direct\"}'");
  c->run->add_option("--plugin-path", c->plugin_path, "extra folder to search for plugins")
      ->check(CLI::ExistingDirectory);
  c->run->add_flag("--overwrite", c->overwrite, "replace an existing run directory");
  c->run->add_flag(
      "--no-render", c->no_render,
      "skip snapshots and video (and the render-only checks: snapshot times beyond the run)");
  c->run->add_flag("--quiet,-q", c->quiet, "no progress line or closing line");
  c->run
      ->add_option("--threads", c->run_threads,
                   "physics partitions stepped in parallel (default: [run] threads, 1)")
      ->check(IntegerOption(1, kMaxThreads));
  AddCheckpointOptions(c->run, c);

  c->check = app.add_subcommand(
      "check", "Check an experiment file (config, model, plugins, topology) without running it");
  c->check->add_option("experiment", c->experiment, "experiment file (TOML)")->required();
  c->check->add_option("--set", c->overrides, "override a value: section.key=value");
  c->check->add_option("--plugin-path", c->plugin_path, "extra folder to search for plugins")
      ->check(CLI::ExistingDirectory);

  c->plugins = app.add_subcommand("plugins", "List the plugins found, with their attributes");
  c->plugins->add_option("--plugin-path", c->plugin_path, "extra folder to search for plugins")
      ->check(CLI::ExistingDirectory);
  c->keys = app.add_subcommand(
      "keys", "Every key of the experiment file: type, unit, default, range, what it does");
  c->keys->add_option("section", c->keys_section, "only this section (and its sub-tables)");
  AddBenchCommand(app, c);
  AddSweepCommand(app, c);
  AddReplayCommand(app, c);
  AddViewCommand(app, c);
  AddExportCommand(app, c);
  AddBenchmarkCommand(app, c);
}

int Dispatch(const CLI::App& app, const CliCommands& c) {
  (void)app;
  try {
    if (c.run->parsed()) return RunCommand(c);
    if (c.check->parsed()) return CheckCommand(c);
    if (c.plugins->parsed()) return PluginsCommand(c);
    if (c.keys->parsed()) return KeysCommand(c);
    if (c.bench && c.bench->parsed()) return BenchCommand(c);
    if (c.sweep->parsed()) return SweepCommand(c);
    if (c.replay && c.replay->parsed()) return ReplayCommand(c);
    if (c.view && c.view->parsed()) return ViewCommand(c);
    if (c.export_scene->parsed()) return ExportCommand(c);
    if (c.benchmark->parsed()) return BenchmarkCommand(c);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mjformation: error: %s\n", EscapeControl(e.what()).c_str());
    return 1;
  }
  return 2;
}

namespace {

// The first argument names the command (only --help and --version come before one): a word
// that is none of them is named, with the nearest command, where CLI11 would say only "A
// subcommand is required". Empty when the first argument is a command or an option.
std::string UnknownCommand(const CLI::App& app, int argc, const char* const* argv) {
  if (argc < 2 || argv[1][0] == '-') return "";
  std::vector<std::string> names;
  for (const CLI::App* command : app.get_subcommands({})) names.push_back(command->get_name());
  const std::string word = argv[1];
  if (std::find(names.begin(), names.end(), word) != names.end()) return "";
  std::string list;
  for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
  return "unknown command '" + word + "'" + DidYouMean(word, names) + " (commands: " + list +
         "; mjformation --help)";
}

}  // namespace

int RunCommandLine(int argc, const char* const* argv) {
  CLI::App app{"mjformation: distributed formation control of quadrotor swarms in MuJoCo"};
  CliCommands commands;
  AddCommands(app, &commands);
  if (const std::string unknown = UnknownCommand(app, argc, argv); !unknown.empty()) {
    std::fprintf(stderr, "mjformation: %s\n", EscapeControl(unknown).c_str());
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version end here with 0; every misuse of the command line exits 2.
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  return Dispatch(app, commands);
}

}  // namespace mjf::runner
