// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
// Internal: parsing of [safety] and [run] stop_on, called by ParseExperiment (config.cc).
#ifndef MJFORMATION_CONFIG_SRC_SAFETY_CONFIG_HPP_
#define MJFORMATION_CONFIG_SRC_SAFETY_CONFIG_HPP_

#include <toml++/toml.h>

#include <string>

#include "mjformation/config/experiment.hpp"

namespace mjf::runner {

// Reads root's [safety] table (may be absent) and [run] stop_on into c->safety. Throws
// ConfigError as "FILE:LINE: [section] key: reason".
void ParseSafetySections(const toml::table& root, const std::string& path, ExperimentConfig* c);

}  // namespace mjf::runner

#endif  // MJFORMATION_CONFIG_SRC_SAFETY_CONFIG_HPP_
