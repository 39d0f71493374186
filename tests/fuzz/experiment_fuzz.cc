// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The experiment file with --set overrides (runner/config): the input is the file's text, then,
// after each line "--set", one override (section.key=value) as the command line gives it.
#include "fuzz_util.hpp"
#include "mjformation/config/config.hpp"

namespace {

// Relative paths in the file (plugin_path, [formation.shape] file) resolve against this
// folder; nothing is read from it while parsing.
mjf::fuzz::ScratchDir& Scratch() {
  static mjf::fuzz::ScratchDir dir;
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > 64 * 1024) return 0;  // an experiment file is a page or two
  std::vector<std::string> parts = mjf::fuzz::SplitAt(mjf::fuzz::AsText(data, size), "--set");
  const std::string text = parts.front();
  std::vector<std::string> overrides;
  for (size_t k = 1; k < parts.size(); ++k) {
    std::string item = parts[k];
    if (!item.empty() && item.back() == '\n') item.pop_back();  // the shell gives no newline
    overrides.push_back(item);
  }
  try {
    const mjf::runner::ExperimentConfig c =
        mjf::runner::ParseExperiment(text, Scratch().path() + "/experiment.toml", overrides);
    (void)c;
  } catch (const mjf::runner::ConfigError&) {
    // A refusal: the contract's clean error (FILE:LINE: [section] key: reason).
  }
  return 0;
}
