// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The network model alone: exact latency, loss statistics (Bernoulli, Gilbert-Elliott bursts),
// jitter statistics, determinism, thread independence, newer-message-wins and range limits.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <mjformation/config/fixed_state_archive.hpp>
#include <mjformation/network/link.hpp>
#include <mjformation/network/network.hpp>
#include <thread>
#include <vector>

namespace mjf::network {
namespace {

constexpr double kDt = 0.001;

mjfMessage MessageAt(int sender, int64_t step) {
  mjfMessage m{};
  m.sender = sender;
  m.send_time = static_cast<double>(step) * kDt;
  m.state.pos[0] = static_cast<double>(step);
  return m;
}

// The leader's link to follower 1 and a directed ring 1 -> 2 -> ... -> n -> 1, every link with
// parameters p.
std::vector<LinkSpec> LeaderAndRing(int n, const LinkParams& p) {
  std::vector<LinkSpec> specs = {{0, 1, p}};
  for (int i = 1; i <= n; ++i) specs.push_back({i, i % n + 1, p});
  return specs;
}

TEST(LinkTest, DeliversExactlyTheConfiguredLatency) {
  for (double latency : {0.0, 0.001, 0.01, 0.02, 0.05, 0.1}) {
    LinkSpec spec{0, 1, {}};
    spec.params.latency = latency;
    Network net(1, {spec}, kDt, 7);
    std::vector<mjfMessage> inbox;
    const mjfMessage* leader = nullptr;
    double first_arrival = -1.0;
    for (int64_t step = 0; step < 200; ++step) {
      if (step == 0) net.Broadcast(step, 0, MessageAt(0, step));
      net.Deliver(step);
      net.Inbox(1, -1, &inbox, &leader);
      if (leader && first_arrival < 0) first_arrival = static_cast<double>(step) * kDt;
    }
    // Measured on timestamps: arrival time - send time equals the latency to the step.
    EXPECT_NEAR(first_arrival - 0.0, latency, 1e-12) << latency;
    EXPECT_NEAR(net.link(0).stats().latency_max, latency, 1e-12);
  }
}

// Exchange rounds over the links: a round message handed to a follower link arrives
// exactly its latency later, measured on the steps' timestamps, tagged with its sample; it never
// travels on the leader link (rounds are between followers) and is not held like a state.
TEST(LinkTest, RoundOverALinkArrivesItsLatencyLater) {
  for (double latency : {0.0, 0.001, 0.005, 0.02, 0.049}) {
    LinkSpec follower_link{1, 2, {}};
    follower_link.params.latency = latency;
    LinkSpec leader_link{0, 1, {}};
    leader_link.params.latency = latency;
    Network net(2, {leader_link, follower_link}, kDt, 7);
    const int64_t sent_at = 13;
    mjfMessage round = MessageAt(1, sent_at);
    round.round = 2;
    round.n_payload = 2;
    round.payload[0] = 0.25;
    std::vector<RoundLetter> letters;
    double arrival_time = -1.0;
    for (int64_t step = 0; step < 100; ++step) {
      if (step == sent_at) {
        net.SendRound(step, 1, 10, round);
        net.SendRound(step, 0, 10, round);  // the leader has no follower link: nothing sent
      }
      const size_t before = letters.size();
      net.CollectRounds(step, &letters);
      if (letters.size() > before) arrival_time = static_cast<double>(step) * kDt;
    }
    ASSERT_EQ(letters.size(), 1u) << latency;
    EXPECT_NEAR(arrival_time - static_cast<double>(sent_at) * kDt, latency, 1e-12) << latency;
    EXPECT_EQ(letters[0].link, 1);
    EXPECT_EQ(letters[0].sample_step, 10);
    EXPECT_EQ(letters[0].message.round, 2);
    EXPECT_EQ(letters[0].message.payload[0], 0.25);
    const LinkStats& st = net.link(1).stats();
    EXPECT_EQ(st.rounds_sent, 1);
    EXPECT_EQ(st.rounds_delivered, 1);
    EXPECT_NEAR(st.round_latency_max, latency, 1e-12);
    EXPECT_EQ(st.sent, 0);  // not counted as a state message
    EXPECT_EQ(net.link(0).stats().rounds_sent, 0);
  }
}

// A lost round message never arrives; the draws are the state messages' (one loss uniform,
// then one for the jitter), so loss p drops a fraction p and jitter stays within [0, jitter].
TEST(LinkTest, RoundOverALinkIsLostAndJitteredLikeAState) {
  LinkParams params;
  params.latency = 0.002;
  params.jitter = 0.003;
  params.loss = 0.3;
  Link link(params, kDt, LinkSeed(9, 4));
  const int n = 20000;
  int delivered = 0;
  for (int k = 0; k < n; ++k) {
    if (auto arrival = link.TransmitRoundDelayed(1000)) {
      ++delivered;
      EXPECT_GE(*arrival - 1000, 2);
      EXPECT_LE(*arrival - 1000, 5);
    }
  }
  const double p = 1.0 - static_cast<double>(delivered) / n;
  EXPECT_NEAR(p, 0.3, 4.0 * std::sqrt(0.3 * 0.7 / n));
  EXPECT_EQ(link.stats().rounds_sent, n);
  EXPECT_EQ(link.stats().rounds_lost, n - delivered);
}

TEST(LinkTest, BernoulliLossWithinBinomialInterval) {
  const int n = 100000;
  for (double p : {0.0, 0.05, 0.2, 0.5, 1.0}) {
    LinkParams params;
    params.loss = p;
    Link link(params, kDt, LinkSeed(3, 0));
    int lost = 0;
    for (int k = 0; k < n; ++k) lost += link.Transmit(k) ? 0 : 1;
    // 99 % interval of Binomial(n, p): +- 2.576 sigma.
    const double sigma = std::sqrt(n * p * (1 - p));
    EXPECT_LE(std::abs(lost - n * p), 2.576 * sigma + 1e-9) << "p = " << p;
    EXPECT_EQ(link.stats().lost, lost);
  }
}

TEST(LinkTest, GilbertElliottMeanBurstLength) {
  LinkParams params;
  params.loss_model = LossModel::kGilbertElliott;
  params.burst_enter = 0.02;
  params.burst_exit = 0.25;  // mean burst 1 / 0.25 = 4 messages
  params.loss = 0.0;
  params.burst_loss = 1.0;
  Link link(params, kDt, LinkSeed(11, 2));
  const int n = 200000;
  int bursts = 0, lost = 0, run = 0;
  for (int k = 0; k < n; ++k) {
    if (!link.Transmit(k)) {
      ++lost;
      ++run;
    } else if (run > 0) {
      ++bursts;
      run = 0;
    }
  }
  const double mean_burst = static_cast<double>(lost) / bursts;
  // Burst length is geometric with mean 1/exit = 4, sd sqrt(1-exit)/exit = 3.46; with ~1500
  // bursts the standard error is 0.09: allow 4 standard errors.
  EXPECT_NEAR(mean_burst, 4.0, 4 * 3.46 / std::sqrt(bursts));
  // Stationary loss = enter / (enter + exit) = 0.0741.
  const double expected = 0.02 / 0.27;
  EXPECT_NEAR(static_cast<double>(lost) / n, expected,
              4 * std::sqrt(expected * (1 - expected) / n) * std::sqrt(2 * mean_burst));
}

TEST(LinkTest, JitterStatistics) {
  LinkParams params;
  params.latency = 0.01;
  params.jitter = 0.04;
  Link link(params, 1e-6, LinkSeed(5, 1));  // a fine step so quantisation is negligible
  const int n = 100000;
  double sum = 0, sum2 = 0, lo = 1e9, hi = -1e9;
  for (int k = 0; k < n; ++k) {
    const double d = static_cast<double>(*link.Transmit(0)) * 1e-6 - params.latency;
    sum += d;
    sum2 += d * d;
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
  const double mean = sum / n, var = sum2 / n - mean * mean;
  // Uniform [0, J]: mean J/2 (standard error J / sqrt(12 n)), variance J^2/12.
  EXPECT_NEAR(mean, 0.02, 4 * 0.04 / std::sqrt(12.0 * n) + 1e-6);
  EXPECT_NEAR(var, 0.04 * 0.04 / 12, 0.03 * 0.04 * 0.04 / 12);
  EXPECT_GE(lo, 0.0);
  EXPECT_LE(hi, 0.04 + 1e-6);
}

// A ring of 4 followers plus the leader link, lossy with jitter: the bytes every receiver holds.
std::vector<unsigned char> Trace(uint64_t seed) {
  LinkParams p;
  p.latency = 0.005;
  p.jitter = 0.02;
  p.loss = 0.3;
  const std::vector<LinkSpec> specs = LeaderAndRing(4, p);
  Network net(4, specs, kDt, seed);
  std::vector<unsigned char> bytes;
  std::vector<mjfMessage> inbox;
  const mjfMessage* leader = nullptr;
  for (int64_t step = 0; step < 5000; ++step) {
    for (int v = 0; v <= 4; ++v) net.Broadcast(step, v, MessageAt(v, step));
    net.Deliver(step);
    for (int v = 1; v <= 4; ++v) {
      net.Inbox(v, -1, &inbox, &leader);
      for (const auto& m : inbox) {
        const auto* b = reinterpret_cast<const unsigned char*>(&m.send_time);
        bytes.insert(bytes.end(), b, b + sizeof(double));
      }
    }
  }
  return bytes;
}

TEST(NetworkTest, SameSeedSameBytesDifferentSeedDifferent) {
  EXPECT_EQ(Trace(42), Trace(42));
  EXPECT_NE(Trace(42), Trace(43));
}

TEST(NetworkTest, TwoInstancesOnTwoThreadsAreIndependent) {
  const auto alone = Trace(9);
  std::vector<unsigned char> a, b;
  std::thread ta([&] { a = Trace(9); });
  std::thread tb([&] { b = Trace(9); });
  ta.join();
  tb.join();
  EXPECT_EQ(a, alone);
  EXPECT_EQ(b, alone);
}

// The fixed-length state (the control tick's block, message_state.hpp): a lossy, jittered,
// bursty ring whose state is taken at every step (a queue past MaxInFlight would throw) and,
// at step 2500, loaded into a network of another seed: both fly on to the same bytes.
TEST(NetworkTest, StateLoadedIntoAnotherNetworkFliesOnTheSameBytes) {
  LinkParams p;
  p.period_steps = 3;
  p.latency = 0.005;
  p.jitter = 0.02;
  p.loss_model = LossModel::kGilbertElliott;
  p.loss = 0.1;
  p.burst_enter = 0.2;
  p.burst_exit = 0.4;
  const std::vector<LinkSpec> specs = LeaderAndRing(4, p);
  Network net(4, specs, kDt, 42), other(4, specs, kDt, 7);
  using runner::FixedStateArchive;
  FixedStateArchive sizing = FixedStateArchive::Sizing();
  net.VisitState(sizing);
  std::vector<double> state(sizing.size());
  auto fly = [&](Network& n, int64_t from, int64_t to, std::vector<double>* sent_times) {
    std::vector<mjfMessage> inbox;
    const mjfMessage* leader = nullptr;
    for (int64_t step = from; step < to; ++step) {
      for (int v = 0; v <= 4; ++v) n.Broadcast(step, v, MessageAt(v, step));
      n.Deliver(step);
      FixedStateArchive saving = FixedStateArchive::Saving(state.data());
      n.VisitState(saving);  // throws when a queue outgrows its bound
      for (int v = 1; v <= 4; ++v) {
        n.Inbox(v, -1, &inbox, &leader);
        for (const auto& m : inbox) sent_times->push_back(m.send_time);
      }
    }
  };
  std::vector<double> first, second, ignored;
  fly(net, 0, 2500, &ignored);
  FixedStateArchive loading = FixedStateArchive::Loading(state.data());
  other.VisitState(loading);
  fly(net, 2500, 5000, &first);
  fly(other, 2500, 5000, &second);
  EXPECT_EQ(first, second);
  EXPECT_GT(first.size(), 1000u);
  for (int l = 0; l < net.n_links(); ++l) {
    EXPECT_EQ(net.link(l).stats().lost, other.link(l).stats().lost) << l;
    EXPECT_EQ(net.link(l).stats().delivered, other.link(l).stats().delivered) << l;
    EXPECT_GT(net.link(l).stats().lost, 0) << l;
  }
}

// The native plugin's walk (FixedStateArchive::Updating into the block it loaded from at the
// last step): its queues' unused slots are zeroed only where they held messages, and the block
// stays what a full save writes, step after step, as queues fill and drain.
TEST(NetworkTest, StateUpdatedInPlaceIsTheFullSaveAtEveryStep) {
  LinkParams p;
  p.period_steps = 1;
  p.latency = 0.01;
  p.jitter = 0.02;
  p.loss = 0.3;
  const std::vector<LinkSpec> specs = LeaderAndRing(3, p);
  Network net(3, specs, kDt, 5);
  using runner::FixedStateArchive;
  FixedStateArchive sizing = FixedStateArchive::Sizing();
  net.VisitState(sizing);
  std::vector<double> block(sizing.size()), full(sizing.size());
  std::vector<mjfMessage> inbox;
  const mjfMessage* leader = nullptr;
  int steps_clearing = 0;  // steps at which a number the block held became zero
  for (int64_t step = 0; step < 400; ++step) {
    FixedStateArchive loading = FixedStateArchive::Loading(block.data());
    if (step > 0) net.VisitState(loading);
    for (int v = 0; v <= 3; ++v) net.Broadcast(step, v, MessageAt(v, step));
    net.Deliver(step);
    for (int v = 1; v <= 3; ++v) net.Inbox(v, -1, &inbox, &leader);
    const std::vector<double> before = block;
    FixedStateArchive updating = FixedStateArchive::Updating(block.data());
    net.VisitState(updating);
    FixedStateArchive saving = FixedStateArchive::Saving(full.data());
    net.VisitState(saving);
    ASSERT_EQ(block, full) << "step " << step;
    for (size_t k = 0; k < block.size(); ++k) {
      if (before[k] != 0 && block[k] == 0) {
        ++steps_clearing;
        break;
      }
    }
  }
  EXPECT_GT(steps_clearing, 50);  // queues drained: there were slots to clear
}

// The bound of a link's queue: one message per broadcast within the longest delay, plus one.
TEST(NetworkTest, MaxInFlightIsTheDelayOverThePeriodPlusOne) {
  LinkParams p;
  p.period_steps = 10;
  p.latency = 0.02;
  EXPECT_EQ(MaxInFlight(p, kDt), 3);  // b13: 20 ms at 100 Hz
  p.jitter = 0.015;
  EXPECT_EQ(MaxInFlight(p, kDt), 4);
  p.period_steps = 1;
  p.latency = 1.0;
  p.jitter = 0.0;
  EXPECT_EQ(MaxInFlight(p, kDt), 1001);
}

TEST(NetworkTest, OlderMessageThanTheOneHeldIsDropped) {
  // Jitter so wide that later messages often overtake earlier ones.
  LinkSpec spec{0, 1, {}};
  spec.params.jitter = 0.05;
  Network net(1, {spec}, kDt, 4);
  std::vector<mjfMessage> inbox;
  const mjfMessage* leader = nullptr;
  double held = -1.0;
  for (int64_t step = 0; step < 3000; ++step) {
    net.Broadcast(step, 0, MessageAt(0, step));
    net.Deliver(step);
    net.Inbox(1, -1, &inbox, &leader);
    if (leader) {
      EXPECT_GE(leader->send_time, held);  // never goes back in time
      held = leader->send_time;
    }
  }
  EXPECT_GT(net.link(0).stats().stale, 100);
}

// Jacobi rounds within a tick: refreshing only the round part of the inbox that round 0 packed
// (the receiver may have predicted its states) gives, field for field, what a fresh Inbox for
// that round packs, whether the round message got through (30 % loss) or not, over many ticks.
TEST(NetworkTest, RefreshRoundSetsTheRoundPartAsInboxDoes) {
  LinkParams lossy;
  lossy.loss = 0.3;
  lossy.jitter = 0.004;
  // Follower vehicles 1, 2, 3 all send to 3 (leader 0 -> 3 as well).
  Network net(3, {{1, 3, lossy}, {0, 3, lossy}, {2, 3, lossy}, {3, 1, lossy}}, kDt, 12);
  std::vector<mjfMessage> refreshed, fresh;
  const mjfMessage* leader = nullptr;
  int fresh_rounds = 0;
  for (int64_t step = 0; step < 400; ++step) {
    for (int v = 0; v <= 3; ++v) net.Broadcast(step, v, MessageAt(v, step));
    net.Deliver(step);
    net.ClearRounds();
    net.Inbox(3, -1, &refreshed, &leader);
    for (mjfMessage& m : refreshed) m.state.pos[1] = 7.0;  // a prediction the refresh keeps
    for (int round = 0; round < 3; ++round) {
      for (int v = 1; v <= 2; ++v) {
        mjfMessage r = MessageAt(v, step);
        r.round = round;
        r.n_payload = 2;
        r.payload[0] = 100.0 * v + round;
        net.ExchangeRound(v, r);
      }
      net.RefreshRound(3, round, &refreshed);
      net.Inbox(3, round, &fresh, &leader);
      ASSERT_EQ(refreshed.size(), fresh.size());
      for (size_t k = 0; k < fresh.size(); ++k) {
        EXPECT_EQ(refreshed[k].round, fresh[k].round);
        EXPECT_EQ(refreshed[k].n_payload, fresh[k].n_payload);
        EXPECT_EQ(0, std::memcmp(refreshed[k].payload, fresh[k].payload, sizeof fresh[k].payload));
        EXPECT_EQ(refreshed[k].send_time, fresh[k].send_time);
        EXPECT_EQ(refreshed[k].state.pos[1], 7.0);
        fresh_rounds += fresh[k].n_payload == 2 ? 1 : 0;  // held messages carry none
      }
    }
  }
  EXPECT_GT(fresh_rounds, 500);          // both cases occurred: rounds that got through ...
  EXPECT_LT(fresh_rounds, 2 * 3 * 400);  // ... and rounds that were lost
}

TEST(NetworkTest, RateIsAMultipleOfTheStep) {
  LinkSpec spec{0, 1, {}};
  spec.params.period_steps = 20;  // 50 Hz at 1 kHz physics
  Network net(1, {spec}, kDt, 1);
  for (int64_t step = 0; step < 1000; ++step) {
    net.Broadcast(step, 0, MessageAt(0, step));
    net.Deliver(step);
  }
  EXPECT_EQ(net.link(0).stats().sent, 50);
  EXPECT_EQ(net.link(0).stats().delivered, 50);
}

TEST(NetworkTest, RangeLimitedLinkDropsAndRestoresAtComputedTimes) {
  // Leader -> 1 -> 2. Follower 2 flies away from 1 at 2 m/s from 4 m, then back after 5 s; the
  // link 1 -> 2 (R = 10 m) exists while |p1 - p2| <= 10: it drops at t = 3 s (the first step
  // with d > 10 is 3.001 s) and comes back at t = 7 s, when d returns to 10.
  LinkParams far;
  LinkParams limited;
  limited.range = 10.0;
  Network net(2, {{0, 1, far}, {1, 2, limited}}, kDt, 1);
  std::vector<std::array<double, 3>> pos(3, {0, 0, 5});
  for (int64_t step = 0; step <= 10000; ++step) {
    const int64_t out = step <= 5000 ? step : 10000 - step;  // ms of flight away from follower 1
    pos[2][0] = 4.0 + 2.0 * static_cast<double>(out) / 1000.0;
    net.UpdateTopology(step, pos);
  }
  ASSERT_EQ(net.events().size(), 2u);
  EXPECT_FALSE(net.events()[0].up);
  EXPECT_NEAR(net.events()[0].time, 3.001, 1e-12);
  EXPECT_TRUE(net.events()[1].up);
  EXPECT_NEAR(net.events()[1].time, 7.0, 1e-12);
  // Without the link, follower 2 is cut off from the leader: no spanning tree from 3.001 s to
  // 6.999 s inclusive, 3999 steps.
  EXPECT_NEAR(net.time_without_spanning_tree(), 3.999, 1e-9);
  EXPECT_TRUE(net.has_spanning_tree());
}

TEST(NetworkTest, AgeOfInformationIsTheLatency) {
  LinkSpec spec{0, 1, {}};
  spec.params.latency = 0.02;
  Network net(1, {spec}, kDt, 1);
  for (int64_t step = 0; step < 1000; ++step) {
    net.Broadcast(step, 0, MessageAt(0, step));
    net.Deliver(step);
  }
  // From step 20 on, the held message is exactly 20 ms old; before, the age grows from 0.
  EXPECT_NEAR(net.age(1).max, 0.02, 1e-12);
  EXPECT_NEAR(net.age(1).mean(), (0.02 * 980 + 0.001 * (19 * 20 / 2)) / 1000, 1e-12);
}

}  // namespace
}  // namespace mjf::network
