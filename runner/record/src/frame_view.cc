// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/record/frame_view.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace mjf::runner {

TrailBuffer::TrailBuffer(int n_vehicles, double seconds, double period)
    : trails_(n_vehicles), capacity_(static_cast<size_t>(seconds / period) + 1) {}

void TrailBuffer::Add(const std::vector<Vec3>& positions) {
  for (size_t i = 0; i < trails_.size() && i < positions.size(); ++i) {
    trails_[i].push_back(positions[i]);
    if (trails_[i].size() > capacity_) trails_[i].pop_front();
  }
}

void TrailBuffer::Clear() {
  for (auto& t : trails_) t.clear();
}

Vec3 CameraTarget(const RenderConfig& render, const std::vector<Vec3>& positions) {
  Vec3 c = {0, 0, 0};
  if (positions.empty()) return c;
  if (render.camera == CameraMode::kLeader) return positions[0];
  for (const auto& p : positions) {
    for (int k = 0; k < 3; ++k) c[k] += p[k];
  }
  for (double& v : c) v /= static_cast<double>(positions.size());
  return c;
}

render::CameraSpec FollowingCamera(const RenderConfig& r, const std::vector<Vec3>& positions,
                                   const Vec3& target) {
  render::CameraSpec cam;
  cam.mode = r.camera == CameraMode::kFixed ? "fixed" : "follow";
  cam.distance = r.distance;
  if (cam.mode == "follow") {
    double farthest = 0;
    for (const auto& p : positions) {
      farthest = std::max(farthest, std::hypot(p[0] - target[0], p[1] - target[1]));
    }
    cam.distance = std::max(r.distance, 2.8 * farthest);
  }
  cam.azimuth = r.azimuth;
  cam.elevation = r.elevation;
  for (int k = 0; k < 3; ++k) cam.lookat[k] = r.lookat[k];
  return cam;
}

render::Overlay FrameOverlay(const TrailBuffer& trails, const std::vector<Vec3>& positions,
                             const std::vector<std::array<double, 2>>& slots, double altitude,
                             double ring_radius, const std::string& label) {
  render::Overlay o;
  for (const auto& t : trails.trails()) o.trails.emplace_back(t.begin(), t.end());
  o.markers = positions;
  for (size_t i = 1; i < slots.size(); ++i) {
    if (!std::isnan(slots[i][0])) o.slots.push_back({slots[i][0], slots[i][1], altitude});
  }
  if (ring_radius > 0 && !positions.empty()) {
    const auto& leader = positions[0];
    for (int k = 0; k <= 96; ++k) {
      const double a = 2 * M_PI * k / 96;
      o.ring_points.push_back(
          {leader[0] + ring_radius * std::cos(a), leader[1] + ring_radius * std::sin(a), altitude});
    }
  }
  // The picture's scale: at the default 45 m the vehicles are dots, and the ring of known radius
  // is the one length a reader can measure against.
  o.label =
      ring_radius > 0 && !positions.empty()
          ? label + fmt::format("   white ring: desired formation, radius {:g} m", ring_radius)
          : label;
  o.legend_vehicles = static_cast<int>(positions.size());
  return o;
}

std::string FrameLabel(const std::string& name, double t) {
  return fmt::format("{}   t = {:.1f} s", name, t);
}

std::vector<int> VehicleBodies(const mjModel* m, int n_vehicles) {
  std::vector<int> bodies;
  for (int i = 0; i < n_vehicles; ++i) {
    bodies.push_back(mj_name2id(m, mjOBJ_BODY, (VehiclePrefix(i) + "vehicle").c_str()));
  }
  return bodies;
}

bool MarkedEventKind(const std::string& kind) { return kind != "near_miss"; }

render::EventMark MakeEventMark(const std::string& kind, double time,
                                const std::vector<int>& vehicles, const Vec3& pos) {
  std::string who;
  for (int v : vehicles) {
    who += (who.empty() ? "" : "-") + (v == 0 ? std::string("L") : "F" + std::to_string(v));
  }
  return {pos, fmt::format("{} {} {:.2f} s", who, kind, time)};
}

}  // namespace mjf::runner
