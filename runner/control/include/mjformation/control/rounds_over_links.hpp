// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The exchange-round state machine over the links ([network] rounds = "over_links"; the policy
// is in docs/NETWORK.md, "Exchange rounds over the links"):
//   - Jacobi: follower i's round r iterate w_i (payload[0..1]) goes to each out-neighbour over
//     the follower link, with its latency, jitter and loss. Round r + 1 of follower i runs when
//     the round r messages of every in-neighbour for the same sample have arrived (or the round
//     timeout passed: then the neighbours missing are coupled through their last input u_j, as
//     a lost instantaneous round is). Each round's result is applied as soon as it is computed
//     (anytime Jacobi): the setpoint between samples is the newest iterate.
//   - Central solve: R_i goes up to the solver and W_i comes back down (CentralSolver's star);
//     round 1 runs when W_i arrived.
//   - A follower's exchange ends when its last round ran, or when it takes its next sample (the
//     rounds still missing are dropped: counted incomplete); a round message arriving for an
//     exchange that no longer waits for it is counted late, one for a sample the receiver did
//     not take unmatched.
// With latency 0 and no loss every round arrives in the step it is sent, and each round is
// handed exactly the input it gets instantaneously: the same bits (AgentChannelRoundsTest).
// Pure: no MuJoCo.
#ifndef MJFORMATION_CONTROL_ROUNDS_OVER_LINKS_HPP_
#define MJFORMATION_CONTROL_ROUNDS_OVER_LINKS_HPP_

#include <mjformation/plugin.h>

#include <array>
#include <cstdint>
#include <vector>

#include "mjformation/config/experiment.hpp"
#include "mjformation/control/agent_routing.hpp"
#include "mjformation/control/central_solver.hpp"
#include "mjformation/network/message_state.hpp"
#include "mjformation/network/round_courier.hpp"

namespace mjf::runner {

class RoundsOverLinks {
 public:
  // One follower's exchange of one sample: its round-0 input, frozen, and what has arrived.
  struct Exchange {
    bool waiting = false;      // rounds of this sample still to run
    int64_t sample_step = -1;  // the physics step the sample was taken at
    // Its index on the follower's own clock, local step / steps per sample: the central solve
    // over links gathers the R_i of one index (followers out of phase share it).
    int64_t sample_index = -1;
    double local_time = 0.0;  // the follower's clock then (handed back to the plugin)
    int64_t local_step = 0;
    int next_round = 1;            // the round it runs when its inputs are there
    int64_t round_start_step = 0;  // when it ran round next_round - 1 (for the timeout)
    bool timed_out = false;        // some round ran on the timeout with inputs missing
    mjfVehicleState self{};
    std::vector<mjfMessage> inbox;  // as handed in round 0 (predicted, when predict is on)
    mjfMessage leader{};
    bool has_leader = false;
    std::vector<char> got;            // [round * degree + m]: neighbour m's round message arrived
    std::vector<mjfMessage> letters;  // [round * degree + m]
    bool has_solved = false;          // central solve: W_i of this sample arrived
    double solved[2] = {0.0, 0.0};
  };
  struct RoundStats {
    int64_t samples = 0;              // exchanges started (samples taken)
    int64_t complete = 0;             // every round ran with all its inputs
    int64_t timed_out = 0;            // every round ran, some on the timeout with inputs missing
    int64_t incomplete = 0;           // ended before the last round (the next sample came first)
    std::vector<int64_t> rounds_run;  // [k]: ended samples in which k rounds after round 0 ran
    double completion_sum = 0.0;      // s, sample to last round (complete or timed out)
    double completion_max = 0.0;
  };

  // routing: the links, inboxes and messages the rounds travel on; central: the solver star for
  // coupling = "central_solve" (null for Jacobi). Both outlive this.
  RoundsOverLinks(AgentRouting* routing, CentralSolver* central, const NetworkConfig& config,
                  int n_rounds);

