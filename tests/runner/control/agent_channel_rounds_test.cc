// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Exchange rounds carried over the links ([network] rounds = "over_links"): with no
// latency they are the instantaneous rounds to the bit; with latency L a round takes L (the
// central solve's two hops 2L), measured on the steps at which the commands change and on the
// summary's timestamps; a round not complete before the next sample is dropped and counted, and
// a round whose messages are slower than the timeout runs without them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mjformation/config/config.hpp"
#include "mjformation/control/agent_channel.hpp"
#include "mjformation/sim/simulation.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

ExperimentConfig Exp2(std::vector<std::string> overrides) {
  overrides.insert(overrides.begin(),
                   {"vehicles.model=\"pointmass\"", "attitude={plugin=\"pointmass_direct\"}"});
  ExperimentConfig c =
      LoadExperiment(std::string(MJF_SOURCE_DIR) + "/experiments/exp2.toml", overrides);
  c.plugin_path.push_back(MJF_TEST_PLUGIN_DIR);
  return c;
}

const char kJacobi[] =
    "execution={mode=\"per_agent\", coupling=\"jacobi\", jacobi_rounds=3, predict=\"input\"}";
const char kCentral[] =
    "execution={mode=\"per_agent\", coupling=\"central_solve\", "
    "predict=\"input\"}";

nlohmann::json Rounds(const Simulation& sim) {
  return sim.channel()->Summary()["rounds_over_links"];
}

// Latency 0, no loss: every round arrives in the step it is sent and each round is handed the
// input it gets instantaneously, so the commands and sliding variables are the same doubles at
// every step (the same arithmetic in the same order: no tolerance).
TEST(AgentChannelRoundsTest, OverLinksWithoutLatencyIsInstantaneousToTheBit) {
  for (const char* coupling : {kJacobi, kCentral}) {
    Simulation instant(Exp2({coupling}));
    Simulation over(Exp2({coupling, "network={rounds=\"over_links\"}"}));
    int64_t differing = 0;
    for (int64_t k = 0; k < 3000; ++k) {
      instant.ComputeControls();
      over.ComputeControls();
      for (int i = 1; i < instant.n_vehicles(); ++i) {
        for (int axis = 0; axis < 2; ++axis) {
          differing += instant.setpoints()[i].acc[axis] != over.setpoints()[i].acc[axis];
          differing += instant.setpoints()[i].sliding[axis] != over.setpoints()[i].sliding[axis];
        }
      }
      instant.Integrate();
      over.Integrate();
    }
    EXPECT_EQ(differing, 0) << coupling;
    const nlohmann::json r = Rounds(over);
    EXPECT_EQ(r["samples"].get<int64_t>(), r["complete"].get<int64_t>()) << coupling;
    EXPECT_GT(r["samples"].get<int64_t>(), 6 * 50) << coupling;  // 60 samples of 6 followers
    EXPECT_FALSE(over.channel()->Summary()["oracle"].get<bool>());
    EXPECT_EQ(over.channel()->Summary()["exchange_rounds"], "over_links");
    EXPECT_EQ(instant.channel()->Summary()["exchange_rounds"], "instantaneous");
  }
}

// The steps at which follower `vehicle`'s command changes over the first `steps` steps.
std::vector<int64_t> CommandChanges(Simulation& sim, int vehicle, int64_t steps) {
  std::vector<int64_t> changes;
  double last = NAN;
  for (int64_t k = 0; k < steps; ++k) {
    sim.ComputeControls();
    const double a = sim.setpoints()[vehicle].acc[0];
    if (a != last && k > 0) changes.push_back(k);
    last = a;
    sim.Integrate();
  }
  return changes;
}

// With latency L on every link, a follower's command changes at its sample (round 0, from the
// last inputs) and then once per round that arrives: Jacobi rounds 1..3 at L, 2L, 3L after it,
// the central solve's W_i at 2L (R_i up, W_i down). Measured on the steps the commands change
// and on the round messages' timestamps (summary: latency and sample-to-last-round time).
TEST(AgentChannelRoundsTest, ARoundOverALinkWithLatencyLArrivesLLater) {
  const int64_t l_steps = 10;  // L = 10 ms at the 1 ms step; T = 50 ms = 50 steps
  const std::string net = "network={rounds=\"over_links\", latency=0.01}";
  for (const char* coupling : {kJacobi, kCentral}) {
    const bool central = coupling == kCentral;
    Simulation sim(Exp2({coupling, net}));
    const std::vector<int64_t> changes = CommandChanges(sim, 1, 400);
    // The first sample is at step L (the first messages arrive then); from the second on, every
    // 50 steps. Changes within one sample: at the sample, then per round.
    std::vector<int64_t> expected;
    for (int64_t sample = 50; sample < 400; sample += 50) {
      expected.push_back(sample);
      if (central) {
        expected.push_back(sample + 2 * l_steps);
      } else {
        for (int64_t r = 1; r <= 3; ++r) expected.push_back(sample + r * l_steps);
      }
    }
    std::vector<int64_t> seen;
    for (int64_t k : changes) {
      if (k >= 50) seen.push_back(k);
    }
    EXPECT_EQ(seen, expected) << coupling;
    const nlohmann::json r = Rounds(sim);
    EXPECT_NEAR(r["completion_mean_s"].get<double>(), central ? 0.02 : 0.03, 1e-12) << coupling;
    if (central) {
      for (const auto& pair : r["solver"]["links"]) {
        EXPECT_NEAR(pair["up_r"]["latency_max_s"].get<double>(), 0.01, 1e-12);
        EXPECT_NEAR(pair["down_w"]["latency_mean_s"].get<double>(), 0.01, 1e-12);
      }
    } else {
      for (const auto& link : r["links"]) {
        EXPECT_NEAR(link["round_latency_mean_s"].get<double>(), 0.01, 1e-12);
        EXPECT_NEAR(link["round_latency_max_s"].get<double>(), 0.01, 1e-12);
        EXPECT_EQ(link["round_messages_late"].get<int64_t>(), 0);
      }
    }
  }
}

