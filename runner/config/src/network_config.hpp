// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#ifndef MJFORMATION_CONFIG_SRC_NETWORK_CONFIG_HPP_
#define MJFORMATION_CONFIG_SRC_NETWORK_CONFIG_HPP_

#include <toml++/toml.h>

#include "mjformation/config/experiment.hpp"

namespace mjf::runner {

// Parses [execution] and [network] of the experiment into c.network. [run] and [topology] must
// be parsed already (the rate is checked against the timestep; a link override must name a link
// of the graph). Throws ConfigError as "FILE:LINE: [section] key: reason".
void ParseNetworkSections(const toml::table& root, ExperimentConfig& c);

class SectionReader;
// execution_timing_config.cc: [execution] predict, clock_offset, clock_drift_ppm
// (c: [run] and [formation] parsed already; n.execution read already).
void ParseExecutionTiming(SectionReader& keys, const ExperimentConfig& c, NetworkConfig& n);
// [network] rounds, round_timeout: exchange rounds over the links; refuses a
// latency with which not one round fits a sample (c.network's links parsed already).
void ParseExchangeRounds(SectionReader& keys, ExperimentConfig& c);

}  // namespace mjf::runner

#endif  // MJFORMATION_CONFIG_SRC_NETWORK_CONFIG_HPP_
