// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
// Internal: parsing of [sensors] and [wind], called by ParseExperiment (config.cc).
#ifndef MJFORMATION_CONFIG_SRC_REALISM_CONFIG_HPP_
#define MJFORMATION_CONFIG_SRC_REALISM_CONFIG_HPP_

#include <toml++/toml.h>

#include <string>

#include "mjformation/config/experiment.hpp"

namespace mjf::runner {

// Reads root's [sensors] and [wind] tables (either may be absent) into c->sensors and c->wind.
// Needs c->timestep, c->duration and c->altitude already parsed. Throws ConfigError as
// "FILE:LINE: [section] key: reason".
void ParseRealismSections(const toml::table& root, const std::string& path, ExperimentConfig* c);

}  // namespace mjf::runner

#endif  // MJFORMATION_CONFIG_SRC_REALISM_CONFIG_HPP_