// Clocks out of phase (offsets U[0, 25 ms], T = 50 ms): the instantaneous central solve finds no
// instant at which every follower samples and skips every sample; over the links the solver
// gathers the R_i of one sample index (each follower's own period), so it solves once per period
// and every exchange completes, W_i arriving after the last follower of that period sampled.
TEST(AgentChannelRoundsTest, CentralSolveOverLinksGathersOneSampleIndexAcrossClocks) {
  const std::string clocks =
      "execution={mode=\"per_agent\", coupling=\"central_solve\", predict=\"input\", "
      "clock_offset=0.025}";
  Simulation instant(Exp2({clocks}));
  Simulation over(Exp2({clocks, "network={rounds=\"over_links\"}"}));
  for (int64_t k = 0; k < 1000; ++k) {  // 1 s: 20 periods
    instant.ComputeControls();
    over.ComputeControls();
    instant.Integrate();
    over.Integrate();
  }
  const nlohmann::json inst = instant.channel()->Summary();
  EXPECT_GT(inst["central_solve_skipped_samples"].get<int64_t>(), 0);
  const nlohmann::json r = Rounds(over);
  EXPECT_EQ(over.channel()->Summary()["central_solve_skipped_samples"].get<int64_t>(), 0);
  const int64_t solves = r["solver"]["solves"].get<int64_t>();
  EXPECT_GE(solves, 19);  // one per period after the first messages
  EXPECT_LE(solves, 21);
  // Every follower's exchange of a solved period completes (the last may still be running).
  EXPECT_GE(r["complete"].get<int64_t>(), 6 * (solves - 1));
  EXPECT_EQ(r["incomplete"].get<int64_t>(), 0);
  // The waiting is the clocks' disagreement: some exchange took longer than a step, none a period.
  EXPECT_GT(r["completion_max_s"].get<double>(), 0.001);
  EXPECT_LT(r["completion_max_s"].get<double>(), 0.05);
}

// round_policy = "hold": the command changes once per sample, when the exchange finishes (the
// central solve's W_i 2L after the sample, Jacobi's round 3 at 3L), not at round 0 and not at the
// rounds between; and at the first sample's finish (both flights sampled the same state) the
// command it changes to is the one "apply" has then: the finished exchange's result.
TEST(AgentChannelRoundsTest, HoldPolicyChangesTheCommandOnlyWhenTheExchangeFinishes) {
  const int64_t l_steps = 10;  // L = 10 ms, T = 50 steps
  for (const char* coupling : {kJacobi, kCentral}) {
    const bool central = coupling == kCentral;
    Simulation hold(
        Exp2({coupling, "network={rounds=\"over_links\", latency=0.01, round_policy=\"hold\"}"}));
    Simulation apply(Exp2({coupling, "network={rounds=\"over_links\", latency=0.01}"}));
    std::vector<int64_t> changes;
    double last = NAN;
    int64_t first_finish_checked = 0;
    for (int64_t k = 0; k < 400; ++k) {
      hold.ComputeControls();
      apply.ComputeControls();
      const double a = hold.setpoints()[1].acc[0];
      if (a != last && k > 0) changes.push_back(k);
      last = a;
      // The first sample is at step L (the first messages arrive then), from the same state in
      // both flights: its finished exchange gives both the same command.
      if (k == l_steps + (central ? 2 : 3) * l_steps) {
        EXPECT_EQ(a, apply.setpoints()[1].acc[0]) << coupling;
        ++first_finish_checked;
      }
      hold.Integrate();
      apply.Integrate();
    }
    EXPECT_EQ(first_finish_checked, 1);
    std::vector<int64_t> expected;
    for (int64_t sample = 50; sample < 400; sample += 50) {
      expected.push_back(sample + (central ? 2 : 3) * l_steps);
    }
    std::vector<int64_t> seen;
    for (int64_t k : changes) {
      if (k >= 50) seen.push_back(k);
    }
    EXPECT_EQ(seen, expected) << coupling;
    EXPECT_EQ(Rounds(hold)["round_policy"], "hold");
    EXPECT_EQ(Rounds(apply)["round_policy"], "apply");
  }
}

