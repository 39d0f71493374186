// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// bounds.hpp: the seeded uniform numbers every random leader draws, and the tracking leaders
// (TrackClamped) as pure functions of (t, state).
#include "mjformation/guidance/bounds.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "guidance_util.hpp"
#include "mjformation/guidance/lemniscate.hpp"
#include "mjformation/guidance/trajectory.hpp"
#include "mjformation/guidance/waypoints.hpp"

namespace mjf::guidance {
namespace {

using test::Fly;
using test::WriteTemp;

// The tracking leaders are functions of (t, state): two instances from the same configuration
// give the same commands bit for bit.
TEST(TrackingLeadersTest, SameConfigurationSameCommands) {
  LemniscateGuidance::Config lc;
  WaypointGuidance::Config wc;
  wc.points = {{20, 0}, {0, 20}, {-20, 0}, {0, -20}};
  wc.loop = true;
  const TrajectoryTable table =
      ReadTrajectoryCsv(WriteTemp("traj_det.csv", "0,0,0\n3,2,1\n6,5,1\n9,5,4\n"));
  const std::vector<std::function<GuidanceOutput(double, const Vec3&, const Vec3&)>> pairs[] = {
      {[l = LemniscateGuidance(lc)](double t, const Vec3& p, const Vec3& v) {
         return l.Update(t, p, v);
       },
       [l = LemniscateGuidance(lc)](double t, const Vec3& p, const Vec3& v) {
         return l.Update(t, p, v);
       }},
      {[w = WaypointGuidance(wc)](double t, const Vec3& p, const Vec3& v) {
         return w.Update(t, p, v);
       },
       [w = WaypointGuidance(wc)](double t, const Vec3& p, const Vec3& v) {
         return w.Update(t, p, v);
       }},
      {[g = TrajectoryGuidance({}, table)](double t, const Vec3& p, const Vec3& v) {
         return g.Update(t, p, v);
       },
       [g = TrajectoryGuidance({}, table)](double t, const Vec3& p, const Vec3& v) {
         return g.Update(t, p, v);
       }},
  };
  for (const auto& pair : pairs) {
    EXPECT_EQ(Fly(pair[0], {3, -2, 5}, 0.01, 60.0).ax, Fly(pair[1], {3, -2, 5}, 0.01, 60.0).ax);
  }
}

TEST(HashUniformTest, UniformAndIndependentOfCallOrder) {
  double sum = 0, lo = 1, hi = 0;
  for (uint64_t k = 0; k < 100000; ++k) {
    const double u = HashUniform(9, 0, k);
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
    lo = std::min(lo, u);
    hi = std::max(hi, u);
  }
  EXPECT_NEAR(sum / 100000, 0.5, 0.005);  // 5 standard errors of the mean (0.0009)
  EXPECT_LT(lo, 1e-3);
  EXPECT_GT(hi, 1 - 1e-3);
  EXPECT_NE(HashUniform(9, 0, 5), HashUniform(9, 1, 5));
  EXPECT_NE(HashUniform(9, 0, 5), HashUniform(10, 0, 5));
}

}  // namespace
}  // namespace mjf::guidance
