// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/control/agent_channel.hpp"

#include <fmt/format.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <map>

#include "mjformation/control/delay_margin.hpp"
#include "mjformation/control/errors.hpp"
#include "mjformation/control/message_prediction.hpp"
#include "mjformation/core/discrete_smc_agent.hpp"
#include "mjformation/core/graph.hpp"
#include "mjformation/core/laplacian_solver.hpp"

namespace mjf::runner {

struct AgentChannel::CentralSolver {
  explicit CentralSolver(const core::Graph& graph)
      : solver(graph.laplacian_h()), rhs(graph.num_followers(), 2) {}
  core::LaplacianSolver solver;
  Eigen::Matrix<double, Eigen::Dynamic, 2> rhs;
};

namespace {

int RoundsFor(const NetworkConfig& c) {
  switch (c.coupling) {
    case Coupling::kJacobi:
      return 1 + c.jacobi_rounds;  // round 0 from the last inputs, then m exchanges
    case Coupling::kCentralSolve:
      return 2;  // round 0 publishes R_i; the host solves; round 1 uses the solution
    default:
      return 1;
  }
}

}  // namespace

// Every follower edge j -> i and every leader link 0 -> i with a_i0 > 0, in the order of the
// follower's in-neighbours (the order of its messages), then its leader link.
std::vector<network::LinkSpec> AgentChannel::Links(const core::Graph& graph,
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

AgentChannel::AgentChannel(const core::Graph& graph, const NetworkConfig& config, double timestep,
                           uint64_t seed)
    : config_(config),
      n_followers_(graph.num_followers()),
      n_rounds_(RoundsFor(config)),
      spectral_radius_(core::JacobiSpectralRadius(graph)),
      network_(graph.num_followers(), Links(graph, config), timestep, seed),
      neighbour_ids_(n_followers_),
      neighbour_weights_(n_followers_),
      neighbourhoods_(n_followers_),
      outgoing_(n_followers_),
      self_(n_followers_),
      inbox_(n_followers_),
      inputs_(n_followers_),
      solved_(2 * static_cast<size_t>(n_followers_), 0.0),
      clocks_(n_followers_, config.clock_offset, config.clock_drift_ppm, timestep, seed,
              config.clock_sync),
      leader_held_(n_followers_),
      sample_age_(n_followers_),
      coupling_radius_(CouplingSpectralRadius(graph)) {
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
  if (config.coupling == Coupling::kCentralSolve) {
    central_ = std::make_unique<CentralSolver>(graph);
  }
  SetUpRoundsOverLinks(seed);
}

AgentChannel::~AgentChannel() = default;

void AgentChannel::BeginTick(int64_t step, double time, const std::vector<mjfVehicleState>& truth,
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
  have_solution_ = false;
  if (over_links_) CollectRounds();
}

const mjfAgentInput& AgentChannel::Input(int follower, int round) {
  mjfAgentInput& in = inputs_[follower];
  // Instantaneous rounds r > 0 run in round 0's tick, on the messages round 0 fetched and
  // predicted: only their round part changes (Jacobi), or nothing (the central solve carries no
  // round messages: the host solves). Re-fetching and re-predicting would give the same bytes.
  if (round > 0 && !over_links_) {
    if (!central_) network_.RefreshRound(follower + 1, round - 1, &inbox_[follower]);
  } else {
    const mjfMessage* leader = nullptr;
    network_.Inbox(follower + 1, round > 0 ? round - 1 : -1, &inbox_[follower], &leader);
    if (config_.predict != Predict::kNone) {
      PredictInbox(follower, leader);
      if (leader) leader = &leader_held_[follower];
    }
    in.n_messages = static_cast<int>(inbox_[follower].size());
    in.messages = inbox_[follower].data();
    in.leader = leader;
  }
  in.follower = follower;
  in.self = &self_[follower];
  in.round = round;
  in.n_rounds = n_rounds_;
  mjfMessage& out = outgoing_[follower];
  out.round = round;
  out.n_payload = 0;
  in.outgoing = &out;
  const bool last = round == n_rounds_ - 1;
  in.solved = central_ && last && have_solution_ ? &solved_[2 * follower] : nullptr;
  return in;
}

// Each message carried from the time its state refers to up to this follower's sample time,
// both read on the clocks that stamped them: tau = c_i(now) - c_j(send time) (no common clock); with
// synchronised clocks both read the common time and tau is the message's true age.
void AgentChannel::PredictInbox(int follower, const mjfMessage* leader) {
  const double now = clocks_.Reading(follower + 1, time_);
  for (mjfMessage& m : inbox_[follower]) {
    PredictMessage(config_.predict, now - clocks_.Reading(m.sender, m.send_time), &m);
  }
  if (!leader) return;
  leader_held_[follower] = *leader;
  PredictMessage(config_.predict, now - leader->send_time, &leader_held_[follower]);
}

// Age of information where the law samples (a follower that wrote a payload in round 0): now
// minus the send time of the oldest message it acts on.
void AgentChannel::RecordSampleAge() {
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

void AgentChannel::EndRound(int round, const std::vector<mjfSetpoint>& setpoints) {
  if (round == 0) RecordSampleAge();
  for (int i = 0; i < n_followers_; ++i) {
    mjfMessage& out = outgoing_[i];
    out.sender = i + 1;
    out.send_time = time_;
    out.state = self_[i];
    out.input[0] = setpoints[i + 1].acc[0];
    out.input[1] = setpoints[i + 1].acc[1];
    out.input[2] = 0.0;
  }
  if (round == n_rounds_ - 1) return;
  if (central_) {
    CentralSolve();
    return;
  }
  for (int i = 0; i < n_followers_; ++i) {
    // A follower with nothing new this round (between samples) sends no round message.
    if (outgoing_[i].n_payload > 0) network_.ExchangeRound(i + 1, outgoing_[i]);
  }
}

// The reference: L_H W = R solved at once for the R_i the followers published (payload[2..3]).
// A follower that has not yet heard every in-neighbour (loss or latency at start-up) does not
// sample and publishes nothing (n_payload = 0); the system cannot be solved without its row, so
// that sample gets no solution and every follower closes its loop with the last inputs, as under
// last_input (counted in summary.json: network.central_solve_skipped_samples).
void AgentChannel::CentralSolve() {
  int sampled = 0;
  int published = 0;
  for (int i = 0; i < n_followers_; ++i) {
    sampled += outgoing_[i].n_payload > 0 ? 1 : 0;
    published += outgoing_[i].n_payload >= 4 ? 1 : 0;
  }
  if (sampled == 0) return;  // between samples
  if (published != sampled) {
    throw SimulationError(
        fmt::format("t = {:.3f} s: coupling = \"central_solve\": {} of {} followers that sampled "
                    "published R_i (payload[2..3]) in round 0; the plugin does not support the "
                    "central solve",
                    time_, published, sampled));
  }
  if (published != n_followers_) {
    ++central_skipped_samples_;
    return;
  }
  for (int i = 0; i < n_followers_; ++i) {
    central_->rhs(i, 0) = outgoing_[i].payload[2];
    central_->rhs(i, 1) = outgoing_[i].payload[3];
  }
  central_->solver.SolveInPlace(central_->rhs);
  for (int i = 0; i < n_followers_; ++i) {
    solved_[2 * i] = central_->rhs(i, 0);
    solved_[2 * i + 1] = central_->rhs(i, 1);
  }
  have_solution_ = true;
}

void AgentChannel::SolveGathered() {
  for (int i = 0; i < n_followers_; ++i) {
    central_->rhs(i, 0) = solver_rows_[2 * i];
    central_->rhs(i, 1) = solver_rows_[2 * i + 1];
  }
  central_->solver.SolveInPlace(central_->rhs);
  for (int i = 0; i < n_followers_; ++i) {
    solved_[2 * i] = central_->rhs(i, 0);
    solved_[2 * i + 1] = central_->rhs(i, 1);
  }
}

nlohmann::json AgentChannel::Summary() const {
  using Json = nlohmann::json;
  Json links = Json::array();
  for (int l = 0; l < network_.n_links(); ++l) {
    const network::LinkStats& st = network_.link(l).stats();
    const int64_t arrived = st.delivered;
    links.push_back({{"from", network_.spec(l).from},
                     {"to", network_.spec(l).to},
                     {"sent", st.sent},
                     {"delivered", st.delivered},
                     {"lost", st.lost},
                     {"stale_dropped", st.stale},
                     {"out_of_range", st.out_of_range},
                     {"latency_mean_s", arrived > 0 ? st.latency_sum / arrived : 0.0},
                     {"latency_max_s", st.latency_max},
                     {"round_messages_sent", st.rounds_sent},
                     {"round_messages_lost", st.rounds_lost}});
  }
  Json age = Json::array();
  for (int v = 1; v <= n_followers_; ++v) {
    age.push_back(
        {{"follower", v}, {"mean_s", network_.age(v).mean()}, {"max_s", network_.age(v).max}});
  }
  Json sample_age = Json::array();
  for (int i = 0; i < n_followers_; ++i) {
    sample_age.push_back({{"follower", i + 1},
                          {"samples", sample_age_[i].ticks},
                          {"mean_s", sample_age_[i].mean()},
                          {"max_s", sample_age_[i].max}});
  }
  Json events = Json::array();
  for (const auto& e : network_.events()) {
    if (events.size() >= 1000) break;  // the count below is complete
    events.push_back({{"time_s", e.time}, {"from", e.from}, {"to", e.to}, {"up", e.up}});
  }
  Json summary = {{"execution", ToString(config_.execution)},
                  {"coupling", ToString(config_.coupling)},
                  {"rounds_per_step", n_rounds_},
                  {"central_solve_skipped_samples", central_skipped_samples_},
                  {"jacobi_spectral_radius", spectral_radius_},
                  {"links", links},
                  {"age_of_information", age},
                  {"topology_switches", network_.events().size()},
                  {"topology_events", events},
                  {"time_without_spanning_tree_s", network_.time_without_spanning_tree()},
                  {"predict", ToString(config_.predict)},
                  // Instantaneous exchange rounds take no time (Jacobi: loss only; the central
                  // solve: at once, over every follower): that central solve is the ideal
                  // reference, not a protocol. Over the links they take their latency.
                  {"exchange_rounds", ToString(config_.rounds)},
                  {"oracle", config_.coupling == Coupling::kCentralSolve && !over_links_},
                  {"age_of_information_at_samples", sample_age},
                  {"clocks", ClocksSummary()}};
  if (over_links_) summary["rounds_over_links"] = RoundsSummary();
  return summary;
}

// The clocks as drawn (in phase: offsets and drifts all 0) and the exchange-round policy.
nlohmann::json AgentChannel::ClocksSummary() const {
  nlohmann::json offsets = nlohmann::json::array(), drifts = nlohmann::json::array();
  for (int i = 0; i < n_followers_; ++i) {
    offsets.push_back(clocks_.offset(i));
    drifts.push_back(clocks_.drift(i) * 1e6);
  }
  nlohmann::json clocks = {
      {"in_phase", !clocks_.active()}, {"offset_s", offsets}, {"drift_ppm", drifts}};
  // Written only when set, so that runs without it keep their summary's bytes.
  if (clocks_.synchronised()) clocks["synchronised"] = true;
  return clocks;
}

nlohmann::json AgentChannel::DelayMarginSummary(double period, double q) const {
  const DelayMargin m = PredictedDelayMargin(period, q, coupling_radius_);
  auto finite = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
  return {{"coupling_spectral_radius", coupling_radius_},
          {"period_s", period},
          {"q", q},
          {"without_prediction_s", finite(m.without_prediction)},
          {"with_prediction_s", finite(m.with_prediction)},
          {"with_prediction_is_lower_bound", m.with_prediction_capped},
          {"assumes", "a message every step, in-phase clocks, no loss (docs/NETWORK.md)"}};
}

}  // namespace mjf::runner
