// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/control/agent_routing.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "mjformation/formation/graph.hpp"

namespace mjf::runner {

std::vector<network::LinkSpec> AgentRouting::Links(const formation::Graph& graph,
                                                   const NetworkConfig& c) {
  std::map<std::pair<int, int>, network::LinkParams> overrides;
  for (const auto& o : c.links) overrides[{o.from, o.to}] = o.params;
  auto params = [&](int from, int to) {
    auto it = overrides.find({from, to});
    return it == overrides.end() ? c.defaults : it->second;
  };
  std::vector<network::LinkSpec> links;
  for (int i = 0; i < graph.num_followers(); ++i) {
    for (int k = graph.in_begin(i); k < graph.in_end(i); ++k) {
      const int j = graph.in_neighbor(k);
      links.push_back({j + 1, i + 1, params(j + 1, i + 1)});
    }
    if (graph.leader_weight(i) > 0.0) links.push_back({0, i + 1, params(0, i + 1)});
  }
  return links;
}

AgentRouting::AgentRouting(const formation::Graph& graph, const NetworkConfig& config, int n_rounds,
                           double timestep, uint64_t seed)
    : n_followers_(graph.num_followers()),
      n_rounds_(n_rounds),
      network_(graph.num_followers(), Links(graph, config), timestep, seed),
      neighbour_ids_(n_followers_),
      neighbour_weights_(n_followers_),
      neighbourhoods_(n_followers_),
      outgoing_(n_followers_),
      self_(n_followers_),
      inbox_(n_followers_),
      inputs_(n_followers_),
      sample_age_(n_followers_) {
  for (int i = 0; i < n_followers_; ++i) {
    for (int k = graph.in_begin(i); k < graph.in_end(i); ++k) {
      neighbour_ids_[i].push_back(graph.in_neighbor(k));
      neighbour_weights_[i].push_back(graph.in_weight(k));
    }
    neighbourhoods_[i] = {i,
                          n_followers_,
                          graph.leader_weight(i),
                          static_cast<int>(neighbour_ids_[i].size()),
                          neighbour_ids_[i].data(),
                          neighbour_weights_[i].data()};
    inbox_[i].reserve(neighbour_ids_[i].size());
    outgoing_[i] = mjfMessage{};
    for (double& u : outgoing_[i].input) u = std::nan("");
  }
}

void AgentRouting::BeginTick(int64_t step, double time, const std::vector<mjfVehicleState>& truth,
                             const std::vector<mjfVehicleState>& measured,
                             const std::vector<mjfSetpoint>& setpoints) {
  time_ = time;
  step_ = step;
  positions_.resize(truth.size());  // allocates on the first tick only
  for (size_t v = 0; v < truth.size(); ++v) {
    positions_[v] = {truth[v].pos[0], truth[v].pos[1], truth[v].pos[2]};
  }
  network_.UpdateTopology(step, positions_);
  network_.ClearRounds();
  for (int v = 0; v <= n_followers_; ++v) {
    mjfMessage m = v == 0 ? mjfMessage{} : outgoing_[v - 1];
    m.sender = v;
    // Its payload is the sender's last round of the previous tick.
    m.round = n_rounds_ - 1;
    m.send_time = time;
    m.state = measured[v];
    // The sender's last formation input u (x, y), as it is on the bus: one sample old.
    m.input[0] = setpoints[v].acc[0];
    m.input[1] = setpoints[v].acc[1];
    m.input[2] = 0.0;
    network_.Broadcast(step, v, m);
  }
  network_.Deliver(step);
  for (int i = 0; i < n_followers_; ++i) self_[i] = measured[i + 1];
}

const mjfMessage* AgentRouting::FetchInbox(int follower, int round) {
  const mjfMessage* leader = nullptr;
  network_.Inbox(follower + 1, round, &inbox_[follower], &leader);
  return leader;
}

void AgentRouting::RefreshRound(int follower, int round) {
  network_.RefreshRound(follower + 1, round, &inbox_[follower]);
}

mjfMessage* AgentRouting::OpenOutgoing(int follower, int round) {
  mjfMessage& out = outgoing_[follower];
  out.round = round;
  out.n_payload = 0;
  return &out;
}

void AgentRouting::FillOutgoing(int follower, const std::vector<mjfSetpoint>& setpoints) {
  mjfMessage& out = outgoing_[follower];
  out.sender = follower + 1;
  out.send_time = time_;
  out.state = self_[follower];
  out.input[0] = setpoints[follower + 1].acc[0];
  out.input[1] = setpoints[follower + 1].acc[1];
  out.input[2] = 0.0;
}

void AgentRouting::ExchangeRound() {
  for (int i = 0; i < n_followers_; ++i) {
    // A follower with nothing new this round (between samples) sends no round message.
    if (outgoing_[i].n_payload > 0) network_.ExchangeRound(i + 1, outgoing_[i]);
  }
}

// Now minus the send time of the oldest message the follower acts on.
void AgentRouting::RecordSampleAge() {
  for (int i = 0; i < n_followers_; ++i) {
    if (outgoing_[i].n_payload <= 0) continue;
    double oldest = time_;
    for (const mjfMessage& m : inbox_[i]) oldest = std::min(oldest, m.send_time);
    if (inputs_[i].leader) oldest = std::min(oldest, inputs_[i].leader->send_time);
    network::AgeStats& a = sample_age_[i];
    a.sum += time_ - oldest;
    a.max = std::max(a.max, time_ - oldest);
    ++a.ticks;
  }
}

}  // namespace mjf::runner
