// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The plan of a sweep: the grid of --vary values times --seeds, every run's configuration
// parsed and checked before anything runs.
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <set>

#include "mjformation/config/config.hpp"
#include "mjformation/config/paths.hpp"
#include "mjformation/sim/simulation.hpp"
#include "sweep.hpp"

namespace mjf::runner::sweep {
namespace {

constexpr double kMaxRuns = 100000;  // runs in one sweep

}  // namespace

// "formation.q=1,2.5,4.5" -> {formation.q, [1, 2.5, 4.5]}. Commas inside [], {} or a TOML
// string do not split: "wind.mean=[3,0,0],[6,0,0]", "sensors={preset=\"typical\", scale=3.0},
// {...}" or "run.name='a,b','c'". A string is TOML's: "..." (where \" does not end it) or '...'
// (a literal string: no escapes, and the other quote is a plain character inside it).
Axis ParseAxis(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size()) {
    throw ConfigError("--vary '" + text + "': expected section.key=v1,v2,...");
  }
  Axis axis{text.substr(0, eq), {}};
  const std::string rest = text.substr(eq + 1);
  int depth = 0;
  char quote = 0;  // the quote of the string the scan is in; 0 outside strings
  std::string value;
  for (size_t i = 0; i <= rest.size(); ++i) {
    const char ch = i < rest.size() ? rest[i] : ',';
    if (quote == '"' && ch == '\\' && i + 1 < rest.size()) {  // an escape: \" or \\ stays inside
      value += ch;
      value += rest[++i];
      continue;
    }
    if (!quote && (ch == '"' || ch == '\'')) {
      quote = ch;
    } else if (ch == quote) {
      quote = 0;
    }
    const bool quoted = quote != 0;
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
  if (depth != 0 || quote) {
    throw ConfigError("--vary '" + text + "': unbalanced [ { or a string's quote (\" or ')");
  }
  return axis;
}

std::vector<Axis> ParseAxes(const std::vector<std::string>& texts) {
  std::vector<Axis> axes;
  for (const auto& text : texts) {
    Axis axis = ParseAxis(text);
    // The later override would win in every run while the run names and sweep.csv's columns
    // still showed both values: refused, the values go into one --vary.
    for (const Axis& earlier : axes) {
      if (earlier.key == axis.key) {
        throw ConfigError("--vary " + axis.key +
                          " is given twice; list all its values in one: --vary " + axis.key +
                          "=v1,v2,...");
      }
    }
    axes.push_back(std::move(axis));
  }
  return axes;
}

namespace {

std::string TrimmedKey(const std::string& text) {
  const std::string key = text.substr(0, text.find('='));
  const size_t first = key.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return key.substr(first, key.find_last_not_of(" \t") - first + 1);
}

// A key both fixed by --set and swept by --vary: every run takes the swept value (the axis is
// applied last), so the --set would be dropped without a word. Refused, naming both.
void RefuseFixedAndVaried(const std::vector<std::string>& overrides,
                          const std::vector<Axis>& axes) {
  for (const std::string& set : overrides) {
    for (const Axis& axis : axes) {
      if (TrimmedKey(set) == TrimmedKey(axis.key)) {
        throw ConfigError("--set " + set + " and --vary " + axis.key +
                          "=...: the sweep sets this key in every run; drop the --set or put "
                          "its value among the --vary values");
      }
    }
  }
}

// A run folder name's piece: letters, digits and . _ + - = { } kept, every other byte as %XX (like
// a URL), so no value can add a separator (','), a path component, a glob ('[' '*' '?') or a byte
// a shell would mangle; a table reads {preset=typical}.
std::string EscapeForName(const std::string& text) {
  std::string out;
  for (const char ch : text) {
    const auto byte = static_cast<unsigned char>(ch);
    if (std::isalnum(byte) || ch == '.' || ch == '_' || ch == '+' || ch == '-' || ch == '=' ||
        ch == '{' || ch == '}') {
      out += ch;
    } else {
      out += fmt::format("%{:02X}", byte);
    }
  }
  return out;
}

}  // namespace

// A name for a point's run directory: "key=value" pairs joined by ','. The value is shown plain
// (DisplayValue; quotes and spaces dropped: the run's config.toml and sweep.json hold the exact
// value); an array's or a table's brackets are dropped and its commas written '_', so
// wind.mean=[6.0,0.0,0.0] reads mean=6.0_0.0_0.0 and {preset="typical",scale=3.0} reads
// {preset=typical_scale=3.0} (no comma, so no shell brace expansion); any other byte outside
// EscapeForName's set is %XX. Values that would share a name are refused by PlanSweep.
// `legacy`: the name sweeps wrote before (brackets and commas as %XX), for --resume.
std::string PointName(const std::vector<Axis>& axes, const std::vector<size_t>& index,
                      bool legacy) {
  std::string name;
  for (size_t a = 0; a < axes.size(); ++a) {
    const std::string key = axes[a].key.substr(axes[a].key.rfind('.') + 1);
    std::string value;
    for (const char ch : DisplayValue(axes[a].values[index[a]])) {
      if (ch == '"' || ch == ' ') continue;
      if (!legacy && (ch == '[' || ch == ']')) continue;
      value += !legacy && ch == ',' ? '_' : ch;
    }
    name += (a ? "," : "") + EscapeForName(key) + "=" + EscapeForName(value);
  }
  return name;
}

namespace {

// Refuses a grid too large to plan before anything is allocated for it: every run's
// configuration is built up front.
void CheckPlanSize(const SweepPlan& plan) {
  double runs = std::max(1, plan.seeds);
  for (const Axis& axis : plan.axes) runs *= static_cast<double>(axis.values.size());
  if (runs > kMaxRuns) {
    throw ConfigError(fmt::format(
        "sweep: {:.0f} runs (--vary values x --seeds) is more than {} in one sweep; split it "
        "into several sweeps",
        runs, kMaxRuns));
  }
}

// Every grid cell checked as `run` would check it (config, model, plugins and their
// attributes), with the fixed overrides, before the sweep folder exists: a value can be valid
// alone and not with another axis's (kf_ins with a suite that has no accelerometer). A grid of
// more than kMaxCheckedCells cells is checked on the cells where at most one axis leaves its first
// value: every value once, combinations beyond that fail their runs (exit 3), as said there.
constexpr size_t kMaxCheckedCells = 256;
void CheckCells(const SweepPlan& plan) {
  const bool all = plan.cells.size() <= kMaxCheckedCells;
  // Each cell's first run: its configuration, already parsed by PlanSweep (seeds do not change
  // what is checked here).
  for (size_t r = 0; r < plan.runs.size(); ++r) {
    if (r > 0 && plan.runs[r].cell == plan.runs[r - 1].cell) continue;
    const std::vector<size_t>& cell = plan.cells[plan.runs[r].cell];
    const auto moved = std::count_if(cell.begin(), cell.end(), [](size_t k) { return k != 0; });
    if (!all && moved > 1) continue;
    std::string values;
    for (size_t a = 0; a < plan.axes.size(); ++a) {
      values += (a ? " with " : "") + plan.axes[a].key + "=" + plan.axes[a].values[cell[a]];
    }
    try {
      Simulation check(plan.runs[r].config);
    } catch (const std::exception& e) {
      throw ConfigError(
          "--vary " + values + ": " + e.what() +
          (plan.axes.size() > 1 ? " (leave that combination out: sweep it apart)" : ""));
    }
  }
  if (!all) {
    std::fprintf(stderr,
                 "sweep: note: %zu grid cells: each --vary value checked once (not every "
                 "combination: more than %zu cells)\n",
                 plan.cells.size(), kMaxCheckedCells);
  }
}

// --seeds varies run.seed, which drives every seeded component; a plugin seed the file pins
// stays fixed: said once, so the Monte Carlo is not taken for wider than it is.
void WarnPinnedSeeds(const ExperimentConfig& config) {
  for (const PluginSection* s : {&config.leader, &config.formation, &config.attitude}) {
    const auto it = s->attributes.find("seed");
    if (it == s->attributes.end()) continue;
    std::fprintf(stderr,
                 "sweep: note: %s:%d: [%s] seed = %s is pinned in the file: plugin '%s' draws the "
                 "same random numbers in every run (leave it out to let run.seed drive it)\n",
                 config.source_path.c_str(), it->second.line, s->section.c_str(),
                 it->second.text.c_str(), s->plugin.c_str());
  }
}

}  // namespace

std::string DisplayValue(const std::string& toml) {
  // A basic TOML string without escapes: its text. Anything else (numbers, booleans, arrays,
  // inline tables, strings with escapes) as written.
  if (toml.size() >= 2 && toml.front() == '"' && toml.back() == '"' &&
      toml.find_first_of("\\\"", 1) == toml.size() - 1) {
    return toml.substr(1, toml.size() - 2);
  }
  return toml;
}

// A CSV field: as is, or quoted (RFC 4180) when it holds a comma, quote, CR or LF.
std::string CsvField(const std::string& v) {
  if (v.find_first_of(",\"\r\n") == std::string::npos) return v;
  std::string out = "\"";
  for (char ch : v) out += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return out + "\"";
}

namespace {

// Every combination of the axes' values, as value indices, the first axis slowest.
std::vector<std::vector<size_t>> GridCells(const std::vector<Axis>& axes) {
  std::vector<std::vector<size_t>> cells(1);
  for (const Axis& axis : axes) {
    std::vector<std::vector<size_t>> next;
    for (const auto& p : cells) {
      for (size_t k = 0; k < axis.values.size(); ++k) {
        next.push_back(p);
        next.back().push_back(k);
      }
    }
    cells = std::move(next);
  }
  return cells;
}

// --resume of a sweep written with the older folder names: its finished runs keep their folders.
std::string ResumedName(const CliCommands& c, const std::string& name, const std::string& legacy) {
  if (!c.sweep_resume || c.out.empty() || legacy == name) return name;
  if (!IsDirectory(c.out + "/" + name) && IsDirectory(c.out + "/" + legacy)) return legacy;
  return name;
}

// The runs of one grid cell: one, or one per seed (base.seed, base.seed + 1, ...).
void AddCellRuns(const CliCommands& c, SweepPlan& plan, size_t cell) {
  std::vector<std::string> overrides = c.overrides;
  for (size_t a = 0; a < plan.axes.size(); ++a) {
    overrides.push_back(plan.axes[a].key + "=" + plan.axes[a].values[plan.cells[cell][a]]);
  }
  const auto checks = ExperimentChecks::Rendering(!c.no_render);
  const ExperimentConfig base = LoadExperiment(c.experiment, overrides, checks);
  if (cell == 0 && plan.seeds > 0) WarnPinnedSeeds(base);
  const std::string point = PointName(plan.axes, plan.cells[cell]);
  const std::string legacy_point = PointName(plan.axes, plan.cells[cell], /*legacy=*/true);
  auto seeded_name = [](const std::string& p, int seed) {
    return (p.empty() ? "" : p + ",") + "seed=" + std::to_string(seed);
  };
  for (int k = 0; k < std::max(1, plan.seeds); ++k) {
    RunSpec run;
    run.cell = cell;
    run.seed = base.seed + k;  // recorded in the run's config.toml and summary.json
    if (plan.seeds == 0) {
      run.config = base;
      run.name = ResumedName(c, point, legacy_point);
    } else {
      std::vector<std::string> seeded = overrides;
      seeded.push_back("run.seed=" + std::to_string(run.seed));
      run.config = LoadExperiment(c.experiment, seeded, checks);
      run.name = ResumedName(c, seeded_name(point, run.seed), seeded_name(legacy_point, run.seed));
    }
    for (const auto& path : c.plugin_path) run.config.plugin_path.push_back(path);
    plan.runs.push_back(std::move(run));
  }
}

}  // namespace

SweepPlan PlanSweep(const CliCommands& c) {
  SweepPlan plan;
  plan.axes = ParseAxes(c.sweep_vary);
  RefuseFixedAndVaried(c.overrides, plan.axes);
  if (c.sweep_seeds < 0 || (c.sweep->count("--seeds") && c.sweep_seeds == 0)) {
    throw ConfigError("sweep: --seeds must be >= 1 (seeds per grid cell)");
  }
  plan.seeds = c.sweep_seeds;
  if (plan.axes.empty() && plan.seeds == 0) {
    throw ConfigError("sweep: give --vary section.key=v1,v2,... and/or --seeds N");
  }
  CheckPlanSize(plan);
  plan.cells = GridCells(plan.axes);
  for (size_t cell = 0; cell < plan.cells.size(); ++cell) AddCellRuns(c, plan, cell);
  CheckCells(plan);
  std::set<std::string> names;
  for (const RunSpec& run : plan.runs) {
    if (!names.insert(run.name).second) {
      throw ConfigError("sweep: two runs would share the directory '" + run.name +
                        "' (values that differ only in quotes or spaces); write them apart");
    }
  }
  plan.out = c.out.empty() ? "runs/" + plan.runs.front().config.name + "_sweep" : c.out;
  return plan;
}

}  // namespace mjf::runner::sweep
