// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// [safety]: the thresholds of the safety events, and [run] stop_on: the events that end a run.
// Every run looks for the events; with these at their defaults a run's timeseries and metrics
// are what they were (summary.json only gains "events").
#include "safety_config.hpp"

#include <algorithm>
#include <iterator>

#include "section_reader.hpp"

namespace mjf::runner {
namespace {

void ReadStopOn(SectionReader& run, SafetyConfig* s) {
  const toml::array* a = run.Array("stop_on");
  if (!a) return;
  std::string known;
  for (const char* k : kSafetyEventKinds) known += (known.empty() ? "" : ", ") + std::string(k);
  for (const toml::node& item : *a) {
    auto v = item.value_exact<std::string>();
    if (!v || std::find(std::begin(kSafetyEventKinds), std::end(kSafetyEventKinds), *v) ==
                  std::end(kSafetyEventKinds)) {
      run.FailAt(&item, "stop_on", "expected event kinds among " + known);
    }
    s->stop_on.push_back(*v);
  }
}

// region = [[x_min, x_max], [y_min, y_max], [z_min, z_max]] in m.
void ReadRegion(SectionReader& safety, SafetyConfig* s) {
  const toml::array* a = safety.Array("region");
  if (!a) return;
  const char* const kUsage = "expected [[x_min, x_max], [y_min, y_max], [z_min, z_max]] in m";
  if (a->size() != 3) safety.Fail("region", kUsage);
  for (size_t axis = 0; axis < 3; ++axis) {
    const toml::array* range = a->get(axis)->as_array();
    if (!range || range->size() != 2) safety.FailAt(a->get(axis), "region", kUsage);
    const double lo = safety.AsNumber(*range->get(0), "region");
    const double hi = safety.AsNumber(*range->get(1), "region");
    if (!(lo < hi)) safety.FailAt(range, "region", "each range needs min < max");
    s->region[2 * axis] = lo;
    s->region[2 * axis + 1] = hi;
  }
  s->has_region = true;
}

}  // namespace

void ParseSafetySections(const toml::table& root, const std::string& path, ExperimentConfig* c) {
  SafetyConfig& s = c->safety;
  SectionReader run(path, root.get_as<toml::table>("run"), "run");
  ReadStopOn(run, &s);
  SectionReader safety(path, root.get_as<toml::table>("safety"), "safety");
  s.flip_tilt_deg = safety.Number("flip_tilt_deg", s.flip_tilt_deg);
  s.near_miss_m = safety.Number("near_miss_m", s.near_miss_m);
  ReadRegion(safety, &s);
  safety.RejectUnknown();
  if (!(s.flip_tilt_deg > 0 && s.flip_tilt_deg <= 180)) {
    safety.Fail("flip_tilt_deg", "must be in (0, 180] degrees");
  }
  if (!(s.near_miss_m >= 0 && s.near_miss_m <= 1000)) {
    safety.Fail("near_miss_m", "must be in [0, 1000] m (0: no near-miss events)");
  }
}

}  // namespace mjf::runner
