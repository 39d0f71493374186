// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The native engine plugins' instance configuration (mujoco_plugin/src/swarm_host.cc,
// ConfigFromPairs): each <config key="SECTION" value="..."> of an mjformation.swarm instance is
// the body of a TOML inline table, and the pairs go through the experiment parser as
// `SECTION = {VALUE}`. An input line is one <config>: the key, one space, the value attribute's
// text. Lines whose key is not a section the instance carries are left out, as MuJoCo's
// compiler refuses them before the plugin sees them. mjformation.attitude's `attitude` and
// `guidance` keys go through the same parser as [attitude] and [leader].
#include <algorithm>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "fuzz_util.hpp"
#include "swarm_host.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > 16 * 1024) return 0;  // an MJCF <plugin> element's attributes
  const std::vector<std::string>& carried = mjf::native::CarriedSections();
  std::vector<std::pair<std::string, std::string>> pairs;
  std::istringstream in(mjf::fuzz::AsText(data, size));
  for (std::string line; std::getline(in, line) && pairs.size() < 16;) {
    const size_t space = line.find(' ');
    const std::string key = line.substr(0, space);
    if (std::find(carried.begin(), carried.end(), key) == carried.end()) continue;
    pairs.emplace_back(key, space == std::string::npos ? "" : line.substr(space + 1));
  }
  try {
    const mjf::runner::ExperimentConfig c =
        mjf::native::ConfigFromPairs(pairs, "MJCF plugin 'mjformation.swarm' instance 'fuzz'");
    (void)c;
  } catch (const mjf::runner::ConfigError&) {
    // A refusal: the message names the instance and the section and key.
  }
  return 0;
}
