// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Exchange rounds carried over the links ([network] rounds = "over_links"; the policy
// is in docs/NETWORK.md, "Exchange rounds over the links"):
//   - Jacobi: follower i's round r iterate w_i (payload[0..1]) goes to each out-neighbour over
//     the follower link, with its latency, jitter and loss. Round r + 1 of follower i runs when
//     the round r messages of every in-neighbour for the same sample have arrived (or the round
//     timeout passed: then the neighbours missing are coupled through their last input u_j, as
//     a lost instantaneous round is). Each round's result is applied as soon as it is computed
//     (anytime Jacobi): the setpoint between samples is the newest iterate.
//   - Central solve: R_i goes up to the solver, vehicle 0 (the leader), over a link with the
//     parameters of follower i's leader link (or [network]'s defaults), and W_i comes back down
//     on a link with the same parameters. The solver solves L_H W = R when it holds every R_i of
//     one sample (a sample is a physics step: followers out of phase never share one).
//   - A follower's exchange ends when its last round ran, or when it takes its next sample (the
//     rounds still missing are dropped: counted incomplete); a round message arriving for an
//     exchange that no longer waits for it is counted late, one for a sample the receiver did
//     not take unmatched.
// With latency 0 and no loss every round arrives in the step it is sent, and each round is
// handed exactly the input it gets instantaneously: the same bits (AgentChannelRoundsTest).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "mjformation/control/agent_channel.hpp"
#include "mjformation/control/errors.hpp"
#include "mjformation/time_steps.hpp"

