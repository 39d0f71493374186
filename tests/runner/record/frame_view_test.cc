// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// runner/record/src/frame_view.cc: trails, the camera's follow point and distance, the overlay and
// the label that run, replay and the viewer all draw.
#include "mjformation/record/frame_view.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace mjf::runner {
namespace {

TEST(FrameViewTest, TrailsKeepTheLastSecondsOnly) {
  TrailBuffer trails(2, 1.0, 0.25);  // 1 s at 4 Hz: 1 / 0.25 + 1 = 5 points
  for (int k = 0; k < 8; ++k) {
    trails.Add({{double(k), 0, 0}, {0, double(k), 0}});
  }
  ASSERT_EQ(trails.trails().size(), 2u);
  ASSERT_EQ(trails.trails()[0].size(), 5u);
  EXPECT_EQ(trails.trails()[0].front()[0], 3.0);  // the oldest kept
  EXPECT_EQ(trails.trails()[0].back()[0], 7.0);
  EXPECT_EQ(trails.trails()[1].back()[1], 7.0);
  // Fewer positions than trails: the others are left alone.
  trails.Add({{100, 0, 0}});
  EXPECT_EQ(trails.trails()[0].back()[0], 100.0);
  EXPECT_EQ(trails.trails()[1].back()[1], 7.0);
  trails.Clear();
  EXPECT_TRUE(trails.trails()[0].empty());
  EXPECT_TRUE(trails.trails()[1].empty());
}

TEST(FrameViewTest, CameraTargetIsTheCentroidOrTheLeader) {
  const std::vector<Vec3> p = {{10, 0, 2}, {0, 3, 2}, {-4, -3, 5}};
  RenderConfig r;
  r.camera = CameraMode::kFollow;
  EXPECT_EQ(CameraTarget(r, p), (Vec3{2, 0, 3}));
  r.camera = CameraMode::kLeader;
  EXPECT_EQ(CameraTarget(r, p), (Vec3{10, 0, 2}));
  EXPECT_EQ(CameraTarget(r, {}), (Vec3{0, 0, 0}));
}

TEST(FrameViewTest, AFollowingCameraBacksOffToShowEveryone) {
  RenderConfig r;
  r.distance = 20;
  r.azimuth = 30;
  r.elevation = -40;
  r.lookat = {1, 2, 3};
  // Farthest vehicle 15 m from the target (horizontally; height does not count): 2.8 x 15 = 42.
  const std::vector<Vec3> far = {{0, 0, 0}, {9, 12, 50}};
  auto cam = FollowingCamera(r, far, {0, 0, 0});
  EXPECT_EQ(cam.mode, "follow");
  EXPECT_DOUBLE_EQ(cam.distance, 42.0);
  EXPECT_EQ(cam.azimuth, 30);
  EXPECT_EQ(cam.elevation, -40);
  EXPECT_EQ(cam.lookat[2], 3);
  // Close together: the configured distance.
  EXPECT_EQ(FollowingCamera(r, {{0, 0, 0}, {1, 1, 0}}, {0, 0, 0}).distance, 20.0);
  // A fixed camera never moves.
  r.camera = CameraMode::kFixed;
  cam = FollowingCamera(r, far, {0, 0, 0});
  EXPECT_EQ(cam.mode, "fixed");
  EXPECT_EQ(cam.distance, 20.0);
}

TEST(FrameViewTest, OverlaySlotsRingAndLabel) {
  TrailBuffer trails(3, 1.0, 0.5);
  trails.Add({{0, 0, 1}, {1, 0, 1}, {2, 0, 1}});
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<Vec3> positions = {{5, 5, 2}, {1, 0, 2}, {2, 0, 2}};
  // The leader's slot (index 0) is never drawn, nor a follower's NaN slot.
  const auto o = FrameOverlay(trails, positions, {{9, 9}, {3, 4}, {nan, nan}}, 2.5, 10.0, "x");
  ASSERT_EQ(o.slots.size(), 1u);
  EXPECT_EQ(o.slots[0], (std::array<double, 3>{3, 4, 2.5}));
  EXPECT_EQ(o.markers, positions);
  ASSERT_EQ(o.trails.size(), 3u);
  EXPECT_EQ(o.trails[2].front(), (std::array<double, 3>{2, 0, 1}));
  // 97 points closing a 10 m circle about the leader, at the altitude.
  ASSERT_EQ(o.ring_points.size(), 97u);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(o.ring_points.front()[k], o.ring_points.back()[k], 1e-12);
  EXPECT_NEAR(o.ring_points.front()[0], 15.0, 1e-12);  // starts on +x of the leader
  for (const auto& q : o.ring_points) {
    EXPECT_NEAR(std::hypot(q[0] - 5, q[1] - 5), 10.0, 1e-12);
    EXPECT_EQ(q[2], 2.5);
  }
  // The ring is the picture's scale: the label says what it is and how large.
  EXPECT_EQ(o.label, "x   white ring: desired formation, radius 10 m");
  const auto no_ring = FrameOverlay(trails, positions, {}, 2.5, 0.0, "x");
  EXPECT_TRUE(no_ring.ring_points.empty());
  EXPECT_EQ(no_ring.label, "x");
}

TEST(FrameViewTest, Label) {
  EXPECT_EQ(FrameLabel("exp2", 12.345), "exp2   t = 12.3 s");
  EXPECT_EQ(FrameLabel("a", 0), "a   t = 0.0 s");
  EXPECT_EQ(FrameLabel("a", 39.96), "a   t = 40.0 s");
}

}  // namespace
}  // namespace mjf::runner