// Latency 0: every exchange finishes in the tick it starts, so holding changes nothing.
TEST(AgentChannelRoundsTest, HoldPolicyWithoutLatencyIsApplyToTheBit) {
  for (const char* coupling : {kJacobi, kCentral}) {
    Simulation apply(Exp2({coupling, "network={rounds=\"over_links\"}"}));
    Simulation hold(Exp2({coupling, "network={rounds=\"over_links\", round_policy=\"hold\"}"}));
    int64_t differing = 0;
    for (int64_t k = 0; k < 1000; ++k) {
      apply.ComputeControls();
      hold.ComputeControls();
      for (int i = 1; i < apply.n_vehicles(); ++i) {
        differing += apply.setpoints()[i].acc[0] != hold.setpoints()[i].acc[0];
        differing += apply.setpoints()[i].acc[1] != hold.setpoints()[i].acc[1];
      }
      apply.Integrate();
      hold.Integrate();
    }
    EXPECT_EQ(differing, 0) << coupling;
  }
}

// Jacobi m = 3 with L = 20 ms and T = 50 ms: rounds 1 and 2 run at 20 and 40 ms; round 3 would
// need 60 ms, so the next sample drops it (the exchange is incomplete, 2 rounds run) and the
// round 2 messages, arriving 10 ms into the next sample, are counted late. The command between
// samples is the round 2 iterate, and the next sample replaces it with its own round 0.
TEST(AgentChannelRoundsTest, ARoundNotCompleteBeforeTheNextSampleIsDroppedAndCounted) {
  Simulation sim(Exp2({kJacobi, "network={rounds=\"over_links\", latency=0.02}"}));
  const std::vector<int64_t> changes = CommandChanges(sim, 3, 1000);
  for (int64_t sample = 100; sample < 1000; sample += 50) {
    for (int64_t at : {sample, sample + 20, sample + 40}) {
      EXPECT_NE(std::find(changes.begin(), changes.end(), at), changes.end()) << at;
    }
    EXPECT_EQ(std::find(changes.begin(), changes.end(), sample + 60), changes.end())
        << "no round 3 at " << sample + 60;
  }
  const nlohmann::json r = Rounds(sim);
  EXPECT_EQ(r["complete"].get<int64_t>(), 0);
  EXPECT_EQ(r["timed_out"].get<int64_t>(), 0);
  const int64_t incomplete = r["incomplete"].get<int64_t>();
  EXPECT_GE(incomplete, 6 * 18);
  // Every sample ran 2 rounds but the first (taken at 20 ms, when the first messages arrived:
  // the sample at 50 ms came after its round 1).
  EXPECT_EQ(r["rounds_run"][1].get<int64_t>(), 6);
  EXPECT_EQ(r["rounds_run"][2].get<int64_t>(), incomplete - 6);
  EXPECT_EQ(r["in_progress_at_end"].get<int64_t>(), 6);
  for (const auto& link : r["links"]) EXPECT_GE(link["round_messages_late"].get<int64_t>(), 18);
}

// The timeout: follower 2's round messages reach follower 1 after 30 ms, the timeout is 5 ms,
// every other link has no latency. Follower 1 runs each round on the timeout, coupled to
// follower 2 through its last input (5, 10, 15 ms after the sample); its other neighbour's
// iterates arrive in time. Follower 2's messages then arrive for rounds it has passed: late.
TEST(AgentChannelRoundsTest, ARoundSlowerThanTheTimeoutRunsWithoutIt) {
  Simulation sim(Exp2({kJacobi,
                       "network={rounds=\"over_links\", round_timeout=0.005, "
                       "link=[{from=2, to=1, latency=0.03}]}"}));
  for (int64_t k = 0; k < 1000; ++k) {
    sim.ComputeControls();
    sim.Integrate();
  }
  const nlohmann::json r = Rounds(sim);
  const nlohmann::json& f1 = r["followers"][0];
  ASSERT_EQ(f1["follower"], 1);
  EXPECT_GE(f1["timed_out"].get<int64_t>(), 18);
  EXPECT_EQ(f1["complete"].get<int64_t>(), 0);
  EXPECT_NEAR(f1["completion_max_s"].get<double>(), 0.015, 1e-12);
  for (const auto& link : r["links"]) {
    if (link["from"] == 2 && link["to"] == 1) {
      EXPECT_GE(link["round_messages_late"].get<int64_t>(), 18 * 3);
    }
  }
}

}  // namespace
}  // namespace mjf::runner
