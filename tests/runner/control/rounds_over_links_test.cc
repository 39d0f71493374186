// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The exchange-round state machine over the links, driven as the control tick drives it, with
// a stand-in for the plugins: a round runs when its inputs arrived (at once without latency, a
// latency later with it), on the timeout when they never do, is dropped by the next sample, and
// the hold policy keeps the last finished command while an exchange runs.
#include "mjformation/control/rounds_over_links.hpp"

#include <gtest/gtest.h>

#include <utility>
#include <vector>

#include "mjformation/formation/graph.hpp"

namespace mjf::runner {
namespace {

constexpr double kDt = 0.001;

// Leader -> 1, 1 <-> 2 (0-based followers 0, 1).
formation::Graph Pair() { return formation::Graph(2, {1.0, 0.0}, {{0, 1}, {1, 0}}); }

NetworkConfig OverLinks(double latency) {
  NetworkConfig c;
  c.execution = Execution::kPerAgent;
  c.coupling = Coupling::kJacobi;
  c.rounds = ExchangeRounds::kOverLinks;
  c.sample_period = kDt;
  c.defaults.latency = latency;
  return c;
}

// The control tick's calls, with plugins that write payload[0] = 10 (i + 1) in round 0 (when
// they sample, also as their command) and 100 (i + 1) + r in round r.
class Tick {
 public:
  explicit Tick(const NetworkConfig& c)
      : routing_(Pair(), c, 2, kDt, 1),
        rounds_(&routing_, nullptr, c, 2),
        states_(3),
        setpoints_(3) {}

  // The (follower, round) pairs continued at `step`; sample: the followers take a sample.
  std::vector<std::pair<int, int>> Run(int64_t step, bool sample) {
    std::vector<std::pair<int, int>> ran;
    routing_.BeginTick(step, kDt * static_cast<double>(step), states_, states_, setpoints_);
    rounds_.CollectRounds();
    ContinueRounds(&ran);
    for (int i = 0; i < 2; ++i) {
      rounds_.SetCallContext(i, kDt * static_cast<double>(step), step);
      routing_.input(i).leader = routing_.FetchInbox(i, -1);
      mjfMessage* out = routing_.OpenOutgoing(i, 0);
      out->n_payload = sample ? 1 : 0;
      out->payload[0] = 10.0 * (i + 1);
      if (sample) setpoints_[i + 1].acc[0] = out->payload[0];
    }
    routing_.RecordSampleAge();
    rounds_.StartExchanges(setpoints_);
    ContinueRounds(&ran);
    rounds_.HoldPendingCommands(&setpoints_);
    return ran;
  }
  RoundsOverLinks& rounds() { return rounds_; }
  const std::vector<mjfSetpoint>& setpoints() const { return setpoints_; }
  double last_neighbour_payload(int follower) const { return last_payload_[follower]; }

 private:
  void ContinueRounds(std::vector<std::pair<int, int>>* ran) {
    int round = 0;
    double time = 0.0;
    int64_t local_step = 0;
    for (int i; (i = rounds_.NextContinuedRound(&round, &time, &local_step)) >= 0;) {
      const mjfAgentInput& in = rounds_.ContinuedInput(i, round);
      last_payload_[i] = in.n_messages > 0 ? in.messages[0].payload[0] : -1.0;
      in.outgoing->n_payload = 1;
      in.outgoing->payload[0] = 100.0 * (i + 1) + round;
      setpoints_[i + 1].acc[0] = in.outgoing->payload[0];
      rounds_.EndContinuedRound(i, round, setpoints_);
      ran->emplace_back(i, round);
    }
  }

