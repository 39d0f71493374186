// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
// The reaching-transient metrics from hand-made record ticks.
#include "mjformation/record/transient_metrics.hpp"

#include <gtest/gtest.h>

namespace mjf::runner {
namespace {

TEST(TransientMetrics, DistancesSettleTimeAndPeaks) {
  TransientMetrics m(2);
  const double demand0[2] = {3.0, 4.0}, demand1[2] = {0.6, 0.8};
  // Follower 0: 8 m away at 4 s (before the settle time), 2 m at 6 s, 0.5 m from 7 s on.
  // Follower 1: inside 1 m at 4 s and 6 s, 1.5 m at the last tick (not settled).
  const double t[4] = {4.0, 6.0, 7.0, 8.0};
  const double d0[4] = {8.0, 2.0, 0.5, 0.5}, d1[4] = {0.2, 0.3, 0.4, 1.5};
  const double v0[4] = {0.0, 2.0, 2.0, 2.0};  // +1 m/s^2 over 2 s, then constant
  for (int k = 0; k < 4; ++k) {
    const double vel0[2] = {v0[k], 0.0}, vel1[2] = {0.0, 3.0 * k};  // 3 m/s^2 from 6 s
    m.Add(0, t[k], d0[k], demand0, vel0);
    m.Add(1, t[k], d1[k], demand1, vel1);
  }
  nlohmann::ordered_json out;
  m.AddTo(&out);
  EXPECT_DOUBLE_EQ(out["max_slot_distance_after_5s_m"][0].get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(out["max_slot_distance_after_5s_m"][1].get<double>(), 1.5);
  EXPECT_DOUBLE_EQ(out["time_within_1m_s"][0].get<double>(), 6.0);  // last tick outside
  EXPECT_TRUE(out["time_within_1m_s"][1].is_null());
  EXPECT_DOUBLE_EQ(out["peak_demanded_accel"][0].get<double>(), 5.0);
  EXPECT_DOUBLE_EQ(out["peak_demanded_accel"][1].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(out["peak_delivered_accel"][0].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(out["peak_delivered_accel"][1].get<double>(), 3.0);
}

TEST(TransientMetrics, NeverOutsideSettlesAtZero) {
  TransientMetrics m(1);
  const double zero[2] = {0.0, 0.0};
  m.Add(0, 0.0, 0.1, zero, zero);
  m.Add(0, 1.0, 0.2, zero, zero);
  nlohmann::ordered_json out;
  m.AddTo(&out);
  EXPECT_DOUBLE_EQ(out["time_within_1m_s"][0].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(out["max_slot_distance_after_5s_m"][0].get<double>(), 0.0);
}

}  // namespace
}  // namespace mjf::runner
