// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// trajectory: the adapter of TrajectoryGuidance (the CSV is read once, at creation).
#include "mjformation/guidance/trajectory.hpp"

#include <string>

#include "adapter.hpp"

namespace mjf::guidance::adapter {
namespace {

using mjf::plugin::ConfigError;

constexpr const char* kFile = "file";
constexpr const char* kTimeOffset = "time_offset";
const mjfAttribute kTrajectoryAttributes[] = {
    rows::kAMin,
    rows::kAMax,
    {kFile, "",
     "CSV of rows t,x,y[,z] (optional header; a relative path is relative to the experiment file)"},
    {kTimeOffset, "0", "s: the file's time at simulation time 0"},
    {kAltitude, "5", "m: altitude setpoint when the file has no z"},
    rows::kYaw,
    rows::kKp,
    rows::kKd,
};

void* TrajectoryCreate(const mjfCreateContext* ctx) {
  return mjf::plugin::CreateOrExplain(ctx, [ctx]() -> void* {
    const mjf::plugin::Attributes attributes(ctx);
    TrajectoryGuidance::Config config;
    config.bounds = ReadBounds(attributes);
    const std::string file = attributes.String(kFile);
    if (Blank(file)) throw ConfigError("attribute 'file' is required: a CSV of t,x,y[,z] rows");
    const auto table = ReadTrajectoryCsv(file);
    config.time_offset = attributes.Number(kTimeOffset);
    config.altitude = attributes.Number(kAltitude);
    config.yaw = attributes.Number(kYaw);
    config.gains = ReadGains(attributes);
    return new LeaderInstance<TrajectoryGuidance>{CheckVehicle(ctx),
                                                  TrajectoryGuidance(config, table)};
  });
}

}  // namespace

const mjfPlugin kTrajectory = LeaderPlugin<TrajectoryGuidance>(
    "trajectory",
    "leader on a recorded path (CSV t,x,y[,z]) interpolated by a C1 spline, command clamped "
    "to [a_min, a_max]",
    kTrajectoryAttributes, TrajectoryCreate);

}  // namespace mjf::guidance::adapter
