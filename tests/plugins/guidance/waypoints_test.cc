// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// waypoints: a smooth path through the points within the bounds; points too close for the
// bounds, or coincident, refused.
#include "mjformation/guidance/waypoints.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "guidance_util.hpp"

namespace mjf::guidance {
namespace {

using test::Fly;
using test::Stats;

TEST(WaypointTest, SmoothPathThroughThePointsWithinBounds) {
  WaypointGuidance::Config c;
  c.points = {{20, 0}, {0, 20}, {-20, 0}, {0, -20}};
  c.speed = 2.0;
  c.loop = true;
  const WaypointGuidance law(c);
  const HermitePath& path = law.path();
  const double leg = std::hypot(20.0, 20.0) / 2.0;  // s per segment
  EXPECT_NEAR(path.duration(), 4 * leg, 1e-9);
  for (int k = 0; k <= 4; ++k) {  // through each point at its time, and around again
    const GuidanceOutput at = path.Evaluate(k * leg);
    EXPECT_NEAR(at.pos[0], c.points[k % 4][0], 1e-9) << k;
    EXPECT_NEAR(at.pos[1], c.points[k % 4][1], 1e-9) << k;
  }
  // C1: velocity continuous across a knot; acceleration inside the bounds everywhere (dense).
  const GuidanceOutput before = path.Evaluate(leg - 1e-7), after = path.Evaluate(leg + 1e-7);
  EXPECT_NEAR(before.vel[0], after.vel[0], 1e-5);
  EXPECT_NEAR(before.vel[1], after.vel[1], 1e-5);
  for (double t = 0; t < 2 * path.duration(); t += 0.01) {
    const GuidanceOutput r = path.Evaluate(t);
    ASSERT_LE(std::abs(r.acc[0]), 1.0 + 1e-12) << t;
    ASSERT_LE(std::abs(r.acc[1]), 1.0 + 1e-12) << t;
  }
  const auto hi = path.max_acc(), lo = path.min_acc();
  EXPECT_LE(hi[0], 1.0);
  EXPECT_GE(lo[0], -1.0);
  const Stats s = Fly([&](double t, const Vec3& p, const Vec3& v) { return law.Update(t, p, v); },
                      {20, 0, 5}, 0.01, 200.0);
  EXPECT_GE(s.a_min[0], -1.0);
  EXPECT_LE(s.a_max[1], 1.0);
}

TEST(WaypointTest, TooCloseForTheBoundsOrCoincidentRefused) {
  WaypointGuidance::Config c;
  c.points = {{0, 0}, {1, 0}, {1, 1}};  // 1 m legs at 4 m/s need ~ 16 m/s^2
  c.speed = 4.0;
  c.loop = false;
  try {
    WaypointGuidance law(c);
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("points"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("too close"), std::string::npos) << e.what();
  }
  c.speed = 0.5;  // slow enough: 6 (1 m) / (2 s)^2 = 1.5 ... still above 1
  EXPECT_THROW(WaypointGuidance{c}, std::invalid_argument);
  c.speed = 0.3;
  EXPECT_NO_THROW(WaypointGuidance{c});
  c.points = {{0, 0}, {0, 0}};
  EXPECT_THROW(WaypointGuidance{c}, std::invalid_argument);
}

}  // namespace
}  // namespace mjf::guidance
