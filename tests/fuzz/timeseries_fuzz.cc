// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// A run directory's records as `replay` reads them (runner/app LoadRecording): timeseries.csv,
// then after a line "--- config.toml" the run's config.toml and after "--- summary.json" its
// summary (each optional). A recording that loads is then used as replay uses it: the frame
// nearest a time, the trails at a frame, and the --snapshots times checked against it.
#include "fuzz_util.hpp"
#include "mjformation/app/replay.hpp"
#include "mjformation/config/config_error.hpp"
#include "mjformation/config/experiment.hpp"

namespace {

mjf::fuzz::ScratchDir& Scratch() {
  static mjf::fuzz::ScratchDir dir;
  return dir;
}

// Splits the input at the lines "--- NAME": {"timeseries.csv" text, "config.toml" text, ...}.
std::vector<std::pair<std::string, std::string>> Files(const std::string& input) {
  std::vector<std::pair<std::string, std::string>> files = {{"timeseries.csv", ""}};
  size_t start = 0;
  while (start <= input.size()) {
    size_t end = input.find('\n', start);
    if (end == std::string::npos) end = input.size();
    const std::string line = input.substr(start, end - start);
    if (line == "--- config.toml" || line == "--- summary.json") {
      files.emplace_back(line.substr(4), "");
    } else {
      files.back().second += line + (end < input.size() ? "\n" : "");
    }
    start = end + 1;
  }
  return files;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > 256 * 1024) return 0;
  bool has_config = false, has_summary = false;
  for (const auto& [name, text] : Files(mjf::fuzz::AsText(data, size))) {
    Scratch().Write(name, text);
    has_config |= name == "config.toml";
    has_summary |= name == "summary.json";
  }
  if (!has_config) Scratch().Write("config.toml", "[run]\nname = \"fuzz\"\n");
  if (!has_summary) Scratch().Write("summary.json", "{}\n");
  try {
    const mjf::runner::Recording rec = mjf::runner::LoadRecording(Scratch().path());
    const int last = rec.Frame(rec.t.back());
    mjf::runner::TrailsAt(rec, last);
    mjf::runner::CheckReplayTimes(rec, {rec.t.front(), rec.t.back()});
  } catch (const mjf::runner::ReplayError&) {
    // A refusal naming the file (and row).
  } catch (const mjf::runner::ConfigError&) {
    // A --snapshots time outside the recording.
  }
  return 0;
}
