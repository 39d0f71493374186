// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// What the runner draws over the scene (trails, desired slots, the desired circle, vehicle
// markers, the time label) and where its following camera looks, computed from vehicle
// positions alone, so that the replay of a run directory (replay.hpp) and the live viewer draw
// exactly what `run` draws into its snapshots (run.cc, same rules).
#ifndef MJFORMATION_RECORD_FRAME_VIEW_HPP_
#define MJFORMATION_RECORD_FRAME_VIEW_HPP_

#include <array>
#include <deque>
#include <string>
#include <vector>

#include "mjformation/config/experiment.hpp"
#include "mjformation/render.hpp"
#include "mjformation/scene/scene.hpp"

namespace mjf::runner {

using Vec3 = std::array<double, 3>;

// The last `seconds` of each vehicle's path, sampled every `period` s (run.cc: 0.1 s).
class TrailBuffer {
 public:
  TrailBuffer(int n_vehicles, double seconds, double period);
  void Add(const std::vector<Vec3>& positions);
  void Clear();
  const std::vector<std::deque<Vec3>>& trails() const { return trails_; }
  template <typename Archive>
  void VisitState(Archive& a) {
    a(trails_);
  }

 private:
  std::vector<std::deque<Vec3>> trails_;
  size_t capacity_;
};

// The camera's follow point: the formation's centroid, or the leader for camera = "leader".
Vec3 CameraTarget(const RenderConfig& render, const std::vector<Vec3>& positions);

// The configured camera; a following camera backs off so that every vehicle stays in the
// picture: MuJoCo's 45 degree field of view shows about 0.35 x distance around the target, hence
// distance >= 2.8 x the farthest vehicle from it.
render::CameraSpec FollowingCamera(const RenderConfig& render, const std::vector<Vec3>& positions,
                                   const Vec3& target);

// What is drawn: trails, markers under the vehicles, the followers' slots (x, y; NaN: none) at
// `altitude`, the desired circle of `ring_radius` about the leader (0: none), the label.
render::Overlay FrameOverlay(const TrailBuffer& trails, const std::vector<Vec3>& positions,
                             const std::vector<std::array<double, 2>>& slots, double altitude,
                             double ring_radius, const std::string& label);

// "<name>   t = 12.3 s", as in the snapshots.
std::string FrameLabel(const std::string& name, double t);

// Each vehicle's root body (uav<i>_vehicle) in a composed scene, -1 where absent: the bodies
// recoloured in the vehicle's palette colour at render time (render::TintVehicleGeoms).
std::vector<int> VehicleBodies(const mjModel* m, int n_vehicles);

// Whether a safety event of `kind` is marked in pictures: all but near misses, which can be
// many and are not damage.
bool MarkedEventKind(const std::string& kind);
// The mark of an event of `kind` at `time` involving `vehicles` (0 = leader): at `pos` (the
// vehicle's position when it happened; for a pair the midpoint), labelled "F6 flip 34.19 s".
render::EventMark MakeEventMark(const std::string& kind, double time,
                                const std::vector<int>& vehicles, const Vec3& pos);
constexpr size_t kMaxEventMarks = 20;  // the first ones; more would hide the picture

}  // namespace mjf::runner

#endif  // MJFORMATION_RECORD_FRAME_VIEW_HPP_
