// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// [execution] predict / clock_offset / clock_drift_ppm / clock_sync (docs/NETWORK.md): the
// timing of per-agent execution as a swarm has it. Every value is checked here, before anything
// runs.
#include <cmath>
#include <mjformation/plugin_contract.hpp>
#include <sstream>

#include "mjformation/config/source_location.hpp"
#include "network_config.hpp"
#include "section_reader.hpp"

namespace mjf::runner {
namespace {

constexpr double kMaxDriftPpm = 1e4;

// The sample period a follower's clock offset is bounded by: [formation] period when the file
// gives it (the discrete law's T), else the physics step (laws that sample every step).
double SamplePeriod(const ExperimentConfig& c) {
  const auto it = c.formation.attributes.find(plugin::contract::kPeriod);
  if (it == c.formation.attributes.end()) return c.timestep;
  char* end = nullptr;
  const double period = std::strtod(it->second.text.c_str(), &end);
  return end != it->second.text.c_str() && period > 0.0 ? period : c.timestep;
}

}  // namespace

void ParseExecutionTiming(SectionReader& keys, const ExperimentConfig& c, NetworkConfig& n) {
  n.predict = keys.Enum("predict", Predict::kNone, kPredictWords);
  n.clock_offset = keys.Number("clock_offset", 0.0);
  const double period = SamplePeriod(c);
  n.sample_period = period;
  if (!(n.clock_offset >= 0.0 && n.clock_offset < period)) {
    std::ostringstream out;
    out << "must be in [0, T) s with T = " << period
        << " s the sample period ([formation] period, else the timestep): an offset of a whole "
           "period is no offset";
    keys.Fail("clock_offset", out.str());
  }
  n.clock_drift_ppm = keys.Number("clock_drift_ppm", 0.0);
  if (!(n.clock_drift_ppm >= 0.0 && n.clock_drift_ppm <= kMaxDriftPpm)) {
    keys.Fail("clock_drift_ppm",
              "must be in [0, 1e4] ppm (the largest |drift|; each follower "
              "draws its own in [-value, value])");
  }
  n.clock_sync = keys.Bool("clock_sync", false);
  const bool timing = n.predict != Predict::kNone || n.clock_offset > 0.0 ||
                      n.clock_drift_ppm > 0.0 || n.clock_sync;
  if (timing && n.execution != Execution::kPerAgent) {
    keys.Fail(keys.Has("predict")        ? "predict"
              : keys.Has("clock_offset") ? "clock_offset"
              : keys.Has("clock_sync")   ? "clock_sync"
                                         : "clock_drift_ppm",
              "needs mode = \"per_agent\" (central mode sees every state at once)");
  }
}

void ParseExchangeRounds(SectionReader& keys, ExperimentConfig& c) {
  NetworkConfig& n = c.network;
  n.rounds = keys.Enum("rounds", ExchangeRounds::kInstantaneous, kExchangeRoundsWords);
  n.round_timeout = keys.Number("round_timeout", 0.0);
  if (!(n.round_timeout >= 0.0 && n.round_timeout <= c.duration)) {
    keys.Fail("round_timeout",
              "must be in [0, duration] s (0: no timeout, a round waits until the next sample)");
  }
  if (keys.Has("round_timeout") && n.rounds != ExchangeRounds::kOverLinks) {
    keys.Fail("round_timeout", "needs rounds = \"over_links\" (instantaneous rounds take no time)");
  }
  n.round_policy = keys.Enum("round_policy", RoundPolicy::kApply, kRoundPolicyWords);
  if (keys.Has("round_policy") && n.rounds != ExchangeRounds::kOverLinks) {
    keys.Fail("round_policy",
              "needs rounds = \"over_links\" (instantaneous rounds end in the tick they start)");
  }
  if (n.rounds != ExchangeRounds::kOverLinks || n.coupling == Coupling::kLastInput) return;
  // Not even one round fits a sample: a Jacobi round takes one hop (a follower link's fixed
  // latency), the central solve's round two (R_i up to the solver on the leader's star, W_i
  // back); jitter is left out, since some draws could still be short. Such a run would never
  // use a round's result, so it is refused, at the line that set the latency.
  const double period = SamplePeriod(c);
  const bool central = n.coupling == Coupling::kCentralSolve;
  double worst = keys.Has("latency") ? n.defaults.latency : 0.0;
  const NetworkConfig::LinkOverride* worst_link = nullptr;
  for (const auto& link : n.links) {
    // Jacobi rounds travel on follower links; the central solve's on the leader's links' star.
    if ((link.from == 0) != central || !(link.params.latency > worst)) continue;
    worst = link.params.latency;
    worst_link = &link;
  }
  const double round_time = central ? 2.0 * worst : worst;
  if (round_time < period) return;
  std::ostringstream out;
  out << "with rounds = \"over_links\" and coupling = \"" << ToString(n.coupling)
      << "\", one exchange round takes at least " << round_time << " s ("
      << (central ? "R_i up to the solver and W_i back, twice the latency"
                  : "one hop over a follower link")
      << "), not less than the sample period T = " << period
      << " s ([formation] period): not one round fits a sample";
  if (!worst_link) keys.Fail("latency", out.str());
  SourceLocation{c.source_path, worst_link->line, SectionKey("network.link", "latency")}.Fail(
      out.str());
}

}  // namespace mjf::runner
