// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// summary.json "network" of per-agent execution (docs/NETWORK.md), written from the read-only
// state of the channel's parts: the routing's links and ages, the exchange rounds over the
// links, the central solver's star, the clocks. Pure: no MuJoCo.
#ifndef MJFORMATION_CONTROL_CHANNEL_SUMMARY_HPP_
#define MJFORMATION_CONTROL_CHANNEL_SUMMARY_HPP_

#include <nlohmann/json.hpp>

#include "mjformation/config/experiment.hpp"
#include "mjformation/control/agent_clock.hpp"
#include "mjformation/control/agent_routing.hpp"
#include "mjformation/control/central_solver.hpp"
#include "mjformation/control/rounds_over_links.hpp"

namespace mjf::runner {

// What the network summary reads; central (coupling = "central_solve") and rounds (rounds
// carried over the links) may be null.
struct ChannelParts {
  const NetworkConfig& config;
  int n_rounds;
  double jacobi_spectral_radius;
  const AgentRouting& routing;
  const CentralSolver* central;
  const RoundsOverLinks* rounds;
  const AgentClocks& clocks;
};

// "network": coupling, Jacobi spectral radius, per-link counts and measured latency, age of
// information per follower, topology switches, time without a spanning tree, the clocks, and
// "rounds_over_links" when the rounds travel over the links.
nlohmann::json NetworkSummary(const ChannelParts& parts);
// "network.clocks": the clocks as drawn (in phase: offsets and drifts all 0).
nlohmann::json ClocksSummary(const AgentClocks& clocks, int n_followers);
// "network.rounds_over_links": the exchanges per follower and in total, the round messages per
// follower link, the policy, and the solver's star (central solve).
nlohmann::json RoundsSummary(const RoundsOverLinks& rounds, const network::Network& network,
                             const CentralSolver* central);
// "network.rounds_over_links.solver": the central solve's star of links to vehicle 0 and back.
nlohmann::json SolverStarSummary(const CentralSolver& central);

}  // namespace mjf::runner

#endif  // MJFORMATION_CONTROL_CHANNEL_SUMMARY_HPP_
