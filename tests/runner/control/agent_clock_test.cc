// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The followers' clocks: drawn within the configured bounds, seeded, and the steps
// they read produce the configured sample times.
#include "mjformation/control/agent_clock.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace mjf::runner {
namespace {

TEST(AgentClockTest, InPhaseByDefault) {
  const AgentClocks clocks(3, 0.0, 0.0, 0.001, 7);
  EXPECT_FALSE(clocks.active());
  EXPECT_EQ(clocks.Local(2, 1.234), 1.234);
  EXPECT_EQ(clocks.LocalStep(1, 0.003), 3);
}

TEST(AgentClockTest, DrawsAreBoundedSeededAndDistinct) {
  const AgentClocks a(50, 0.025, 200.0, 0.001, 7), b(50, 0.025, 200.0, 0.001, 7);
  const AgentClocks c(50, 0.025, 200.0, 0.001, 8);
  int differ = 0;
  for (int i = 0; i < 50; ++i) {
    EXPECT_GE(a.offset(i), 0.0);
    EXPECT_LE(a.offset(i), 0.025);
    EXPECT_LE(std::abs(a.drift(i)), 200e-6);
    EXPECT_EQ(a.offset(i), b.offset(i));
    EXPECT_EQ(a.drift(i), b.drift(i));
    differ += a.offset(i) != c.offset(i) ? 1 : 0;
  }
  EXPECT_GT(differ, 45);
  EXPECT_NE(a.offset(0), a.offset(1));
}

// A follower with period T = 50 steps samples when floor(c_i(t) / dt) enters a new multiple of
// 50: the first true step at or after (k T - o_i) / (1 + d_i), for every k over 20 s.
TEST(AgentClockTest, StepsReadProduceTheConfiguredSampleTimes) {
  const double dt = 0.001, period = 0.05;
  const AgentClocks clocks(4, 0.04, 1e4, dt, 3);  // drift up to 1 %: the bound
  for (int i = 0; i < 4; ++i) {
    int64_t last_index = clocks.LocalStep(i, 0.0) / 50;
    int samples = 0;
    for (int64_t n = 1; n < 20000; ++n) {
      const double t = static_cast<double>(n) * dt;
      const int64_t index = clocks.LocalStep(i, t) / 50;
      if (index == last_index) continue;
      ASSERT_EQ(index, last_index + 1) << "a sample skipped at step " << n;
      last_index = index;
      ++samples;
      const double ideal =
          (static_cast<double>(index) * period - clocks.offset(i)) / (1.0 + clocks.drift(i));
      EXPECT_GE(t, ideal - 1e-9);
      EXPECT_LT(t, ideal + dt + 1e-9) << "follower " << i << " sample " << index;
    }
    // 20 s of its clock's periods, within one of (1 + d_i) 20 / T.
    EXPECT_NEAR(samples, (1.0 + clocks.drift(i)) * 20.0 / period, 1.0);
  }
}

// Synchronised clocks ([execution] clock_sync): the same draws and the same sample steps as free
// clocks of the same seed (the loops still sample out of phase), but every clock reads the
// common time.
TEST(AgentClockTest, SynchronisedClocksReadTheCommonTimeAndSampleAsFreeOnes) {
  const AgentClocks free(5, 0.04, 300.0, 0.001, 11);
  const AgentClocks synced(5, 0.04, 300.0, 0.001, 11, /*synchronised=*/true);
  EXPECT_FALSE(free.synchronised());
  EXPECT_TRUE(synced.synchronised());
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(free.offset(i), synced.offset(i));
    EXPECT_EQ(free.drift(i), synced.drift(i));
    for (double t : {0.0, 0.0123, 7.5, 39.999}) {
      EXPECT_EQ(synced.LocalStep(i, t), free.LocalStep(i, t));
      EXPECT_EQ(synced.Reading(i + 1, t), t);
      EXPECT_EQ(free.Reading(i + 1, t), free.Local(i + 1, t));
    }
  }
  EXPECT_NE(free.Reading(1, 1.0), 1.0);  // the free clock is off (offset or drift drawn)
}

}  // namespace
}  // namespace mjf::runner
