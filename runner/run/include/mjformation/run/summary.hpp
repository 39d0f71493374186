// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// summary.json: what a run was, how far it got, and its metrics (keys: docs/ARCHITECTURE.md).
#ifndef MJFORMATION_RUN_SUMMARY_HPP_
#define MJFORMATION_RUN_SUMMARY_HPP_

#include <nlohmann/json.hpp>
#include <string>

#include "mjformation/run/run.hpp"

namespace mjf::runner {

class Simulation;
struct ExperimentConfig;

// `recorded`: what the recorders and metrics added ("metrics", "snapshots", ...).
nlohmann::ordered_json BuildSummary(const Simulation& sim, const RunResult& result,
                                    const nlohmann::ordered_json& recorded);

// summary.json's "sensors" and "wind" entries (the resolved parameters), each only when that
// stage is switched on, so default runs keep their summary bytes.
void AddRealismSummary(const ExperimentConfig& c, nlohmann::ordered_json* summary);

// One line for the run's closing output when the leader's measured acceleration left Assumption
// 1's bounds (summary.json `leader_acceleration.assumption1_holds` false): when, how often, by how
// much, and what it voids (Theorem 2's band). Empty when the assumption holds or has no bounds.
std::string Assumption1Text(const nlohmann::ordered_json& summary);

}  // namespace mjf::runner

#endif  // MJFORMATION_RUN_SUMMARY_HPP_
