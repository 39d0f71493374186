// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// `mjformation sweep`: runs an experiment over the Cartesian product of parameter values, several
// simulations at once on worker threads (simulations share no state), one run directory per
// point, and a sweep.csv / sweep.json table of the metrics.
#include <fmt/format.h>

#include <atomic>
#include <cctype>
#include <cstdio>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>

#include "mjformation/runner/cli.hpp"
#include "mjformation/runner/output.hpp"
#include "mjformation/runner/run.hpp"

namespace mjf::runner {
namespace {

struct Axis {
  std::string key;                  // section.key
  std::vector<std::string> values;  // TOML values
};

// "formation.q=1,2.5,4.5" -> {formation.q, [1, 2.5, 4.5]}. Values may not contain commas.
Axis ParseAxis(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size()) {
    throw ConfigError("--vary '" + text + "': expected section.key=v1,v2,...");
  }
  Axis axis{text.substr(0, eq), {}};
  std::string rest = text.substr(eq + 1);
  size_t start = 0;
  while (true) {
    const size_t comma = rest.find(',', start);
    const std::string v = rest.substr(start, comma - start);
    if (v.empty()) throw ConfigError("--vary '" + text + "': empty value");
    axis.values.push_back(v);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return axis;
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

}  // namespace

int SweepCommand(const CliCommands& c) {
  std::vector<Axis> axes;
  for (const auto& v : c.sweep_vary) axes.push_back(ParseAxis(v));
  if (axes.empty()) throw ConfigError("sweep: give at least one --vary section.key=v1,v2,...");
  // Every point's file and overrides are parsed before any is run.
  std::vector<std::vector<size_t>> points(1);
  for (const Axis& axis : axes) {
    std::vector<std::vector<size_t>> next;
    for (const auto& p : points) {
      for (size_t k = 0; k < axis.values.size(); ++k) {
        next.push_back(p);
        next.back().push_back(k);
      }
    }
    points = std::move(next);
  }
  std::vector<ExperimentConfig> configs;
  for (const auto& p : points) {
    std::vector<std::string> overrides = c.overrides;
    for (size_t a = 0; a < axes.size(); ++a) {
      overrides.push_back(axes[a].key + "=" + axes[a].values[p[a]]);
    }
    configs.push_back(LoadExperiment(c.experiment, overrides));
    for (const auto& path : c.plugin_path) configs.back().plugin_path.push_back(path);
  }
  const std::string out = c.out.empty() ? "runs/" + configs.front().name + "_sweep" : c.out;
  RunDirectory sweep_dir(out, c.overwrite);

  const int jobs = std::max(1, std::min<int>(c.sweep_jobs, static_cast<int>(points.size())));
  std::vector<nlohmann::ordered_json> results(points.size());
  std::vector<std::string> errors(points.size());
  std::atomic<size_t> next{0};
  std::atomic<int> done{0};
  std::mutex print;
  std::fprintf(stderr, "sweep: %zu runs, %d at a time, into %s\n", points.size(), jobs,
               out.c_str());
  auto worker = [&] {
    for (size_t i; (i = next++) < points.size();) {
      RunOptions options;
      options.out_dir = out + "/" + PointName(axes, points[i]);
      options.overwrite = c.overwrite;
      options.render = !c.no_render;
      try {
        const RunResult r = RunExperiment(configs[i], options);
        results[i] = r.summary;
        if (!r.complete) errors[i] = r.error;
      } catch (const std::exception& e) {
        errors[i] = e.what();
      }
      std::lock_guard<std::mutex> lock(print);
      std::fprintf(stderr, "  [%d/%zu] %s%s\n", ++done, points.size(),
                   PointName(axes, points[i]).c_str(),
                   errors[i].empty() ? "" : (": " + errors[i]).c_str());
    }
  };
  std::vector<std::thread> threads;
  for (int j = 0; j < jobs; ++j) threads.emplace_back(worker);
  for (auto& t : threads) t.join();

  // The table, in point order (deterministic whatever the thread timing).
  auto metric = [](const nlohmann::ordered_json& s, const char* key) -> std::string {
    if (!s.contains("metrics") || !s["metrics"].contains(key) || !s["metrics"][key].is_number()) {
      return "";
    }
    return fmt::format("{:.6g}", s["metrics"][key].get<double>());
  };
  const char* const kMetrics[] = {
      "sigma_f_mean",    "sigma_f_final",     "max_final_slot_error_m",         "min_separation_m",
      "reaching_time_s", "saturation_time_s", "max_follower_tilt_deg_in_window"};
  std::string csv;
  for (const Axis& axis : axes) csv += axis.key + ",";
  csv += "complete";
  for (const char* m : kMetrics) csv += std::string(",") + m;
  csv += ",run,error\n";
  nlohmann::ordered_json table = nlohmann::ordered_json::array();
  std::printf("%s\n", csv.substr(0, csv.find(",run,error")).c_str());
  int failures = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    std::string row;
    nlohmann::ordered_json entry;
    for (size_t a = 0; a < axes.size(); ++a) {
      row += axes[a].values[points[i][a]] + ",";
      entry[axes[a].key] = axes[a].values[points[i][a]];
    }
    const bool complete = errors[i].empty();
    failures += !complete;
    row += complete ? "true" : "false";
    for (const char* m : kMetrics) row += "," + metric(results[i], m);
    std::printf("%s\n", row.c_str());
    std::string error = errors[i];
    for (char& ch : error) {
      if (ch == ',' || ch == '\n') ch = ';';
    }
    csv += row + "," + PointName(axes, points[i]) + "," + error + "\n";
    entry["complete"] = complete;
    entry["run"] = PointName(axes, points[i]);
    entry["error"] = complete ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(error);
    entry["metrics"] = results[i].contains("metrics") ? results[i]["metrics"] : nullptr;
    table.push_back(entry);
  }
  sweep_dir.WriteText("sweep.csv", csv);
  sweep_dir.WriteText("sweep.json", table.dump(2) + "\n");
  std::fprintf(stderr, "sweep: table in %s/sweep.csv%s\n", out.c_str(),
               failures ? fmt::format(" ({} runs failed or stopped early)", failures).c_str() : "");
  return failures ? 3 : 0;
}

void AddSweepCommand(CLI::App& app, CliCommands* c) {
  c->sweep = app.add_subcommand(
      "sweep", "Run an experiment over a grid of parameter values, several at once");
  c->sweep->add_option("experiment", c->experiment, "experiment file (TOML)")->required();
  c->sweep
      ->add_option("--vary", c->sweep_vary,
                   "a swept parameter: section.key=v1,v2,... (repeat for a grid)")
      ->required()
      ->allow_extra_args(false);
  c->sweep->add_option("--set", c->overrides, "fixed override: section.key=value");
  c->sweep->add_option("--out,-o", c->out, "sweep directory (default: runs/<run.name>_sweep)");
  c->sweep->add_option("--jobs,-j", c->sweep_jobs, "simulations at once (threads)")
      ->capture_default_str();
  c->sweep->add_option("--plugin-path", c->plugin_path, "extra folder to search for plugins");
  c->sweep->add_flag("--overwrite", c->overwrite, "replace existing run directories");
  c->sweep->add_flag("--no-render", c->no_render, "skip snapshots and video");
}

}  // namespace mjf::runner
