// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The sweep's --vary values (runner/app sweep_plan.cc): each input line is one --vary argument.
// The axes are parsed, the run names of the grid's first cells made, and every value applied to
// a small experiment as the sweep applies it (an override per axis), up to the experiment
// parser's verdict; building the simulations is the experiment and MJCF targets' business.
#include "../../runner/app/src/sweep.hpp"
#include "fuzz_util.hpp"
#include "mjformation/config/config.hpp"

namespace {

const char kExperiment[] = R"([run]
name = "fuzz"
duration = 1.0
[vehicles]
model = "pointmass"
followers = 2
[formation]
plugin = "hover"
[attitude]
plugin = "pointmass_direct"
)";

mjf::fuzz::ScratchDir& Scratch() {
  static mjf::fuzz::ScratchDir dir;
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > 16 * 1024) return 0;  // a command line
  namespace sweep = mjf::runner::sweep;
  std::vector<std::string> args;
  const std::string input = mjf::fuzz::AsText(data, size);
  for (size_t start = 0; start < input.size() && args.size() < 4;) {
    size_t end = input.find('\n', start);
    if (end == std::string::npos) end = input.size();
    args.push_back(input.substr(start, end - start));
    start = end + 1;
  }
  std::vector<sweep::Axis> axes;
  try {
    axes = sweep::ParseAxes(args);
  } catch (const mjf::runner::ConfigError&) {
    return 0;  // a refusal naming the --vary argument
  }
  std::vector<size_t> index(axes.size(), 0);
  for (size_t a = 0; a < axes.size(); ++a) {
    for (size_t k = 0; k < axes[a].values.size() && k < 8; ++k) {
      index[a] = k;
      sweep::PointName(axes, index);
      const std::vector<std::string> overrides = {axes[a].key + "=" + axes[a].values[k]};
      try {
        mjf::runner::ParseExperiment(kExperiment, Scratch().path() + "/fuzz.toml", overrides);
      } catch (const mjf::runner::ConfigError&) {
        // A value the experiment refuses: the sweep's plan stops with this message.
      }
    }
    index[a] = 0;
  }
  return 0;
}
