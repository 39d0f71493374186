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
#include "mjformation/network/round_courier.hpp"

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

  // Exchange rounds over the links ([network] rounds = "over_links" with coupling = "jacobi" or
  // "central_solve", docs/NETWORK.md; agent_channel_rounds.cc). The control tick then runs:
  // BeginTick; ContinueRounds (earlier samples' rounds whose inputs have arrived); round 0 of
  // every follower (SetCallContext, Input(i, 0), the plugin); EndSampleRound (a follower that
  // sampled posts round 0, or R_i to the solver); ContinueRounds again (what arrived in this
  // very step). A continued round is handed its sample's input, time and step, frozen at round 0.
  bool rounds_over_links() const { return over_links_; }
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
  // Rounds over links (agent_channel_rounds.cc).
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
  void SetUpRoundsOverLinks(uint64_t seed);
  void CollectRounds();
  void TakeJacobiLetter(const network::RoundLetter& letter);
  void TakeSolverLetter(const network::RoundLetter& letter);
  void TakeSolutionLetter(const network::RoundLetter& letter);
  // L_H W = R for the rows in solver_rows_ (R_i x, y per follower), into solved_.
  void SolveGathered();
  void FillOutgoing(int follower, const std::vector<mjfSetpoint>& setpoints);
  void EndExchange(int follower, bool finished);
  bool RoundInputsArrived(int follower) const;
  nlohmann::json RoundsSummary() const;
  nlohmann::json SolverStarSummary() const;
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
  // Rounds over links.
  bool over_links_ = false;
  int64_t step_ = 0;
  int64_t timeout_steps_ = 0;      // round_timeout in steps (0: none)
  int64_t steps_per_sample_ = 1;   // T in physics steps (the sample index's divisor)
  std::vector<double> call_time_;  // [follower] clock reading of this tick's round 0
  std::vector<int64_t> call_step_;
  std::vector<Exchange> exchanges_;      // [follower] its current sample's rounds
  std::vector<RoundStats> round_stats_;  // [follower]
  std::vector<network::RoundLetter> letters_;
  std::vector<int64_t> late_, unmatched_;  // [link] round messages nobody waited for any more
  // The central solve over links: the solver is vehicle 0 (the leader); follower i's R_i goes up
  // and W_i comes down on a pair of links with its leader link's parameters (docs/NETWORK.md).
  std::vector<network::Link> solver_up_, solver_down_;  // [follower]
  network::RoundCourier up_in_flight_, down_in_flight_;
  int64_t solver_sample_ = -1;       // the sample whose R_i the solver is gathering
  std::vector<char> solver_has_;     // [follower] R_i of solver_sample_ arrived
  std::vector<double> solver_rows_;  // [2 follower + axis] R_i as it arrived
  int solver_count_ = 0;
  int64_t solver_solves_ = 0;
  std::vector<int64_t> up_late_, down_late_;     // [follower]
  std::vector<std::array<double, 2>> held_acc_;  // [follower] round_policy = "hold"
};

}  // namespace mjf::runner

#endif  // MJFORMATION_CONTROL_AGENT_CHANNEL_HPP_