  AgentRouting routing_;
  RoundsOverLinks rounds_;
  std::vector<mjfVehicleState> states_;
  std::vector<mjfSetpoint> setpoints_;
  double last_payload_[2] = {0.0, 0.0};
};

TEST(RoundsOverLinksTest, WithoutLatencyRoundOneRunsInTheSampleStepOnTheNeighboursRoundZero) {
  Tick tick(OverLinks(0.0));
  const auto ran = tick.Run(0, true);
  ASSERT_EQ(ran.size(), 2u);
  EXPECT_EQ(ran[0], std::make_pair(0, 1));
  EXPECT_EQ(ran[1], std::make_pair(1, 1));
  EXPECT_DOUBLE_EQ(tick.last_neighbour_payload(0), 20.0);  // follower 2's round 0
  EXPECT_DOUBLE_EQ(tick.last_neighbour_payload(1), 10.0);
  EXPECT_EQ(tick.rounds().stats(0).complete, 1);
  EXPECT_FALSE(tick.rounds().exchange(0).waiting);
}

TEST(RoundsOverLinksTest, WithLatencyRoundOneRunsWhenItsInputsArrive) {
  Tick tick(OverLinks(0.002));
  EXPECT_TRUE(tick.Run(0, true).empty());
  EXPECT_TRUE(tick.rounds().exchange(1).waiting);
  EXPECT_TRUE(tick.Run(1, false).empty());
  EXPECT_EQ(tick.Run(2, false).size(), 2u);
  const RoundsOverLinks::RoundStats& st = tick.rounds().stats(1);
  EXPECT_EQ(st.samples, 1);
  EXPECT_EQ(st.complete, 1);
  EXPECT_NEAR(st.completion_sum, 0.002, 1e-12);
  EXPECT_EQ(st.rounds_run[1], 1);
}

TEST(RoundsOverLinksTest, ALostRoundRunsOnTheTimeoutOrIsDroppedByTheNextSample) {
  NetworkConfig c = OverLinks(0.0);
  c.defaults.loss = 1.0;
  c.round_timeout = 0.003;
  Tick timed(c);
  timed.Run(0, true);
  EXPECT_TRUE(timed.Run(2, false).empty());
  EXPECT_EQ(timed.Run(3, false).size(), 2u);
  EXPECT_DOUBLE_EQ(timed.last_neighbour_payload(0), -1.0);  // nothing arrived at all
  EXPECT_EQ(timed.rounds().stats(0).timed_out, 1);
  c.round_timeout = 0.0;
  Tick dropped(c);
  dropped.Run(0, true);
  dropped.Run(1, true);
  EXPECT_EQ(dropped.rounds().stats(0).incomplete, 1);
  EXPECT_EQ(dropped.rounds().stats(0).samples, 2);
  EXPECT_EQ(dropped.rounds().stats(0).rounds_run[0], 1);
}

TEST(RoundsOverLinksTest, HoldKeepsTheLastFinishedCommandWhileAnExchangeRuns) {
  NetworkConfig c = OverLinks(0.002);
  c.round_policy = RoundPolicy::kHold;
  Tick tick(c);
  tick.Run(0, true);
  EXPECT_DOUBLE_EQ(tick.setpoints()[1].acc[0], 0.0);  // no exchange finished yet
  tick.Run(1, false);
  EXPECT_DOUBLE_EQ(tick.setpoints()[1].acc[0], 0.0);
  tick.Run(2, false);
  EXPECT_DOUBLE_EQ(tick.setpoints()[1].acc[0], 101.0);  // round 1 finished the exchange
  tick.Run(3, true);
  EXPECT_DOUBLE_EQ(tick.setpoints()[1].acc[0], 101.0);  // held while the next one runs
}

TEST(RoundsOverLinksTest, ARoundMessageForADroppedExchangeIsLate) {
  Tick tick(OverLinks(0.002));
  tick.Run(0, true);
  tick.Run(1, true);  // drops sample 0's rounds: its round-0 messages arrive late
  tick.Run(2, false);
  int64_t late = 0;
  for (int l = 0; l < 3; ++l) late += tick.rounds().late(l);
  EXPECT_EQ(late, 2);
  EXPECT_EQ(tick.rounds().stats(0).incomplete, 1);
}

}  // namespace
}  // namespace mjf::runner