  int n_followers() const { return n_followers_; }
  int n_rounds() const { return n_rounds_; }
  const NetworkConfig& config() const { return config_; }
  // Follower's clock reading of this tick's round 0 (the sample's, if it samples).
  void SetCallContext(int follower, double local_time, int64_t local_step);
  // After every follower's round 0: a follower that sampled starts an exchange (posts its round
  // 0, or its R_i to the solver); then what arrived in this step is collected.
  void StartExchanges(const std::vector<mjfSetpoint>& setpoints);
  // Every round message due at the routing's step, handed to the exchanges waiting for it.
  void CollectRounds();
  // The first follower whose next round can run now (its inputs arrived, or the round timeout
  // passed), or -1; *round, *local_time, *local_step: that round and its sample's clock reading.
  int NextContinuedRound(int* round, double* local_time, int64_t* local_step);
  const mjfAgentInput& ContinuedInput(int follower, int round);
  void EndContinuedRound(int follower, int round, const std::vector<mjfSetpoint>& setpoints);
  // round_policy = "hold": a follower whose exchange is still running flies the command of its
  // last finished exchange (setpoint acc x, y); one whose exchange has ended keeps its plugin's
  // command, which becomes the held one.
  void HoldPendingCommands(std::vector<mjfSetpoint>* setpoints);

  // Everything the rounds carry from step to step, of a length fixed at construction (the
  // control tick's state, AgentChannel::VisitState): each follower's exchange (its inbox as a
  // bounded queue of its in-neighbours' messages) and counts, each link's late and unmatched
  // letters, the held commands. The letters in flight are the network's and the star's.
  template <typename Archive>
  void VisitState(Archive& archive) {
    for (int i = 0; i < n_followers_; ++i) {
      Exchange& ex = exchanges_[i];
      archive(ex.waiting, ex.sample_step, ex.sample_index, ex.local_time, ex.local_step,
              ex.next_round, ex.round_start_step, ex.timed_out, ex.self);
      network::VisitBounded(archive, ex.inbox, routing_.neighbour_ids(i).size(),
                            "an exchange's inbox",
                            [](Archive& a, mjfMessage& m) { network::VisitMessage(a, m); });
      network::VisitMessage(archive, ex.leader);
      archive(ex.has_leader, ex.got);
      network::VisitMessages(archive, ex.letters);
      archive(ex.has_solved, ex.solved);
      RoundStats& st = round_stats_[i];
      archive(st.samples, st.complete, st.timed_out, st.incomplete, st.rounds_run,
              st.completion_sum, st.completion_max);
    }
    archive(late_, unmatched_, held_acc_);
  }

  const Exchange& exchange(int follower) const { return exchanges_[follower]; }
  const RoundStats& stats(int follower) const { return round_stats_[follower]; }
  int64_t late(int link) const { return late_[link]; }
  int64_t unmatched(int link) const { return unmatched_[link]; }

 private:
  void TakeJacobiLetter(const network::RoundLetter& letter);
  void TakeSolutionLetter(const network::RoundLetter& letter);
  void StartExchange(int follower);
  void EndExchange(int follower, bool finished);
  bool RoundInputsArrived(int follower) const;

  AgentRouting& routing_;
  CentralSolver* central_;
  NetworkConfig config_;
  int n_followers_;
  int n_rounds_;
  int64_t timeout_steps_ = 0;      // round_timeout in steps (0: none)
  int64_t steps_per_sample_ = 1;   // T in physics steps (the sample index's divisor)
  std::vector<double> call_time_;  // [follower] clock reading of this tick's round 0
  std::vector<int64_t> call_step_;
  std::vector<Exchange> exchanges_;      // [follower] its current sample's rounds
  std::vector<RoundStats> round_stats_;  // [follower]
  std::vector<network::RoundLetter> letters_;
  std::vector<int64_t> late_, unmatched_;        // [link] round messages nobody waited for any more
  std::vector<std::array<double, 2>> held_acc_;  // [follower] round_policy = "hold"
};

}  // namespace mjf::runner

#endif  // MJFORMATION_CONTROL_ROUNDS_OVER_LINKS_HPP_
