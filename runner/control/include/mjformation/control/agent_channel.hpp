// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The communication channel stage of the control tick in per-agent execution
// ([execution] mode = "per_agent", docs/NETWORK.md). Each tick:
//   BeginTick: range limits from the true positions; every vehicle broadcasts its measured state,
//              its last formation input u and its last payload; due messages are delivered.
//   Input(i, r): what follower i is handed in round r (its own state, the newest message held
//              from each in-neighbour, the leader's when a_i0 > 0): never the swarm's arrays.
//   EndRound(r): Jacobi exchange of the round's payloads (loss only), or the central solve.
// Pure: no MuJoCo; the network is mjf::network::Network.
#ifndef MJFORMATION_CONTROL_AGENT_CHANNEL_HPP_
#define MJFORMATION_CONTROL_AGENT_CHANNEL_HPP_

#include <mjformation/plugin.h>

#include <array>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "mjformation/config/config.hpp"
#include "mjformation/control/agent_clock.hpp"
#include "mjformation/network/network.hpp"

namespace mjf::core {
class Graph;
}  // namespace mjf::core

namespace mjf::runner {

class AgentChannel {
 public:
  // graph: the follower graph (0-based); links get [network] defaults and overrides.
  AgentChannel(const core::Graph& graph, const NetworkConfig& config, double timestep,
               uint64_t seed);
  ~AgentChannel();

  int n_rounds() const { return n_rounds_; }
  // What follower i (0-based) knows of the graph: its own row of L_H, for create().
  const mjfNeighbourhood& neighbourhood(int follower) const { return neighbourhoods_[follower]; }

  void BeginTick(int64_t step, double time, const std::vector<mjfVehicleState>& truth,
                 const std::vector<mjfVehicleState>& measured,
                 const std::vector<mjfSetpoint>& setpoints);
  const mjfAgentInput& Input(int follower, int round);
  // After every follower ran round `round`; setpoints: the bus (inputs of the next broadcast).
  void EndRound(int round, const std::vector<mjfSetpoint>& setpoints);

  const network::Network& network() const { return network_; }
  // summary.json "network": coupling, Jacobi spectral radius, per-link counts and measured
  // latency, age of information per follower, topology switches, time without a spanning tree.
  nlohmann::json Summary() const;
  double jacobi_spectral_radius() const { return spectral_radius_; }
  const AgentClocks& clocks() const { return clocks_; }
  // summary.json "network.delay_margin" (docs/NETWORK.md): rho(L_H^-1 A) and the margins
  // predicted for the discrete law (48) with sample period T and q, with and without prediction.
  nlohmann::json DelayMarginSummary(double period, double q) const;

 private:
  void CentralSolve();
  void PredictInbox(int follower, const mjfMessage* leader);
  void RecordSampleAge();
  nlohmann::json ClocksSummary() const;
  static std::vector<network::LinkSpec> Links(const core::Graph& graph, const NetworkConfig& c);

  NetworkConfig config_;
  int n_followers_;
  int n_rounds_;
  double spectral_radius_;
  network::Network network_;
  std::vector<std::vector<int>> neighbour_ids_;
  std::vector<std::vector<double>> neighbour_weights_;
  std::vector<mjfNeighbourhood> neighbourhoods_;
  std::vector<mjfMessage> outgoing_;  // [follower] the last thing each follower wrote
  std::vector<mjfVehicleState> self_;
  std::vector<std::array<double, 3>> positions_;  // true positions, for range limits
  std::vector<std::vector<mjfMessage>> inbox_;    // [follower]
  std::vector<mjfAgentInput> inputs_;
  struct CentralSolver;                     // L_H factor and its right-hand side
  std::unique_ptr<CentralSolver> central_;  // central_solve only
  std::vector<double> solved_;              // [2 follower + axis]
  bool have_solution_ = false;
  int64_t central_skipped_samples_ = 0;  // samples some follower did not publish R_i in
  double time_ = 0.0;
  AgentClocks clocks_;
  std::vector<mjfMessage> leader_held_;        // [follower] the leader's message as predicted
  std::vector<network::AgeStats> sample_age_;  // [follower] age at the samples the law takes
  double coupling_radius_;                     // rho(L_H^-1 A), for the delay margin
};

}  // namespace mjf::runner

#endif  // MJFORMATION_CONTROL_AGENT_CHANNEL_HPP_
