// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The tables of a sweep: sweep.csv / sweep.json per run, or with --seeds per cell (mean,
// standard deviation and 95 % Student-t confidence interval of every metric, the runs in
// sweep_runs.csv). Written atomically (temporary file + rename), with a completeness flag: an
// interrupted sweep keeps its finished runs and marks the others "not run".
#include <fmt/format.h>

#include <cmath>

#include "mjformation/app/sweep_stats.hpp"
#include "mjformation/record/output.hpp"
#include "sweep.hpp"

namespace mjf::runner::sweep {
namespace {

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

// The safety events a run reported (summary.json "events", absent when none).
int64_t EventCount(const Json& s) {
  if (!s.is_object() || !s.contains("events") || !s["events"].contains("count")) return 0;
  return s["events"]["count"].get<int64_t>();
}
std::string FirstEvent(const Json& s) {
  if (EventCount(s) == 0 || s["events"]["list"].empty()) return "";
  return s["events"]["list"][0]["what"].get<std::string>();
}
// A flip, a ground impact or a collision makes a run another experiment (a vehicle crashed or
// hit another), so the cell statistics leave such runs out; a near miss or a region exit is only
// reported (Exp 2's followers start 1.5 m apart, inside the near-miss distance of 1.25 m between
// centres, so any turbulence gives every run one: leaving those out would empty a study).
const char* const kInvalidatingKinds[] = {"flip", "ground_impact", "collision"};

int64_t InvalidatingCount(const Json& s) {
  if (EventCount(s) == 0 || !s["events"].contains("by_kind")) return 0;
  int64_t n = 0;
  for (const char* kind : kInvalidatingKinds) {
    const Json& by_kind = s["events"]["by_kind"];
    if (by_kind.contains(kind)) n += by_kind[kind].get<int64_t>();
  }
  return n;
}

// The tables gain their event columns only when some run had an event: the tables of a sweep
// without one keep their bytes.
bool AnyEvents(const std::vector<RunOutcome>& outcomes) {
  for (const RunOutcome& o : outcomes) {
    if (EventCount(o.summary) > 0) return true;
  }
  return false;
}

// Per-run table: one row per run in plan order (whatever the completion order).
std::string RunsCsv(const SweepPlan& plan, const std::vector<RunOutcome>& outcomes) {
  std::string csv;
  for (const Axis& axis : plan.axes) csv += axis.key + ",";
  if (plan.seeds) csv += "seed,";
  csv += "complete";
  for (const char* m : kMainMetrics) csv += std::string(",") + m;
  const bool events = AnyEvents(outcomes);
  csv += events ? ",run,error,safety_events,first_safety_event\n" : ",run,error\n";
  for (size_t i = 0; i < plan.runs.size(); ++i) {
    const RunSpec& run = plan.runs[i];
    for (size_t a = 0; a < plan.axes.size(); ++a) {
      csv += CsvField(DisplayValue(plan.axes[a].values[plan.cells[run.cell][a]])) + ",";
    }
    if (plan.seeds) csv += std::to_string(run.seed) + ",";
    csv += outcomes[i].complete() ? "true" : "false";
    for (const char* m : kMainMetrics) csv += "," + MetricText(outcomes[i].summary, m);
    csv += "," + CsvField(run.name) + "," + (outcomes[i].complete() ? "" : RunStatus(outcomes[i]));
    if (events) {
      csv += fmt::format(",{},{}", EventCount(outcomes[i].summary),
                         CsvSafe(FirstEvent(outcomes[i].summary)));
    }
    csv += "\n";
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
                                                std::vector<int>* completed, bool valid_only) {
  std::vector<std::vector<std::vector<double>>> samples(
      plan.cells.size(), std::vector<std::vector<double>>(keys.size()));
  completed->assign(plan.cells.size(), 0);
  for (size_t i = 0; i < plan.runs.size(); ++i) {
    if (!outcomes[i].complete()) continue;
    if (valid_only && InvalidatingCount(outcomes[i].summary) > 0) continue;
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

// Every run's row of sweep.json; `complete` is cleared when some run did not finish.
Json RunsJson(const SweepPlan& plan, const std::vector<RunOutcome>& outcomes, bool* complete) {
  Json runs = Json::array();
  for (size_t i = 0; i < plan.runs.size(); ++i) {
    const RunSpec& run = plan.runs[i];
    const RunOutcome& o = outcomes[i];
    *complete = *complete && o.state == RunOutcome::kFinished;
    Json entry;
    for (size_t a = 0; a < plan.axes.size(); ++a) {
      entry[plan.axes[a].key] = plan.axes[a].values[plan.cells[run.cell][a]];
    }
    if (plan.seeds) entry["seed"] = run.seed;
    entry["complete"] = o.complete();
    entry["finished"] = o.state == RunOutcome::kFinished;
    entry["run"] = run.name;
    entry["error"] = o.complete() ? Json(nullptr) : Json(RunStatus(o));
    entry["safety_events"] = EventCount(o.summary);
    if (EventCount(o.summary) > 0) {
      entry["first_safety_event"] = FirstEvent(o.summary);
      entry["invalidating_events"] = InvalidatingCount(o.summary);
    }
    entry["metrics"] = o.summary.is_object() && o.summary.contains("metrics") ? o.summary["metrics"]
                                                                              : Json(nullptr);
    runs.push_back(entry);
  }
  return runs;
}

// A cell's statistics as CSV cells and as sweep.json's "metrics".
Json StatsRow(const std::vector<std::string>& keys, const std::vector<SampleStats>& stats,
              std::string* csv) {
  Json metrics = Json::object();
  for (size_t k = 0; k < keys.size(); ++k) {
    const SampleStats& s = stats[k];
    *csv += "," + NumberText(s.mean) + "," + NumberText(s.std) + "," + NumberText(s.ci95_low) +
            "," + NumberText(s.ci95_high);
    metrics[keys[k]] = {{"n", s.n},
                        {"mean", JsonNumber(s.mean)},
                        {"std", JsonNumber(s.std)},
                        {"ci95", {JsonNumber(s.ci95_low), JsonNumber(s.ci95_high)}}};
  }
  return metrics;
}

// Runs of each cell that reported a safety event (complete or not).
std::vector<int> RunsWithEvents(const SweepPlan& plan, const std::vector<RunOutcome>& outcomes) {
  std::vector<int> count(plan.cells.size(), 0);
  for (size_t i = 0; i < plan.runs.size(); ++i) {
    count[plan.runs[i].cell] += EventCount(outcomes[i].summary) > 0;
  }
  return count;
}

// Complete runs of each cell that the statistics leave out (a flip, ground impact or collision).
std::vector<int> RunsLeftOut(const SweepPlan& plan, const std::vector<RunOutcome>& outcomes) {
  std::vector<int> count(plan.cells.size(), 0);
  for (size_t i = 0; i < plan.runs.size(); ++i) {
    count[plan.runs[i].cell] +=
        outcomes[i].complete() && InvalidatingCount(outcomes[i].summary) > 0;
  }
  return count;
}

// With --seeds: the per-cell statistics as sweep.csv's text (`csv`) and sweep.json's "cells".
// When some run had a safety event, each cell has two rows, said apart by `statistics_over`:
// over all complete runs, and over the valid ones (no flip, ground impact or collision; near
// misses and region exits are kept), with how many complete runs that row left out.
Json CellsTable(const SweepPlan& plan, const std::vector<RunOutcome>& outcomes, std::string* csv) {
  const std::vector<std::string> keys = MetricKeys(outcomes);
  const bool events = AnyEvents(outcomes);
  std::vector<int> completed, valid;
  const auto stats = CellStats(plan, outcomes, keys, &completed, false);
  const auto valid_stats = CellStats(plan, outcomes, keys, &valid, true);
  const std::vector<int> with_events = RunsWithEvents(plan, outcomes);
  const std::vector<int> left_out = RunsLeftOut(plan, outcomes);
  for (const Axis& axis : plan.axes) *csv += axis.key + ",";
  *csv += events ? "seeds,runs_with_safety_events,runs_left_out,statistics_over,runs"
                 : "seeds,complete_runs";
  for (const auto& k : keys) *csv += fmt::format(",{0}_mean,{0}_std,{0}_ci95_low,{0}_ci95_high", k);
  *csv += "\n";
  Json cells = Json::array();
  for (size_t cell = 0; cell < plan.cells.size(); ++cell) {
    Json entry;
    std::string values;
    for (size_t a = 0; a < plan.axes.size(); ++a) {
      values += CsvField(DisplayValue(plan.axes[a].values[plan.cells[cell][a]])) + ",";
      entry[plan.axes[a].key] = plan.axes[a].values[plan.cells[cell][a]];
    }
    entry["seeds"] = plan.seeds;
    entry["complete_runs"] = completed[cell];
    entry["runs_with_safety_events"] = with_events[cell];
    entry["runs_left_out"] = left_out[cell];  // complete, with a flip, ground impact or collision
    entry["valid_complete_runs"] = valid[cell];
    if (!events) {
      *csv += values + fmt::format("{},{}", plan.seeds, completed[cell]);
      entry["metrics"] = StatsRow(keys, stats[cell], csv);
      *csv += "\n";
    } else {
      *csv += values + fmt::format("{},{},0,all_complete_runs,{}", plan.seeds, with_events[cell],
                                   completed[cell]);
      entry["metrics"] = StatsRow(keys, stats[cell], csv);
      *csv += "\n" + values +
              fmt::format("{},{},{},valid_runs,{}", plan.seeds, with_events[cell], left_out[cell],
                          valid[cell]);
      entry["metrics_valid"] = StatsRow(keys, valid_stats[cell], csv);
      *csv += "\n";
    }
    cells.push_back(entry);
  }
  return cells;
}

// A metric's value for the short summary: the mean and its 95 % interval, or the value alone
// when every run gave the same (an interval of zero width says nothing a reader needs).
std::string MeanText(const SampleStats& s) {
  if (s.n == 0 || !std::isfinite(s.mean)) return "n/a";
  if (s.n < 2) return fmt::format("{:.4g} (1 run)", s.mean);
  if (s.std == 0) return fmt::format("{:.4g} (the same in all {} runs)", s.mean, s.n);
  return fmt::format("{:.4g}, 95 % CI [{:.4g}, {:.4g}] over {} runs (Student t{})", s.mean,
                     s.ci95_low, s.ci95_high, s.n, s.cut_at_zero ? ", cut at 0" : "");
}

// The varied values of a cell as "key=value, key=value" (the table's plain values).
std::string CellLabel(const SweepPlan& plan, size_t cell) {
  std::string label;
  for (size_t a = 0; a < plan.axes.size(); ++a) {
    label += (a ? ", " : "") + plan.axes[a].key + "=" +
             DisplayValue(plan.axes[a].values[plan.cells[cell][a]]);
  }
  return label.empty() ? "all runs" : label;
}

}  // namespace

std::string SummaryText(const SweepPlan& plan, const std::vector<RunOutcome>& outcomes) {
  constexpr size_t kMaxLines = 20;  // the rest is in the table
  const char* const kMetric = "sigma_f_mean";
  std::string text;
  size_t lines = 0;
  if (plan.seeds) {
    const std::vector<std::string> keys = {kMetric};
    std::vector<int> completed, valid;
    const auto stats = CellStats(plan, outcomes, keys, &completed, false);
    const auto valid_stats = CellStats(plan, outcomes, keys, &valid, true);
    const std::vector<int> with_events = RunsWithEvents(plan, outcomes);
    const std::vector<int> left_out = RunsLeftOut(plan, outcomes);
    std::vector<int> reported_only(plan.cells.size(), 0);
    for (size_t i = 0; i < plan.runs.size(); ++i) {
      reported_only[plan.runs[i].cell] +=
          EventCount(outcomes[i].summary) > 0 && InvalidatingCount(outcomes[i].summary) == 0;
    }
    for (size_t cell = 0; cell < plan.cells.size() && lines < kMaxLines; ++cell, ++lines) {
      // With runs left out, the statistics over the valid runs come first: they are the study's.
      text += fmt::format("  {}: {} {}", CellLabel(plan, cell), kMetric,
                          MeanText(left_out[cell] > 0 ? valid_stats[cell][0] : stats[cell][0]));
      if (completed[cell] < plan.seeds) {
        text += fmt::format("; {} of {} runs incomplete", plan.seeds - completed[cell], plan.seeds);
      }
      if (left_out[cell] > 0) {
        text += fmt::format(
            "; {} of {} complete runs left out (a flip, ground impact or collision; with them: "
            "{})",
            left_out[cell], completed[cell], MeanText(stats[cell][0]));
      }
      if (reported_only[cell] > 0) {
        text += fmt::format("; {} with near misses or region exits only (reported, kept)",
                            RunCount(reported_only[cell]));
      }
      text += "\n";
    }
  } else {
    for (size_t i = 0; i < plan.runs.size() && lines < kMaxLines; ++i, ++lines) {
      const RunOutcome& o = outcomes[i];
      const std::string value = MetricText(o.summary, kMetric);
      text +=
          fmt::format("  {}: {}", CellLabel(plan, plan.runs[i].cell),
                      o.complete() ? fmt::format("{} {}", kMetric, value.empty() ? "n/a" : value)
                                   : "incomplete: " + RunStatus(o));
      if (EventCount(o.summary) > 0) text += "; safety event: " + FirstEvent(o.summary);
      text += "\n";
    }
  }
  const size_t rows = plan.seeds ? plan.cells.size() : plan.runs.size();
  if (rows > lines) text += fmt::format("  ... and {} more in sweep.csv\n", rows - lines);
  return text;
}

void WriteTables(const SweepPlan& plan, const std::vector<RunOutcome>& outcomes) {
  bool complete = true;
  Json runs = RunsJson(plan, outcomes, &complete);
  Json table = {{"complete", complete}, {"seeds", plan.seeds}, {"runs", runs}};
  if (plan.seeds) table["ci95_method"] = kCi95Method;
  if (AnyEvents(outcomes)) {
    Json kinds = Json::array();
    for (const char* kind : kInvalidatingKinds) kinds.push_back(kind);
    table["left_out_events"] = kinds;  // what makes a run leave the cell statistics
  }
  const std::string runs_csv = RunsCsv(plan, outcomes);
  if (!plan.seeds) {
    WriteTextFile(plan.out + "/sweep.csv", runs_csv);
  } else {
    std::string csv;
    table["cells"] = CellsTable(plan, outcomes, &csv);
    WriteTextFile(plan.out + "/sweep_runs.csv", runs_csv);
    WriteTextFile(plan.out + "/sweep.csv", csv);
  }
  WriteTextFile(plan.out + "/sweep.json", table.dump(2) + "\n");
}

}  // namespace mjf::runner::sweep
