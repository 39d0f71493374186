// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/control/rounds_over_links.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "mjformation/control/errors.hpp"
#include "mjformation/time_steps.hpp"

namespace mjf::runner {

RoundsOverLinks::RoundsOverLinks(AgentRouting* routing, CentralSolver* central,
                                 const NetworkConfig& config, int n_rounds)
    : routing_(*routing),
      central_(central),
      config_(config),
      n_followers_(routing->n_followers()),
      n_rounds_(n_rounds) {
  const double timestep = routing_.network().timestep();
  timeout_steps_ = config_.round_timeout > 0.0
                       ? std::max<int64_t>(1, StepsAtOrAfter(config_.round_timeout, timestep))
                       : 0;
  // The sample period was checked to be a whole number of steps where the law was made.
  steps_per_sample_ = NearestSteps(config_.sample_period, timestep);
  held_acc_.assign(n_followers_, {0.0, 0.0});
  call_time_.assign(n_followers_, 0.0);
  call_step_.assign(n_followers_, 0);
  exchanges_.resize(n_followers_);
  round_stats_.resize(n_followers_);
  const size_t exchanged = static_cast<size_t>(n_rounds_ - 1);  // rounds 0 .. n_rounds - 2 sent
  for (int i = 0; i < n_followers_; ++i) {
    const size_t slots = exchanged * routing_.neighbour_ids(i).size();
    exchanges_[i].got.assign(slots, 0);
    exchanges_[i].letters.resize(slots);
    exchanges_[i].inbox.reserve(routing_.neighbour_ids(i).size());
    round_stats_[i].rounds_run.assign(static_cast<size_t>(n_rounds_), 0);
  }
  late_.assign(routing_.network().n_links(), 0);
  unmatched_.assign(routing_.network().n_links(), 0);
  // The fixed-length state's bound on Jacobi letters in flight: rounds 0 .. n_rounds - 2 of a
  // sample go out on every follower link (the central solve's travel over its star instead,
  // bounded by AgentChannel once the star is set up).
  if (central_) return;
  network::Network& network = routing_.network();
  int64_t letters = 0;
  for (int l = 0; l < network.n_links(); ++l) {
    if (network.spec(l).from == 0) continue;
    letters += network::MaxRoundLettersInFlight(network.spec(l).params, timestep, n_rounds_ - 1,
                                                steps_per_sample_);
  }
  network.SetRoundCapacity(static_cast<size_t>(letters));
}

void RoundsOverLinks::HoldPendingCommands(std::vector<mjfSetpoint>* setpoints) {
  if (config_.round_policy != RoundPolicy::kHold) return;
  for (int i = 0; i < n_followers_; ++i) {
    double* acc = (*setpoints)[i + 1].acc;
    if (exchanges_[i].waiting) {
      acc[0] = held_acc_[i][0];
      acc[1] = held_acc_[i][1];
    } else {
      held_acc_[i] = {acc[0], acc[1]};
    }
  }
}

void RoundsOverLinks::SetCallContext(int follower, double local_time, int64_t local_step) {
  call_time_[follower] = local_time;
  call_step_[follower] = local_step;
}

// Ends follower's exchange: finished (its last round ran) or dropped (a new sample, or the
// plugin stopped sampling).
void RoundsOverLinks::EndExchange(int follower, bool finished) {
  Exchange& ex = exchanges_[follower];
  RoundStats& st = round_stats_[follower];
  ex.waiting = false;
  const int ran = ex.next_round - 1;  // rounds after round 0
  ++st.rounds_run[static_cast<size_t>(std::clamp(ran, 0, n_rounds_ - 1))];
  if (!finished) {
    ++st.incomplete;
    return;
  }
  ++(ex.timed_out ? st.timed_out : st.complete);
  const double took =
      static_cast<double>(routing_.step() - ex.sample_step) * routing_.network().timestep();
  st.completion_sum += took;
  st.completion_max = std::max(st.completion_max, took);
}

void RoundsOverLinks::StartExchanges(const std::vector<mjfSetpoint>& setpoints) {
  for (int i = 0; i < n_followers_; ++i) {
    routing_.FillOutgoing(i, setpoints);
    const mjfMessage& out = routing_.outgoing(i);
    if (out.n_payload <= 0) continue;  // did not sample this tick
    if (central_ && out.n_payload < 4) {
      throw SimulationError(fmt::format(
          "t = {:.3f} s: coupling = \"central_solve\": follower {} sampled but published no R_i "
          "(payload[2..3]) in round 0; the plugin does not support the central solve",
          routing_.time(), i + 1));
    }
    StartExchange(i);
  }
  CollectRounds();
}

// Freezes follower's round-0 input for the rounds to come and sends its round 0 (or R_i).
void RoundsOverLinks::StartExchange(int follower) {
  const int64_t step = routing_.step();
  Exchange& ex = exchanges_[follower];
  if (ex.waiting) EndExchange(follower, false);
  ++round_stats_[follower].samples;
  ex.waiting = true;
  ex.sample_step = step;
  ex.sample_index = call_step_[follower] / steps_per_sample_;
  ex.local_time = call_time_[follower];
  ex.local_step = call_step_[follower];
  ex.next_round = 1;
  ex.round_start_step = step;
  ex.timed_out = false;
  ex.self = routing_.self(follower);
  ex.inbox = routing_.inbox(follower);
  const mjfAgentInput& in = routing_.input(follower);
  ex.has_leader = in.leader != nullptr;
  if (ex.has_leader) ex.leader = *in.leader;
  std::fill(ex.got.begin(), ex.got.end(), 0);
  ex.has_solved = false;
  const mjfMessage& out = routing_.outgoing(follower);
  if (central_) {
    central_->PostR(follower, step, ex.sample_index, out);
  } else {
    routing_.network().SendRound(step, follower + 1, step, out);
  }
}

// Every round message due now, in the order Jacobi letters, R_i at the solver (which may solve
// and send W_i), W_i at the followers: with latency 0 all of one step's traffic arrives in it.
void RoundsOverLinks::CollectRounds() {
  const int64_t step = routing_.step();
  letters_.clear();
  if (!central_) {
    routing_.network().CollectRounds(step, &letters_);
    for (const network::RoundLetter& letter : letters_) TakeJacobiLetter(letter);
    return;
  }
  central_->CollectAtSolver(step, routing_.time());
  central_->CollectSolutions(step, &letters_);
  for (const network::RoundLetter& letter : letters_) TakeSolutionLetter(letter);
}

void RoundsOverLinks::TakeJacobiLetter(const network::RoundLetter& letter) {
  const network::LinkSpec& spec = routing_.network().spec(letter.link);
  const int receiver = spec.to - 1;
  const int sender = spec.from - 1;
  Exchange& ex = exchanges_[receiver];
  if (letter.sample_step > ex.sample_step) {
    ++unmatched_[letter.link];  // the receiver took no sample at that step
    return;
  }
  const int round = letter.message.round;
  // Round r is read by round r + 1: useful while the receiver has not run round r + 1 yet.
  if (letter.sample_step < ex.sample_step || !ex.waiting || round + 1 < ex.next_round) {
    ++late_[letter.link];
    return;
  }
  const auto& ids = routing_.neighbour_ids(receiver);
  const auto m = static_cast<size_t>(std::find(ids.begin(), ids.end(), sender) - ids.begin());
  const size_t slot = static_cast<size_t>(round) * ids.size() + m;
  ex.got[slot] = 1;
  ex.letters[slot] = letter.message;
}

void RoundsOverLinks::TakeSolutionLetter(const network::RoundLetter& letter) {
  const int i = letter.link;
  Exchange& ex = exchanges_[i];
  if (!ex.waiting || ex.sample_index != letter.sample_step) {
    central_->CountLateSolution(i);
    return;
  }
  ex.has_solved = true;
  ex.solved[0] = letter.message.payload[0];
  ex.solved[1] = letter.message.payload[1];
}

bool RoundsOverLinks::RoundInputsArrived(int follower) const {
  const Exchange& ex = exchanges_[follower];
  if (central_) return ex.has_solved;
  const size_t degree = routing_.neighbour_ids(follower).size();
  const size_t first = static_cast<size_t>(ex.next_round - 1) * degree;
  return std::all_of(ex.got.begin() + static_cast<std::ptrdiff_t>(first),
                     ex.got.begin() + static_cast<std::ptrdiff_t>(first + degree),
                     [](char g) { return g != 0; });
}

int RoundsOverLinks::NextContinuedRound(int* round, double* local_time, int64_t* local_step) {
  for (int i = 0; i < n_followers_; ++i) {
    Exchange& ex = exchanges_[i];
    if (!ex.waiting) continue;
    const bool arrived = RoundInputsArrived(i);
    const bool timed_out =
        !arrived && timeout_steps_ > 0 && routing_.step() - ex.round_start_step >= timeout_steps_;
    if (!arrived && !timed_out) continue;
    if (timed_out) ex.timed_out = true;
    *round = ex.next_round;
    *local_time = ex.local_time;
    *local_step = ex.local_step;
    return i;
  }
  return -1;
}

const mjfAgentInput& RoundsOverLinks::ContinuedInput(int follower, int round) {
  Exchange& ex = exchanges_[follower];
  std::vector<mjfMessage>& inbox = routing_.inbox(follower);
  inbox = ex.inbox;
  if (!central_) {
    // The neighbours' round r - 1 iterates that arrived; the others keep what they held at the
    // sample (the plugin couples them through u_j, as it does a lost instantaneous round).
    const auto& ids = routing_.neighbour_ids(follower);
    const size_t degree = ids.size();
    for (mjfMessage& m : inbox) {
      const auto k =
          static_cast<size_t>(std::find(ids.begin(), ids.end(), m.sender - 1) - ids.begin());
      const size_t slot = static_cast<size_t>(round - 1) * degree + k;
      if (k >= degree || !ex.got[slot]) continue;
      const mjfMessage& letter = ex.letters[slot];
      m.round = round - 1;
      m.n_payload = letter.n_payload;
      std::copy(letter.payload, letter.payload + MJF_MESSAGE_PAYLOAD, m.payload);
    }
  }
  mjfAgentInput& in = routing_.input(follower);
  in.follower = follower;
  in.self = &ex.self;
  in.n_messages = static_cast<int>(inbox.size());
  in.messages = inbox.data();
  in.leader = ex.has_leader ? &ex.leader : nullptr;
  in.round = round;
  in.n_rounds = n_rounds_;
  in.outgoing = routing_.OpenOutgoing(follower, round);
  in.solved = central_ && ex.has_solved ? ex.solved : nullptr;
  return in;
}

void RoundsOverLinks::EndContinuedRound(int follower, int round,
                                        const std::vector<mjfSetpoint>& setpoints) {
  routing_.FillOutgoing(follower, setpoints);
  Exchange& ex = exchanges_[follower];
  if (routing_.outgoing(follower).n_payload <= 0) {
    // The plugin did not take this round as part of the sample: the exchange is over.
    EndExchange(follower, false);
    return;
  }
  ex.next_round = round + 1;
  ex.round_start_step = routing_.step();
  if (round == n_rounds_ - 1) {
    EndExchange(follower, true);
    return;
  }
  routing_.network().SendRound(routing_.step(), follower + 1, ex.sample_step,
                               routing_.outgoing(follower));
  CollectRounds();
}

}  // namespace mjf::runner
