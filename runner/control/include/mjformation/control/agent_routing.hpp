// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Who hears whom in per-agent execution ([execution] mode = "per_agent", docs/NETWORK.md): the
// network's links (every follower edge j -> i, then the leader link 0 -> i when a_i0 > 0), each
// follower's neighbourhood (its row of L_H), its inbox, the mjfAgentInput it is handed and the
// message it writes. Each tick: range limits from the true positions, every vehicle's broadcast
// of its measured state, last formation input u and last payload, delivery of what is due.
// Pure: no MuJoCo; the network is mjf::network::Network.
#ifndef MJFORMATION_CONTROL_AGENT_ROUTING_HPP_
#define MJFORMATION_CONTROL_AGENT_ROUTING_HPP_

#include <mjformation/plugin.h>

#include <array>
#include <cstdint>
#include <vector>

#include "mjformation/config/experiment.hpp"
#include "mjformation/network/network.hpp"

namespace mjf::formation {
class Graph;
}  // namespace mjf::formation

namespace mjf::runner {

class AgentRouting {
 public:
  // graph: the follower graph (0-based); links get [network] defaults and overrides. n_rounds:
  // rounds per sample (a broadcast carries the sender's last round, n_rounds - 1).
  AgentRouting(const formation::Graph& graph, const NetworkConfig& config, int n_rounds,
               double timestep, uint64_t seed);

  // Every follower edge j -> i and every leader link 0 -> i with a_i0 > 0, in the order of the
  // follower's in-neighbours (the order of its messages), then its leader link.
  static std::vector<network::LinkSpec> Links(const formation::Graph& graph,
                                              const NetworkConfig& c);

  int n_followers() const { return n_followers_; }
  // What follower i (0-based) knows of the graph: its own row of L_H, for create().
  const mjfNeighbourhood& neighbourhood(int follower) const { return neighbourhoods_[follower]; }
  // Follower i's in-neighbours (0-based), in the order of its messages.
  const std::vector<int>& neighbour_ids(int follower) const { return neighbour_ids_[follower]; }
  network::Network& network() { return network_; }
  const network::Network& network() const { return network_; }
  double time() const { return time_; }  // s, of the current tick
  int64_t step() const { return step_; }

  // Range limits from the true positions, every vehicle's broadcast (the bus setpoints carry
  // each sender's last formation input u), delivery; measured: the followers' own states.
  void BeginTick(int64_t step, double time, const std::vector<mjfVehicleState>& truth,
                 const std::vector<mjfVehicleState>& measured,
                 const std::vector<mjfSetpoint>& setpoints);
  // Packs follower's inbox with the newest message held from each in-neighbour (round: the round
  // part to read, -1 for none); returns the leader's message, or null when a_i0 = 0 or nothing
  // arrived yet.
  const mjfMessage* FetchInbox(int follower, int round);
  // Only the round part of the inbox FetchInbox packed this tick, for `round`.
  void RefreshRound(int follower, int round);
  std::vector<mjfMessage>& inbox(int follower) { return inbox_[follower]; }
  const mjfVehicleState& self(int follower) const { return self_[follower]; }
  mjfAgentInput& input(int follower) { return inputs_[follower]; }
  const mjfAgentInput& input(int follower) const { return inputs_[follower]; }
  const std::vector<mjfMessage>& outgoing() const { return outgoing_; }
  mjfMessage& outgoing(int follower) { return outgoing_[follower]; }
  // The message follower writes in `round`: its round set, its payload emptied.
  mjfMessage* OpenOutgoing(int follower, int round);
  // What the next broadcast carries besides the payload: sender, send time, the follower's own
  // state and its formation input u (x, y) from the bus.
  void FillOutgoing(int follower, const std::vector<mjfSetpoint>& setpoints);
  // Jacobi instantaneous exchange: each follower that wrote a payload this round sends it.
  void ExchangeRound();
  // Age of information where the law samples (a follower that wrote a payload in round 0).
  void RecordSampleAge();
  const network::AgeStats& sample_age(int follower) const { return sample_age_[follower]; }

  // What the routing carries from tick to tick (a fixed-length archive): the network, each
  // follower's last message and own state, the ages, the tick's time. The inboxes and inputs
  // are packed afresh on every call (Input), the positions on every tick: not state.
  template <typename Archive>
  void VisitState(Archive& archive) {
    network_.VisitState(archive);
    network::VisitMessages(archive, outgoing_);
    archive(self_, sample_age_, time_, step_);
  }

 private:
  int n_followers_;
  int n_rounds_;
  network::Network network_;
  std::vector<std::vector<int>> neighbour_ids_;
  std::vector<std::vector<double>> neighbour_weights_;
  std::vector<mjfNeighbourhood> neighbourhoods_;
  std::vector<mjfMessage> outgoing_;  // [follower] the last thing each follower wrote
  std::vector<mjfVehicleState> self_;
  std::vector<std::array<double, 3>> positions_;  // true positions, for range limits
  std::vector<std::vector<mjfMessage>> inbox_;    // [follower]
  std::vector<mjfAgentInput> inputs_;
  std::vector<network::AgeStats> sample_age_;  // [follower] age at the samples the law takes
  double time_ = 0.0;
  int64_t step_ = 0;
};

}  // namespace mjf::runner

#endif  // MJFORMATION_CONTROL_AGENT_ROUTING_HPP_
