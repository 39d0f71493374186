// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Unit tests of the source:
// runner/record/src/safety_events.cc: each kind of safety event is found when its threshold is
// crossed and not before, once per vehicle (or pair), with its time, vehicles and value.
#include "mjformation/record/safety_events.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace mjf::runner {
namespace {

mjfVehicleState At(double x, double y, double z) {
  mjfVehicleState s{};
  s.pos[0] = x;
  s.pos[1] = y;
  s.pos[2] = z;
  s.quat[0] = 1;
  return s;
}

// Rolled by `deg` about x: q = (cos(a/2), sin(a/2), 0, 0).
mjfVehicleState Rolled(mjfVehicleState s, double deg) {
  const double a = deg * M_PI / 180.0;
  s.quat[0] = std::cos(a / 2);
  s.quat[1] = std::sin(a / 2);
  return s;
}

TEST(SafetyMonitor, FarApartLevelAndAloftIsNoEvent) {
  SafetyMonitor m(SafetyConfig{}, {0.2, 0.2, 0.2});
  EXPECT_EQ(m.Check(0.0, {At(0, 0, 5), At(3, 0, 5), Rolled(At(0, 3, 5), 89)}), 0u);
  EXPECT_TRUE(m.events().empty());
  EXPECT_EQ(m.Summary()["count"], 0);
}

TEST(SafetyMonitor, FlipBeyondTheThresholdOncePerVehicle) {
  SafetyMonitor m(SafetyConfig{}, {0.2, 0.2});
  m.Check(1.0, {At(0, 0, 5), Rolled(At(5, 0, 5), 80)});
  EXPECT_TRUE(m.events().empty());
  EXPECT_EQ(m.Check(2.5, {At(0, 0, 5), Rolled(At(5, 0, 5), 120)}), 1u);
  EXPECT_EQ(m.Check(2.6, {At(0, 0, 5), Rolled(At(5, 0, 5), 170)}), 0u);  // reported once
  ASSERT_EQ(m.events().size(), 1u);
  const SafetyEvent& e = m.events()[0];
  EXPECT_EQ(e.kind, "flip");
  EXPECT_EQ(e.vehicles, std::vector<int>{1});
  EXPECT_DOUBLE_EQ(e.time_s, 2.5);
  EXPECT_NEAR(e.value, 120, 1e-9);
  EXPECT_EQ(DescribeEvent(e), "follower 1 flipped at 2.50 s (tilt 120.0 deg)");
}

// The tilt's acos is skipped where the cosine shows the tilt below the limit
// (safety_events.cc): a tilt a few ulps of the cosine either side of the limit is still judged
// by the tilt itself, and a flip's value is the tilt computed from the quaternion as before.
TEST(SafetyMonitor, FlipAtTheThresholdIsJudgedByTheTiltItself) {
  for (const double limit : {30.0, 90.0, 179.0, 180.0}) {
    SafetyConfig config;
    config.flip_tilt_deg = limit;
    const double limit_cos = std::cos(limit * M_PI / 180.0);
    int flips = 0;
    // Quaternions rolled about x whose R_zz = 1 - 2 x^2 steps through the limit's cosine.
    for (int k = -40; k <= 40; ++k) {
      const double c = std::clamp(limit_cos + k * 1e-12, -1.0, 1.0);
      mjfVehicleState s = At(0, 0, 5);
      s.quat[1] = std::sqrt((1 - c) / 2);
      s.quat[0] = std::sqrt(1 - s.quat[1] * s.quat[1]);
      const double cos_tilt = std::clamp(1 - 2 * (s.quat[1] * s.quat[1]), -1.0, 1.0);
      const double tilt = std::acos(cos_tilt) * 180.0 / M_PI;  // the formula of the monitor
      SafetyMonitor m(config, {0.2});
      const size_t fresh = m.Check(1.0, {s});
      EXPECT_EQ(fresh, tilt > limit ? 1u : 0u) << "limit " << limit << ", step " << k;
      if (fresh == 1) {
        EXPECT_EQ(m.events()[0].value, tilt);
        ++flips;
      }
    }
    // The steps cross the limit (at 180 no tilt exceeds it).
    if (limit < 180) {
      EXPECT_GT(flips, 0) << limit;
      EXPECT_LT(flips, 81) << limit;
    }
  }
}

TEST(SafetyMonitor, GroundImpactOnlyAfterTheVehicleWasAloft) {
  SafetyMonitor m(SafetyConfig{}, {0.2});
  m.Check(0.0, {At(0, 0, 0.1)});  // starts on the ground: no impact
  EXPECT_TRUE(m.events().empty());
  m.Check(1.0, {At(0, 0, 3)});
  m.Check(2.0, {At(0, 0, 0.15)});
  ASSERT_EQ(m.events().size(), 1u);
  EXPECT_EQ(m.events()[0].kind, "ground_impact");
  EXPECT_EQ(m.events()[0].vehicles, std::vector<int>{0});
  EXPECT_EQ(DescribeEvent(m.events()[0]), "leader hit the ground at 2.00 s (z = 0.150 m)");
}

TEST(SafetyMonitor, NearMissThenCollisionFromTheRadii) {
  SafetyConfig config;
  config.near_miss_m = 0.5;
  SafetyMonitor m(config, {0.2, 0.3, 0.2});
  m.Check(0.0, {At(0, 0, 5), At(1.01, 0, 5), At(-9, 0, 5)});  // gap 0.51 m
  EXPECT_TRUE(m.events().empty());
  m.Check(1.0, {At(0, 0, 5), At(0.9, 0, 5), At(-9, 0, 5)});  // gap 0.4 m: near miss
  ASSERT_EQ(m.events().size(), 1u);
  EXPECT_EQ(m.events()[0].kind, "near_miss");
  EXPECT_NEAR(m.events()[0].clearance, 0.4, 1e-12);
  m.Check(2.0, {At(0, 0, 5), At(0.45, 0, 5), At(-9, 0, 5)});  // 0.45 < 0.2 + 0.3
  ASSERT_EQ(m.events().size(), 2u);
  EXPECT_EQ(m.events()[1].kind, "collision");
  EXPECT_EQ(m.events()[1].vehicles, (std::vector<int>{0, 1}));
  EXPECT_NEAR(m.events()[1].value, 0.45, 1e-12);
  EXPECT_EQ(DescribeEvent(m.events()[1]),
            "leader and follower 1 collided at 2.00 s (separation 0.450 m)");
}

TEST(SafetyMonitor, PairsAreFoundWhateverTheirOrderAlongX) {
  SafetyConfig config;
  config.near_miss_m = 0;
  SafetyMonitor m(config, std::vector<double>(5, 0.1));
  // Vehicles 4 and 0 meet after the others have swapped places along x.
  m.Check(0.0, {At(0, 0, 5), At(1, 0, 5), At(2, 0, 5), At(3, 0, 5), At(4, 0, 5)});
  m.Check(1.0, {At(4, 0, 5), At(3, 0, 5), At(2, 0, 5), At(1, 0, 5), At(4.1, 0.05, 5)});
  ASSERT_EQ(m.events().size(), 1u);
  EXPECT_EQ(m.events()[0].vehicles, (std::vector<int>{0, 4}));
}

// Begin, Scan over ranges (the partitions' threads, in any order) and Finish report what Check
// reports, in the same order, step after step: a crowd that drifts, crosses, tilts, lands and
// leaves the region.
TEST(SafetyMonitor, ScanningInRangesReportsWhatCheckReports) {
  SafetyConfig config;
  config.near_miss_m = 0.3;
  config.has_region = true;
  config.region = {-4, 4, -4, 4, 0, 20};
  const int n = 12;
  std::vector<double> radii(n);
  for (int i = 0; i < n; ++i) radii[i] = 0.1 + 0.01 * i;
  SafetyMonitor whole(config, radii), split(config, radii);
  size_t events = 0;
  for (int step = 0; step < 60; ++step) {
    const double t = 0.1 * step;
    std::vector<mjfVehicleState> states;
    for (int i = 0; i < n; ++i) {
      // Vehicles on a line, the odd ones moving against the even ones, some sinking and tilting.
      const double x = 0.6 * i + (i % 2 ? -1 : 1) * 0.05 * step * (1 + 0.1 * i);
      const double z = i % 3 == 0 ? 2.0 - 0.04 * step : 2.0;
      states.push_back(Rolled(At(x - 3, 0.02 * i, z), i % 4 == 1 ? 3.0 * step : 0.0));
    }
    const size_t expected = whole.Check(t, states);
    split.Begin(states);
    split.Scan(7, 5, states);  // the ranges [0, 3), [3, 7), [7, 12), last first
    split.Scan(0, 3, states);
    split.Scan(3, 4, states);
    EXPECT_EQ(split.Finish(t, states), expected) << "step " << step;
    ASSERT_EQ(split.events().size(), whole.events().size()) << "step " << step;
    for (size_t k = 0; k < whole.events().size(); ++k) {
      const SafetyEvent& a = whole.events()[k];
      const SafetyEvent& b = split.events()[k];
      EXPECT_EQ(b.kind, a.kind);
      EXPECT_EQ(b.time_s, a.time_s);
      EXPECT_EQ(b.vehicles, a.vehicles);
      EXPECT_EQ(b.value, a.value);
      EXPECT_EQ(b.clearance, a.clearance);
    }
    events = whole.events().size();
  }
  // Every kind happened, so the comparison covered each.
  const auto counts = whole.Summary()["by_kind"];
  for (const char* kind : {"flip", "ground_impact", "collision", "near_miss", "left_region"}) {
    EXPECT_GT(counts[kind].get<int>(), 0) << kind;
  }
  EXPECT_GT(events, 10u);
}

TEST(SafetyMonitor, LeavingTheRegion) {
  SafetyConfig config;
  config.has_region = true;
  config.region = {-10, 10, -10, 10, 0, 20};
  SafetyMonitor m(config, {0.2, 0.2});
  m.Check(0.0, {At(0, 0, 5), At(9, 0, 5)});
  EXPECT_TRUE(m.events().empty());
  m.Check(1.0, {At(0, 0, 5), At(13, 4, 5)});
  ASSERT_EQ(m.events().size(), 1u);
  EXPECT_EQ(m.events()[0].kind, "left_region");
  EXPECT_NEAR(m.events()[0].value, 3, 1e-12);
  const auto s = m.Summary();
  EXPECT_EQ(s["by_kind"]["left_region"], 1);
  EXPECT_EQ(s["list"][0]["what"], "follower 1 left the region at 1.00 s (3.000 m outside)");
}

}  // namespace
}  // namespace mjf::runner
