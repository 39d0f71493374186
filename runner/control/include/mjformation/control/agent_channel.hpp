// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The communication channel stage of the control tick in per-agent execution
// ([execution] mode = "per_agent", docs/NETWORK.md), composed of its parts: the routing
// (AgentRouting: links, inboxes, broadcasts), the followers' clocks (AgentClocks), the inbox
// prediction (InboxPrediction), the central solver (CentralSolver, coupling = "central_solve")
// and the exchange rounds over the links (RoundsOverLinks, rounds = "over_links"). Each tick:
//   BeginTick: range limits from the true positions; every vehicle broadcasts its measured state,
//              its last formation input u and its last payload; due messages are delivered.
//   Input(i, r): what follower i is handed in round r (its own state, the newest message held
//              from each in-neighbour, the leader's when a_i0 > 0): never the swarm's arrays.
//   EndRound(r): Jacobi exchange of the round's payloads (loss only), or the central solve.
// Pure: no MuJoCo; the network is mjf::network::Network.
#ifndef MJFORMATION_CONTROL_AGENT_CHANNEL_HPP_
#define MJFORMATION_CONTROL_AGENT_CHANNEL_HPP_

#include <mjformation/plugin.h>

#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mjformation/config/experiment.hpp"
#include "mjformation/config/fixed_state_archive.hpp"
#include "mjformation/control/agent_clock.hpp"
#include "mjformation/control/agent_routing.hpp"
#include "mjformation/control/message_prediction.hpp"
#include "mjformation/network/network.hpp"

namespace mjf::formation {
class Graph;
}  // namespace mjf::formation

namespace mjf::runner {

class CentralSolver;
class RoundsOverLinks;

// The most messages in flight on one link that the native MuJoCo plugin holds in plugin_state
// (every step copies the whole state in and out, so the queue is bounded; b13's links hold 3).
constexpr int64_t kNativeMessagesInFlight = 100;
// Why the native MuJoCo plugin cannot hold the channel of `network` (per-agent execution) in
// plugin_state, naming the key and the numbers, or empty when it can: a link whose messages in
// flight (MaxInFlight) or exchange-round letters in flight (MaxRoundLettersInFlight, rounds =
// "over_links") pass kNativeMessagesInFlight. The runner's checkpoints hold any channel.
std::string NativeNetworkRefusal(const NetworkConfig& network, double timestep);

class AgentChannel {
 public:
  // graph: the follower graph (0-based); links get [network] defaults and overrides.
  AgentChannel(const formation::Graph& graph, const NetworkConfig& config, double timestep,
               uint64_t seed);
  ~AgentChannel();

  int n_rounds() const { return n_rounds_; }
  const NetworkConfig& config() const { return config_; }
  // What follower i (0-based) knows of the graph: its own row of L_H, for create().
  const mjfNeighbourhood& neighbourhood(int follower) const {
    return routing_.neighbourhood(follower);
  }

  void BeginTick(int64_t step, double time, const std::vector<mjfVehicleState>& truth,
                 const std::vector<mjfVehicleState>& measured,
                 const std::vector<mjfSetpoint>& setpoints);
  const mjfAgentInput& Input(int follower, int round);
  // What follower i was last handed (its inbox and leader message as of its last call): what
  // it knows of its neighbours, read after the tick without fetching anything again.
  const mjfAgentInput& LastInput(int follower) const { return routing_.input(follower); }
  // After every follower ran round `round`; setpoints: the bus (inputs of the next broadcast).
  void EndRound(int round, const std::vector<mjfSetpoint>& setpoints);

  // Exchange rounds over the links ([network] rounds = "over_links" with coupling = "jacobi" or
  // "central_solve", docs/NETWORK.md; rounds_over_links.hpp). The control tick then runs:
  // BeginTick; ContinueRounds (earlier samples' rounds whose inputs have arrived); round 0 of
  // every follower (SetCallContext, Input(i, 0), the plugin); EndSampleRound (a follower that
  // sampled posts round 0, or R_i to the solver); ContinueRounds again (what arrived in this
  // very step). A continued round is handed its sample's input, time and step, frozen at round 0.
  bool rounds_over_links() const { return rounds_ != nullptr; }
  void SetCallContext(int follower, double local_time, int64_t local_step);
  void EndSampleRound(const std::vector<mjfSetpoint>& setpoints);
  // The first follower whose next round can run now (its inputs arrived, or the round timeout
  // passed), or -1; *round, *local_time, *local_step: that round and its sample's clock reading.
  int NextContinuedRound(int* round, double* local_time, int64_t* local_step);
  const mjfAgentInput& ContinuedInput(int follower, int round);
  void EndContinuedRound(int follower, int round, const std::vector<mjfSetpoint>& setpoints);
  // The tick's last call (round_policy = "hold"): a follower whose exchange is still running
  // flies the command of its last finished exchange (setpoint acc x, y); one whose exchange has
  // ended keeps its plugin's command, which becomes the held one.
  void HoldPendingCommands(std::vector<mjfSetpoint>* setpoints);

  const network::Network& network() const { return routing_.network(); }
  // summary.json "network" (channel_summary.hpp).
  nlohmann::json Summary() const;
  double jacobi_spectral_radius() const { return spectral_radius_; }
  // rho(L_H^-1 A): what the delay margin of law (48) needs of the graph (delay_margin.hpp).
  double coupling_radius() const { return coupling_radius_; }
  const AgentClocks& clocks() const { return clocks_; }

  // What the channel carries from tick to tick, of a length fixed at construction (the control
  // tick's state, ControlTick::GetState): the routing and the network, the central solve, the
  // exchange rounds over the links. The clocks are drawn once from the seed (configuration, not
  // state).
  void VisitState(FixedStateArchive& archive);
  // What grows with the run beside that block: the range topology's events (checkpoints only).
  void VisitEvents(StateArchive& archive) { routing_.network().VisitEvents(archive); }
  void ForgetTopologyEvents() { routing_.network().ForgetEvents(); }

 private:
  NetworkConfig config_;
  int n_rounds_;
  double spectral_radius_;
  double coupling_radius_;
  AgentRouting routing_;
  AgentClocks clocks_;
  InboxPrediction prediction_;
  std::unique_ptr<CentralSolver> central_;   // central_solve only
  std::unique_ptr<RoundsOverLinks> rounds_;  // rounds over the links only
};

}  // namespace mjf::runner

#endif  // MJFORMATION_CONTROL_AGENT_CHANNEL_HPP_