namespace mjf::runner {
namespace {

// summary.json rounds_over_links.policy: when a round runs and what the follower flies meanwhile.
std::string PolicyText(RoundPolicy policy) {
  return std::string(
             "a round runs when the previous round of every in-neighbour (or W_i) has arrived, or "
             "on the timeout with u_j for what is missing; ") +
         (policy == RoundPolicy::kHold
              ? "the command of the last finished exchange is held until this one finishes; "
              : "each round's result is applied at once; ") +
         "the next sample drops the rounds still missing";
}

}  // namespace

void AgentChannel::SetUpRoundsOverLinks(uint64_t seed) {
  over_links_ = config_.rounds == ExchangeRounds::kOverLinks && n_rounds_ > 1;
  if (!over_links_) return;
  timeout_steps_ =
      config_.round_timeout > 0.0
          ? std::max<int64_t>(1, StepsAtOrAfter(config_.round_timeout, network_.timestep()))
          : 0;
  // The sample period was checked to be a whole number of steps where the law was made.
  steps_per_sample_ = NearestSteps(config_.sample_period, network_.timestep());
  held_acc_.assign(n_followers_, {0.0, 0.0});
  call_time_.assign(n_followers_, 0.0);
  call_step_.assign(n_followers_, 0);
  exchanges_.resize(n_followers_);
  round_stats_.resize(n_followers_);
  const size_t exchanged = static_cast<size_t>(n_rounds_ - 1);  // rounds 0 .. n_rounds - 2 sent
  for (int i = 0; i < n_followers_; ++i) {
    const size_t slots = exchanged * neighbour_ids_[i].size();
    exchanges_[i].got.assign(slots, 0);
    exchanges_[i].letters.resize(slots);
    exchanges_[i].inbox.reserve(neighbour_ids_[i].size());
    round_stats_[i].rounds_run.assign(static_cast<size_t>(n_rounds_), 0);
  }
  late_.assign(network_.n_links(), 0);
  unmatched_.assign(network_.n_links(), 0);
  if (!central_) return;
  // The solver's star: follower i's link pair takes its leader link's parameters when it has
  // one, else the [network] defaults; a range limit does not apply (the star is not the graph).
  solver_has_.assign(n_followers_, 0);
  solver_rows_.assign(2 * static_cast<size_t>(n_followers_), 0.0);
  up_late_.assign(n_followers_, 0);
  down_late_.assign(n_followers_, 0);
  for (int i = 0; i < n_followers_; ++i) {
    network::LinkParams params = config_.defaults;
    for (int l = 0; l < network_.n_links(); ++l) {
      if (network_.spec(l).from == 0 && network_.spec(l).to == i + 1) {
        params = network_.spec(l).params;
      }
    }
    params.range = 0.0;
    // Seeds after every graph link's: the graph's streams are the ones an instantaneous run has.
    const auto base = static_cast<uint64_t>(network_.n_links());
    solver_up_.emplace_back(params, network_.timestep(), network::LinkSeed(seed, base + i));
    solver_down_.emplace_back(params, network_.timestep(),
                              network::LinkSeed(seed, base + n_followers_ + i));
  }
}

void AgentChannel::HoldPendingCommands(std::vector<mjfSetpoint>* setpoints) {
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

void AgentChannel::SetCallContext(int follower, double local_time, int64_t local_step) {
  call_time_[follower] = local_time;
  call_step_[follower] = local_step;
}

// What the next broadcast carries besides the payload (as EndRound fills it).
void AgentChannel::FillOutgoing(int follower, const std::vector<mjfSetpoint>& setpoints) {
  mjfMessage& out = outgoing_[follower];
  out.sender = follower + 1;
  out.send_time = time_;
  out.state = self_[follower];
  out.input[0] = setpoints[follower + 1].acc[0];
  out.input[1] = setpoints[follower + 1].acc[1];
  out.input[2] = 0.0;
}

// Ends follower's exchange: finished (its last round ran) or dropped (a new sample, or the
// plugin stopped sampling).
void AgentChannel::EndExchange(int follower, bool finished) {
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
  const double took = static_cast<double>(step_ - ex.sample_step) * network_.timestep();
  st.completion_sum += took;
  st.completion_max = std::max(st.completion_max, took);
}

void AgentChannel::EndSampleRound(const std::vector<mjfSetpoint>& setpoints) {
  RecordSampleAge();
  for (int i = 0; i < n_followers_; ++i) {
    FillOutgoing(i, setpoints);
    mjfMessage& out = outgoing_[i];
    if (out.n_payload <= 0) continue;  // did not sample this tick
    if (central_ && out.n_payload < 4) {
      throw SimulationError(fmt::format(
          "t = {:.3f} s: coupling = \"central_solve\": follower {} sampled but published no R_i "
          "(payload[2..3]) in round 0; the plugin does not support the central solve",
          time_, i + 1));
    }
    Exchange& ex = exchanges_[i];
    if (ex.waiting) EndExchange(i, false);
    ++round_stats_[i].samples;
    ex.waiting = true;
    ex.sample_step = step_;
    ex.sample_index = call_step_[i] / steps_per_sample_;
    ex.local_time = call_time_[i];
    ex.local_step = call_step_[i];
    ex.next_round = 1;
    ex.round_start_step = step_;
    ex.timed_out = false;
    ex.self = self_[i];
    ex.inbox = inbox_[i];
    ex.has_leader = inputs_[i].leader != nullptr;
    if (ex.has_leader) ex.leader = *inputs_[i].leader;
    std::fill(ex.got.begin(), ex.got.end(), 0);
    ex.has_solved = false;
    if (central_) {
      // Tagged with the sample index: in phase the same one-to-one key as the step; out of
      // phase the solver gathers one index's R_i, taken up to clock_offset apart.
      up_in_flight_.Post(solver_up_[i], i, step_, ex.sample_index, out);
    } else {
      network_.SendRound(step_, i + 1, step_, out);
    }
  }
  CollectRounds();
}

// Every round message due now, in the order Jacobi letters, R_i at the solver (which may solve
// and send W_i), W_i at the followers: with latency 0 all of one step's traffic arrives in it.
void AgentChannel::CollectRounds() {
  letters_.clear();
  if (!central_) {
    network_.CollectRounds(step_, &letters_);
    for (const network::RoundLetter& letter : letters_) TakeJacobiLetter(letter);
    return;
  }
  up_in_flight_.Collect(step_, solver_up_, &letters_);
  for (const network::RoundLetter& letter : letters_) TakeSolverLetter(letter);
  letters_.clear();
  down_in_flight_.Collect(step_, solver_down_, &letters_);
  for (const network::RoundLetter& letter : letters_) TakeSolutionLetter(letter);
}

void AgentChannel::TakeJacobiLetter(const network::RoundLetter& letter) {
  const int receiver = network_.spec(letter.link).to - 1;
  const int sender = network_.spec(letter.link).from - 1;
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
  const auto& ids = neighbour_ids_[receiver];
  const auto m = static_cast<size_t>(std::find(ids.begin(), ids.end(), sender) - ids.begin());
  const size_t slot = static_cast<size_t>(round) * ids.size() + m;
  ex.got[slot] = 1;
  ex.letters[slot] = letter.message;
}

void AgentChannel::TakeSolverLetter(const network::RoundLetter& letter) {
  const int i = letter.link;  // the up-link index is the follower's
  if (letter.sample_step < solver_sample_) {
    ++up_late_[i];
    return;
  }
  if (letter.sample_step > solver_sample_) {
    // A newer sample begins: an older one still missing some R_i cannot be solved any more.
    if (solver_count_ > 0) ++central_skipped_samples_;
    solver_sample_ = letter.sample_step;
    std::fill(solver_has_.begin(), solver_has_.end(), 0);
    solver_count_ = 0;
  }
  if (solver_has_[i]) return;  // one R_i per sample and follower: cannot repeat
  solver_has_[i] = 1;
  ++solver_count_;
  solver_rows_[2 * i] = letter.message.payload[2];
  solver_rows_[2 * i + 1] = letter.message.payload[3];
  if (solver_count_ < n_followers_) return;
  SolveGathered();
  ++solver_solves_;
  solver_count_ = 0;
  std::fill(solver_has_.begin(), solver_has_.end(), 0);
  for (int f = 0; f < n_followers_; ++f) {
    mjfMessage w{};
    w.sender = 0;
    w.round = 0;
    w.send_time = time_;
    w.n_payload = 2;
    w.payload[0] = solved_[2 * f];
    w.payload[1] = solved_[2 * f + 1];
    down_in_flight_.Post(solver_down_[f], f, step_, solver_sample_, w);
  }
}

void AgentChannel::TakeSolutionLetter(const network::RoundLetter& letter) {
  const int i = letter.link;
  Exchange& ex = exchanges_[i];
  if (!ex.waiting || ex.sample_index != letter.sample_step) {
    ++down_late_[i];
    return;
  }
  ex.has_solved = true;
  ex.solved[0] = letter.message.payload[0];
  ex.solved[1] = letter.message.payload[1];
}

bool AgentChannel::RoundInputsArrived(int follower) const {
  const Exchange& ex = exchanges_[follower];
  if (central_) return ex.has_solved;
  const size_t degree = neighbour_ids_[follower].size();
  const size_t first = static_cast<size_t>(ex.next_round - 1) * degree;
  return std::all_of(ex.got.begin() + static_cast<std::ptrdiff_t>(first),
                     ex.got.begin() + static_cast<std::ptrdiff_t>(first + degree),
                     [](char g) { return g != 0; });
}

int AgentChannel::NextContinuedRound(int* round, double* local_time, int64_t* local_step) {
  for (int i = 0; i < n_followers_; ++i) {
    Exchange& ex = exchanges_[i];
    if (!ex.waiting) continue;
    const bool arrived = RoundInputsArrived(i);
    const bool timed_out =
        !arrived && timeout_steps_ > 0 && step_ - ex.round_start_step >= timeout_steps_;
    if (!arrived && !timed_out) continue;
    if (timed_out) ex.timed_out = true;
    *round = ex.next_round;
    *local_time = ex.local_time;
    *local_step = ex.local_step;
    return i;
  }
  return -1;
}

const mjfAgentInput& AgentChannel::ContinuedInput(int follower, int round) {
  Exchange& ex = exchanges_[follower];
  std::vector<mjfMessage>& inbox = inbox_[follower];
  inbox = ex.inbox;
  if (!central_) {
    // The neighbours' round r - 1 iterates that arrived; the others keep what they held at the
    // sample (the plugin couples them through u_j, as it does a lost instantaneous round).
    const size_t degree = neighbour_ids_[follower].size();
    for (mjfMessage& m : inbox) {
      const auto& ids = neighbour_ids_[follower];
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
  mjfAgentInput& in = inputs_[follower];
  in.follower = follower;
  in.self = &ex.self;
  in.n_messages = static_cast<int>(inbox.size());
  in.messages = inbox.data();
  in.leader = ex.has_leader ? &ex.leader : nullptr;
  in.round = round;
  in.n_rounds = n_rounds_;
  mjfMessage& out = outgoing_[follower];
  out.round = round;
  out.n_payload = 0;
  in.outgoing = &out;
  in.solved = central_ && ex.has_solved ? ex.solved : nullptr;
  return in;
}

void AgentChannel::EndContinuedRound(int follower, int round,
                                     const std::vector<mjfSetpoint>& setpoints) {
  FillOutgoing(follower, setpoints);
  Exchange& ex = exchanges_[follower];
  if (outgoing_[follower].n_payload <= 0) {
    // The plugin did not take this round as part of the sample: the exchange is over.
    EndExchange(follower, false);
    return;
  }
  ex.next_round = round + 1;
  ex.round_start_step = step_;
  if (round == n_rounds_ - 1) {
    EndExchange(follower, true);
    return;
  }
  network_.SendRound(step_, follower + 1, ex.sample_step, outgoing_[follower]);
  CollectRounds();
}

// The central solve's star of links to the solver (vehicle 0) and back.
nlohmann::json AgentChannel::SolverStarSummary() const {
  using Json = nlohmann::json;
  Json star = Json::array();
  auto one = [](const network::Link& link, int64_t late) {
    const network::LinkStats& st = link.stats();
    return Json{{"sent", st.rounds_sent},
                {"lost", st.rounds_lost},
                {"delivered", st.rounds_delivered},
                {"latency_mean_s",
                 st.rounds_delivered > 0 ? st.round_latency_sum / st.rounds_delivered : 0.0},
                {"latency_max_s", st.round_latency_max},
                {"late", late}};
  };
  for (int i = 0; i < n_followers_; ++i) {
    star.push_back({{"follower", i + 1},
                    {"up_r", one(solver_up_[i], up_late_[i])},
                    {"down_w", one(solver_down_[i], down_late_[i])}});
  }
  return {{"node", 0},
          {"what",
           "vehicle 0 (the leader) solves L_H W = R when it holds every R_i of one "
           "sample; R_i up and W_i down on a star of links with each follower's "
           "leader-link parameters"},
          {"solves", solver_solves_},
          {"links", star}};
}

nlohmann::json AgentChannel::RoundsSummary() const {
  using Json = nlohmann::json;
  Json followers = Json::array();
  RoundStats total;
  total.rounds_run.assign(static_cast<size_t>(n_rounds_), 0);
  int64_t in_progress = 0;
  for (int i = 0; i < n_followers_; ++i) {
    const RoundStats& st = round_stats_[i];
    const int64_t finished = st.complete + st.timed_out;
    const bool open = exchanges_[i].waiting;
    followers.push_back({{"follower", i + 1},
                         {"samples", st.samples},
                         {"complete", st.complete},
                         {"timed_out", st.timed_out},
                         {"incomplete", st.incomplete},
                         {"in_progress_at_end", open ? 1 : 0},
                         {"rounds_run", st.rounds_run},
                         {"completion_mean_s", finished > 0 ? st.completion_sum / finished : 0.0},
                         {"completion_max_s", st.completion_max}});
    total.samples += st.samples;
    total.complete += st.complete;
    total.timed_out += st.timed_out;
    total.incomplete += st.incomplete;
    total.completion_sum += st.completion_sum;
    total.completion_max = std::max(total.completion_max, st.completion_max);
    for (size_t k = 0; k < st.rounds_run.size(); ++k) total.rounds_run[k] += st.rounds_run[k];
    in_progress += open ? 1 : 0;
  }
  Json links = Json::array();
  for (int l = 0; l < network_.n_links(); ++l) {
    if (network_.spec(l).from == 0) continue;  // rounds travel on follower links only
    const network::LinkStats& st = network_.link(l).stats();
    links.push_back({{"from", network_.spec(l).from},
                     {"to", network_.spec(l).to},
                     {"round_messages_delivered", st.rounds_delivered},
                     {"round_latency_mean_s",
                      st.rounds_delivered > 0 ? st.round_latency_sum / st.rounds_delivered : 0.0},
                     {"round_latency_max_s", st.round_latency_max},
                     {"round_messages_late", late_[l]},
                     {"round_messages_unmatched", unmatched_[l]}});
  }
  const Json solver = central_ ? SolverStarSummary() : Json(nullptr);
  const int64_t finished = total.complete + total.timed_out;
  return {{"round_timeout_s", config_.round_timeout},
          {"round_policy", ToString(config_.round_policy)},
          {"policy", PolicyText(config_.round_policy)},
          {"samples", total.samples},
          {"complete", total.complete},
          {"timed_out", total.timed_out},
          {"incomplete", total.incomplete},
          {"in_progress_at_end", in_progress},
          {"rounds_run", total.rounds_run},
          {"completion_mean_s", finished > 0 ? total.completion_sum / finished : 0.0},
          {"completion_max_s", total.completion_max},
          {"followers", followers},
          {"links", links},
          {"solver", solver}};
}

}  // namespace mjf::runner
