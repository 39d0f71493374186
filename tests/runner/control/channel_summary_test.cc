// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// summary.json "network" from the channel's parts: the clocks as drawn, the links and ages of
// the routing, the oracle flag, the exchange totals over the followers and the solver's star.
#include "mjformation/control/channel_summary.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "mjformation/formation/graph.hpp"

namespace mjf::runner {
namespace {

constexpr double kDt = 0.001;

formation::Graph Pair() { return formation::Graph(2, {1.0, 0.0}, {{0, 1}, {1, 0}}); }

TEST(ChannelSummaryTest, ClocksAreInPhaseUnlessDrawnAndSynchronisedOnlyWhenSet) {
  const nlohmann::json in_phase = ClocksSummary(AgentClocks(2, 0.0, 0.0, kDt, 1), 2);
  EXPECT_TRUE(in_phase["in_phase"].get<bool>());
  EXPECT_EQ(in_phase["offset_s"], nlohmann::json::array({0.0, 0.0}));
  EXPECT_FALSE(in_phase.contains("synchronised"));
  const AgentClocks drawn(2, 0.01, 50.0, kDt, 1, true);
  const nlohmann::json s = ClocksSummary(drawn, 2);
  EXPECT_FALSE(s["in_phase"].get<bool>());
  EXPECT_EQ(s["offset_s"][1].get<double>(), drawn.offset(1));
  EXPECT_EQ(s["drift_ppm"][0].get<double>(), drawn.drift(0) * 1e6);
  EXPECT_TRUE(s["synchronised"].get<bool>());
}

TEST(ChannelSummaryTest, TheInstantaneousCentralSolveIsTheOracle) {
  NetworkConfig c;
  c.execution = Execution::kPerAgent;
  c.coupling = Coupling::kCentralSolve;
  const AgentRouting routing(Pair(), c, 2, kDt, 1);
  const CentralSolver central(Pair());
  const AgentClocks clocks(2, 0.0, 0.0, kDt, 1);
  const nlohmann::json s = NetworkSummary({c, 2, 0.5, routing, &central, nullptr, clocks});
  EXPECT_TRUE(s["oracle"].get<bool>());
  EXPECT_EQ(s["coupling"], "central_solve");
  EXPECT_EQ(s["rounds_per_step"].get<int>(), 2);
  EXPECT_EQ(s["jacobi_spectral_radius"].get<double>(), 0.5);
  EXPECT_EQ(s["central_solve_skipped_samples"].get<int64_t>(), 0);
  EXPECT_EQ(s["links"].size(), 3u);  // leader -> 1, 2 -> 1, 1 -> 2
  EXPECT_EQ(s["age_of_information_at_samples"].size(), 2u);
  EXPECT_FALSE(s.contains("rounds_over_links"));
}

TEST(ChannelSummaryTest, RoundsOverLinksTotalTheFollowersAndListTheSolversStar) {
  NetworkConfig c;
  c.execution = Execution::kPerAgent;
  c.coupling = Coupling::kCentralSolve;
  c.rounds = ExchangeRounds::kOverLinks;
  c.sample_period = kDt;
  AgentRouting routing(Pair(), c, 2, kDt, 1);
  CentralSolver central(Pair());
  central.SetUpStar(routing.network(), c.defaults, 1);
  RoundsOverLinks rounds(&routing, &central, c, 2);
  std::vector<mjfVehicleState> states(3);
  std::vector<mjfSetpoint> setpoints(3);
  routing.BeginTick(0, 0.0, states, states, setpoints);
  for (int i = 0; i < 2; ++i) {
    rounds.SetCallContext(i, 0.0, 0);
    routing.OpenOutgoing(i, 0)->n_payload = 4;  // R_i published
  }
  rounds.StartExchanges(setpoints);  // latency 0: every W_i is back in this step
  const AgentClocks clocks(2, 0.0, 0.0, kDt, 1);
  const nlohmann::json s = NetworkSummary({c, 2, 0.5, routing, &central, &rounds, clocks});
  EXPECT_FALSE(s["oracle"].get<bool>());
  const nlohmann::json& r = s["rounds_over_links"];
  EXPECT_EQ(r["samples"].get<int64_t>(), 2);
  EXPECT_EQ(r["in_progress_at_end"].get<int64_t>(), 2);  // round 1 has not run yet
  EXPECT_EQ(r["followers"].size(), 2u);
  EXPECT_EQ(r["links"].size(), 2u);  // the follower links only
  EXPECT_EQ(r["solver"]["solves"].get<int64_t>(), 1);
  EXPECT_EQ(r["solver"]["links"][1]["up_r"]["delivered"].get<int64_t>(), 1);
  EXPECT_EQ(r["solver"]["links"][1]["down_w"]["sent"].get<int64_t>(), 1);
  EXPECT_EQ(SolverStarSummary(central), r["solver"]);
  EXPECT_EQ(RoundsSummary(rounds, routing.network(), &central), r);
}

}  // namespace
}  // namespace mjf::runner
