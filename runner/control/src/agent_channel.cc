// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/control/agent_channel.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "mjformation/control/central_solver.hpp"
#include "mjformation/control/channel_summary.hpp"
#include "mjformation/control/delay_margin.hpp"
#include "mjformation/control/rounds_over_links.hpp"
#include "mjformation/formation/discrete_smc_agent.hpp"
#include "mjformation/formation/graph.hpp"
#include "mjformation/time_steps.hpp"

namespace mjf::runner {
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

// Each link's parameters with the key that sets them: [network] for the defaults, the
// [[network.link]] table of each override.
std::vector<std::pair<std::string, network::LinkParams>> KeyedLinks(const NetworkConfig& n) {
  std::vector<std::pair<std::string, network::LinkParams>> links = {{"[network]", n.defaults}};
  for (const NetworkConfig::LinkOverride& o : n.links) {
    links.emplace_back(fmt::format("[[network.link]] from = {}, to = {}:", o.from, o.to), o.params);
  }
  return links;
}

}  // namespace

std::string NativeNetworkRefusal(const NetworkConfig& n, double timestep) {
  if (n.execution != Execution::kPerAgent) return "";
  for (const auto& [key, p] : KeyedLinks(n)) {
    const int64_t in_flight = network::MaxInFlight(p, timestep);
    if (in_flight > kNativeMessagesInFlight) {
      return fmt::format(
          "{} latency = {} s and jitter = {} s at a broadcast every {} physics steps keep up to "
          "{} messages in flight on a link; the native MuJoCo plugin holds at most {} (its "
          "queues are part of plugin_state, copied every step): shorten the delay, lower the "
          "rate or fly the experiment with `mjformation run`",
          key, p.latency, p.jitter, p.period_steps, in_flight, kNativeMessagesInFlight);
    }
    if (n.rounds != ExchangeRounds::kOverLinks) continue;
    // The most a link carries: Jacobi's rounds 0 .. n - 2 a sample (the central solve's star
    // carries one R_i and one W_i, fewer).
    const int64_t letters = network::MaxRoundLettersInFlight(
        p, timestep, std::max(1, RoundsFor(n) - 1), NearestSteps(n.sample_period, timestep));
    if (letters > kNativeMessagesInFlight) {
      return fmt::format(
          "{} latency = {} s and jitter = {} s with {} exchange rounds a sample every {} s keep "
          "up to {} round letters in flight on a link; the native MuJoCo plugin holds at most "
          "{}: shorten the delay, use fewer rounds or fly the experiment with `mjformation run`",
          key, p.latency, p.jitter, RoundsFor(n) - 1, n.sample_period, letters,
          kNativeMessagesInFlight);
    }
  }
  return "";
}

AgentChannel::AgentChannel(const formation::Graph& graph, const NetworkConfig& config,
                           double timestep, uint64_t seed)
    : config_(config),
      n_rounds_(RoundsFor(config)),
      spectral_radius_(formation::JacobiSpectralRadius(graph)),
      coupling_radius_(CouplingSpectralRadius(graph)),
      routing_(graph, config, n_rounds_, timestep, seed),
      clocks_(graph.num_followers(), config.clock_offset, config.clock_drift_ppm, timestep, seed,
              config.clock_sync),
      prediction_(config.predict, graph.num_followers()) {
  if (config.coupling == Coupling::kCentralSolve) {
    central_ = std::make_unique<CentralSolver>(graph);
  }
  if (config.rounds != ExchangeRounds::kOverLinks || n_rounds_ <= 1) return;
  rounds_ = std::make_unique<RoundsOverLinks>(&routing_, central_.get(), config, n_rounds_);
  // The star's streams follow every graph link's: the graph keeps an instantaneous run's.
  if (!central_) return;
  central_->SetUpStar(routing_.network(), config.defaults, seed);
  central_->SetStarCapacity(1, NearestSteps(config.sample_period, timestep));
}

AgentChannel::~AgentChannel() = default;

void AgentChannel::BeginTick(int64_t step, double time, const std::vector<mjfVehicleState>& truth,
                             const std::vector<mjfVehicleState>& measured,
                             const std::vector<mjfSetpoint>& setpoints) {
  routing_.BeginTick(step, time, truth, measured, setpoints);
  if (central_) central_->ClearSolution();
  if (rounds_) rounds_->CollectRounds();
}

const mjfAgentInput& AgentChannel::Input(int follower, int round) {
  mjfAgentInput& in = routing_.input(follower);
  // Instantaneous rounds r > 0 run in round 0's tick, on the messages round 0 fetched and
  // predicted: only their round part changes (Jacobi), or nothing (the central solve carries no
  // round messages: the host solves). Re-fetching and re-predicting would give the same bytes.
  if (round > 0 && !rounds_) {
    if (!central_) routing_.RefreshRound(follower, round - 1);
  } else {
    std::vector<mjfMessage>& inbox = routing_.inbox(follower);
    const mjfMessage* leader = routing_.FetchInbox(follower, round > 0 ? round - 1 : -1);
    in.leader = prediction_.PredictInbox(follower, clocks_, routing_.time(), &inbox, leader);
    in.n_messages = static_cast<int>(inbox.size());
    in.messages = inbox.data();
  }
  in.follower = follower;
  in.self = &routing_.self(follower);
  in.round = round;
  in.n_rounds = n_rounds_;
  in.outgoing = routing_.OpenOutgoing(follower, round);
  const bool last = round == n_rounds_ - 1;
  in.solved = central_ && last ? central_->solution(follower) : nullptr;
  return in;
}

void AgentChannel::EndRound(int round, const std::vector<mjfSetpoint>& setpoints) {
  if (round == 0) routing_.RecordSampleAge();
  for (int i = 0; i < routing_.n_followers(); ++i) routing_.FillOutgoing(i, setpoints);
  if (round == n_rounds_ - 1) return;
  if (central_) {
    central_->SolvePublished(routing_.outgoing(), routing_.time());
    return;
  }
  routing_.ExchangeRound();
}

void AgentChannel::SetCallContext(int follower, double local_time, int64_t local_step) {
  rounds_->SetCallContext(follower, local_time, local_step);
}

void AgentChannel::EndSampleRound(const std::vector<mjfSetpoint>& setpoints) {
  routing_.RecordSampleAge();
  rounds_->StartExchanges(setpoints);
}

int AgentChannel::NextContinuedRound(int* round, double* local_time, int64_t* local_step) {
  return rounds_->NextContinuedRound(round, local_time, local_step);
}

const mjfAgentInput& AgentChannel::ContinuedInput(int follower, int round) {
  return rounds_->ContinuedInput(follower, round);
}

void AgentChannel::EndContinuedRound(int follower, int round,
                                     const std::vector<mjfSetpoint>& setpoints) {
  rounds_->EndContinuedRound(follower, round, setpoints);
}

void AgentChannel::HoldPendingCommands(std::vector<mjfSetpoint>* setpoints) {
  rounds_->HoldPendingCommands(setpoints);
}

void AgentChannel::VisitState(FixedStateArchive& archive) {
  routing_.VisitState(archive);
  if (central_) central_->VisitState(archive);
  if (rounds_) rounds_->VisitState(archive);
}

nlohmann::json AgentChannel::Summary() const {
  return NetworkSummary(
      {config_, n_rounds_, spectral_radius_, routing_, central_.get(), rounds_.get(), clocks_});
}

}  // namespace mjf::runner
