// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// waypoints: the adapter of WaypointGuidance.
#include "mjformation/guidance/waypoints.hpp"

#include <string>

#include "adapter.hpp"

namespace mjf::guidance::adapter {
namespace {

using mjf::plugin::ConfigError;

constexpr const char* kPoints = "points";
constexpr const char* kSpeed = "speed";
constexpr const char* kLoop = "loop";
const mjfAttribute kWaypointAttributes[] = {
    rows::kAMin,
    rows::kAMax,
    {kPoints, "20 0 0 20 -20 0 0 -20", "m: waypoints 'x0 y0 x1 y1 ...' (at least two)"},
    {kSpeed, "2", "m/s: cruise speed (segment time = length / speed)"},
    {kLoop, "true", "'true': back to the first point and around again; 'false': stop at the last"},
    rows::kAltitude,
    rows::kYaw,
    rows::kKp,
    rows::kKd,
};

void* WaypointCreate(const mjfCreateContext* ctx) {
  return mjf::plugin::CreateOrExplain(ctx, [ctx]() -> void* {
    const mjf::plugin::Attributes attributes(ctx);
    WaypointGuidance::Config config;
    config.bounds = ReadBounds(attributes);
    const auto points = attributes.Numbers(kPoints);
    if (points.size() < 4 || points.size() % 2 != 0) {
      throw ConfigError(
          "attribute 'points': expected pairs 'x0 y0 x1 y1 ...', at least two "
          "waypoints (got " +
          std::to_string(points.size()) + " numbers)");
    }
    for (size_t k = 0; k < points.size(); k += 2)
      config.points.push_back({points[k], points[k + 1]});
    config.speed = attributes.Number(kSpeed);
    config.loop = attributes.Choice(kLoop, {"true", "false"}) == "true";
    config.altitude = attributes.Number(kAltitude);
    config.yaw = attributes.Number(kYaw);
    config.gains = ReadGains(attributes);
    return new LeaderInstance<WaypointGuidance>{CheckVehicle(ctx), WaypointGuidance(config)};
  });
}

}  // namespace

const mjfPlugin kWaypoints = LeaderPlugin<WaypointGuidance>(
    "waypoints",
    "leader on a smooth (C1 cubic) path through waypoints whose acceleration stays in [a_min, "
    "a_max]",
    kWaypointAttributes, WaypointCreate);

}  // namespace mjf::guidance::adapter
