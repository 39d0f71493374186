// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Plugin family libmjf_guidance.so: thin adapters from the plugin ABI to CircleGuidance and
// HoverGuidance. Each writes setpoints[its vehicle] (acc, pos, vel, yaw), never sliding.
#include <mjformation/plugin.h>

#include <cmath>
#include <mjformation/plugin_util.hpp>
#include <string>

#include "mjformation/guidance/guidance.hpp"
#include "mjformation/guidance/leaders.hpp"

namespace {

using mjf::guidance::CircleGuidance;
using mjf::guidance::GuidanceOutput;
using mjf::guidance::HoverGuidance;
using mjf::guidance::Vec3;
using mjf::plugin::Attributes;
using mjf::plugin::ConfigError;
using mjf::plugin::Require;

constexpr const char* kRadius = "radius";
constexpr const char* kOmega = "omega";
constexpr const char* kCenter = "center";
constexpr const char* kPhase = "phase";
constexpr const char* kAltitude = "altitude";
constexpr const char* kPosition = "position";
constexpr const char* kYaw = "yaw";
constexpr const char* kKp = "kp";
constexpr const char* kKd = "kd";

int CheckVehicle(const mjfCreateContext* ctx) {
  if (ctx->vehicle < 0 || ctx->vehicle >= ctx->n_vehicles) {
    throw ConfigError("no valid vehicle index: this is a per-vehicle plugin");
  }
  return ctx->vehicle;
}

mjf::guidance::TrackingGains ReadGains(const Attributes& attributes) {
  mjf::guidance::TrackingGains gains;
  gains.kp = attributes.Number(kKp);
  Require(gains.kp >= 0, kKp, ">= 0", gains.kp);
  gains.kd = attributes.Number(kKd);
  Require(gains.kd >= 0, kKd, ">= 0", gains.kd);
  return gains;
}

void Write(const GuidanceOutput& out, mjfSetpoint* sp) {
  for (int i = 0; i < 3; ++i) {
    sp->acc[i] = out.acc[i];
    sp->pos[i] = out.pos[i];
    sp->vel[i] = out.vel[i];
  }
  sp->yaw = out.yaw;
}

Vec3 Get(const double* v) { return {v[0], v[1], v[2]}; }

// ---------------------------------------------------------------------------------------------
// circle

const mjfAttribute kCircleAttributes[] = {
    {kRadius, "20", "m: circle radius (paper: 20)"},
    {kOmega, "0.157", "rad/s: angular rate, > 0 counter-clockwise (paper: 0.157)"},
    {kCenter, "0 0", "m: circle centre x y"},
    {kPhase, "0", "rad: angle at t = 0 (0: start at centre + (radius, 0))"},
    {kAltitude, "5", "m: altitude setpoint"},
    {kYaw, "0", "rad: yaw setpoint"},
    {kKp, "1", "1/s^2: position error gain"},
    {kKd, "2", "1/s: velocity error gain"},
};

struct CircleInstance {
  int vehicle;
  CircleGuidance guidance;
};

void* CircleCreate(const mjfCreateContext* ctx) {
  return mjf::plugin::CreateOrExplain(ctx, [ctx]() -> void* {
    const Attributes attributes(ctx);
    CircleGuidance::Config config;
    config.radius = attributes.Number(kRadius);
    Require(config.radius >= 0, kRadius, ">= 0", config.radius);
    config.omega = attributes.Number(kOmega);
    const auto center = attributes.Numbers(kCenter, 2);
    config.center = {center[0], center[1]};
    config.phase = attributes.Number(kPhase);
    config.altitude = attributes.Number(kAltitude);
    config.yaw = attributes.Number(kYaw);
    config.gains = ReadGains(attributes);
    return new CircleInstance{CheckVehicle(ctx), CircleGuidance(config)};
  });
}

int CircleCompute(void* instance, const mjfStepContext* ctx) {
  auto* self = static_cast<CircleInstance*>(instance);
  if (self->vehicle >= ctx->n_vehicles) {
    return mjf::plugin::Fail(ctx, "called for a vehicle the step does not have");
  }
  const mjfVehicleState& s = ctx->states[self->vehicle];
  Write(self->guidance.Update(ctx->time, Get(s.pos), Get(s.vel)), &ctx->setpoints[self->vehicle]);
  return 0;
}

void CircleDestroy(void* instance) { delete static_cast<CircleInstance*>(instance); }

const mjfPlugin kCircle = {
    MJF_ABI_VERSION,
    "circle",
    MJF_KIND_GUIDANCE,
    "leader circle: a = a_ref + kp (p_ref - p) + kd (v_ref - v), constant altitude and yaw",
    static_cast<int>(sizeof(kCircleAttributes) / sizeof(kCircleAttributes[0])),
    kCircleAttributes,
    0,
    nullptr,
    CircleCreate,
    CircleCompute,
    nullptr,
    CircleDestroy,
    nullptr};

// ---------------------------------------------------------------------------------------------
// hover

const mjfAttribute kHoverAttributes[] = {
    {kPosition, "", "m: point to hold 'x y z' (empty: the vehicle's initial position)"},
    {kAltitude, "", "m: overrides the held z when given"},
    {kYaw, "0", "rad: yaw setpoint"},
    {kKp, "1", "1/s^2: position error gain"},
    {kKd, "2", "1/s: velocity gain"},
};

struct HoverInstance {
  int vehicle;
  HoverGuidance guidance;
};

bool Blank(const std::string& s) { return s.find_first_not_of(" \t") == std::string::npos; }

void* HoverCreate(const mjfCreateContext* ctx) {
  return mjf::plugin::CreateOrExplain(ctx, [ctx]() -> void* {
    const Attributes attributes(ctx);
    HoverGuidance::Config config;
    if (!Blank(attributes.String(kPosition))) {
      const auto p = attributes.Numbers(kPosition, 3);
      config.position = {p[0], p[1], p[2]};
    } else if (ctx->initial_pos) {
      config.position = Get(ctx->initial_pos);
    } else {
      throw ConfigError(std::string("attribute '") + kPosition +
                        "' is needed: the host gave no initial position");
    }
    if (!Blank(attributes.String(kAltitude))) config.position[2] = attributes.Number(kAltitude);
    config.yaw = attributes.Number(kYaw);
    config.gains = ReadGains(attributes);
    return new HoverInstance{CheckVehicle(ctx), HoverGuidance(config)};
  });
}

int HoverCompute(void* instance, const mjfStepContext* ctx) {
  auto* self = static_cast<HoverInstance*>(instance);
  if (self->vehicle >= ctx->n_vehicles) {
    return mjf::plugin::Fail(ctx, "called for a vehicle the step does not have");
  }
  const mjfVehicleState& s = ctx->states[self->vehicle];
  Write(self->guidance.Update(Get(s.pos), Get(s.vel)), &ctx->setpoints[self->vehicle]);
  return 0;
}

void HoverDestroy(void* instance) { delete static_cast<HoverInstance*>(instance); }

const mjfPlugin kHover = {
    MJF_ABI_VERSION,
    "hover",
    MJF_KIND_GUIDANCE,
    "holds a point (default: the initial position): a = kp (p_ref - p) - kd v",
    static_cast<int>(sizeof(kHoverAttributes) / sizeof(kHoverAttributes[0])),
    kHoverAttributes,
    0,
    nullptr,
    HoverCreate,
    HoverCompute,
    nullptr,
    HoverDestroy,
    nullptr};

// ---------------------------------------------------------------------------------------------
// Maneuvering leaders (leaders.hpp): every command per axis inside [a_min, a_max].

constexpr const char* kAMin = "a_min";
constexpr const char* kAMax = "a_max";
constexpr const char* kSeed = "seed";
constexpr const char* kSpeedMax = "speed_max";
constexpr const char* kArea = "area";
constexpr const char* kRamp = "ramp";

mjf::guidance::AccelBounds ReadBounds(const Attributes& attributes) {
  mjf::guidance::AccelBounds bounds{attributes.Number(kAMin), attributes.Number(kAMax)};
  bounds.Validate();
  return bounds;
}

uint64_t ReadSeed(const Attributes& attributes) {
  const double seed = attributes.Number(kSeed);
  Require(seed >= 0 && seed == std::floor(seed) && seed < 9007199254740992.0, kSeed,
          "an integer >= 0", seed);
  return static_cast<uint64_t>(seed);
}

mjf::guidance::Envelope::Config ReadEnvelope(const Attributes& attributes) {
  mjf::guidance::Envelope::Config envelope;
  envelope.speed_max = attributes.Number(kSpeedMax);
  const auto area = attributes.Numbers(kArea, 4);
  envelope.area_min = {area[0], area[1]};
  envelope.area_max = {area[2], area[3]};
  if (!(area[2] > area[0] && area[3] > area[1])) {
    throw ConfigError(
        "attribute 'area': expected 'x_min y_min x_max y_max' with x_min < x_max "
        "and y_min < y_max");
  }
  envelope.ramp = attributes.Number(kRamp);
  return envelope;
}

template <typename Law>
struct LeaderInstance {
  int vehicle;
  Law law;
};

template <typename Law>
int LeaderCompute(void* instance, const mjfStepContext* ctx) {
  return mjf::plugin::ComputeOrExplain(ctx, [&]() {
    auto* self = static_cast<LeaderInstance<Law>*>(instance);
    if (self->vehicle >= ctx->n_vehicles) {
      return mjf::plugin::Fail(ctx, "vehicle index outside the scene");
    }
    const mjfVehicleState& s = ctx->states[self->vehicle];
    Write(self->law.Update(ctx->time, Get(s.pos), Get(s.vel)), &ctx->setpoints[self->vehicle]);
    return 0;
  });
}

template <typename Law>
void LeaderDestroy(void* instance) {
  delete static_cast<LeaderInstance<Law>*>(instance);
}

// The descriptor of a leader guidance plugin whose instance is LeaderInstance<Guidance>.
template <typename Guidance, size_t kAttributes>
constexpr mjfPlugin LeaderPlugin(const char* name, const char* doc,
                                 const mjfAttribute (&attributes)[kAttributes],
                                 void* (*create)(const mjfCreateContext*)) {
  return {MJF_ABI_VERSION,
          name,
          MJF_KIND_GUIDANCE,
          doc,
          static_cast<int>(kAttributes),
          attributes,
          0,
          nullptr,
          create,
          LeaderCompute<Guidance>,
          nullptr,
          LeaderDestroy<Guidance>,
          nullptr};
}

// random_accel

constexpr const char* kCorrelationTime = "correlation_time";
const mjfAttribute kRandomAccelAttributes[] = {
    {kAMin, "-1", "m/s^2: lower bound of the commanded acceleration per axis (u_min)"},
    {kAMax, "1", "m/s^2: upper bound of the commanded acceleration per axis (u_max)"},
    {kCorrelationTime, "2", "s: spacing of the random knots (band limit ~ 1 / (2 x it) Hz)"},
    {kSpeedMax, "3", "m/s: speed limit per axis"},
    {kArea, "-40 -40 40 40", "m: box 'x_min y_min x_max y_max' the leader stays inside"},
    {kRamp, "0.3", "m/s: speed band over which the envelope turns the acceleration around"},
    {kSeed, "1", "integer >= 0: random seed (same seed, same path)"},
    {kAltitude, "5", "m: altitude setpoint"},
    {kYaw, "0", "rad: yaw setpoint"},
};

void* RandomAccelCreate(const mjfCreateContext* ctx) {
  return mjf::plugin::CreateOrExplain(ctx, [ctx]() -> void* {
    const Attributes attributes(ctx);
    mjf::guidance::RandomAccelGuidance::Config config;
    config.bounds = ReadBounds(attributes);
    config.correlation_time = attributes.Number(kCorrelationTime);
    config.envelope = ReadEnvelope(attributes);
    config.seed = ReadSeed(attributes);
    config.altitude = attributes.Number(kAltitude);
    config.yaw = attributes.Number(kYaw);
    return new LeaderInstance<mjf::guidance::RandomAccelGuidance>{
        CheckVehicle(ctx), mjf::guidance::RandomAccelGuidance(config)};
  });
}

const mjfPlugin kRandomAccel = LeaderPlugin<mjf::guidance::RandomAccelGuidance>(
    "random_accel",
    "maneuvering leader: smooth seeded random acceleration per axis in [a_min, a_max], speed "
    "limit and area kept",
    kRandomAccelAttributes, RandomAccelCreate);

// bang_bang

constexpr const char* kDwell = "dwell";
const mjfAttribute kBangBangAttributes[] = {
    {kAMin, "-1", "m/s^2: lower bound of the commanded acceleration per axis (u_min)"},
    {kAMax, "1", "m/s^2: upper bound of the commanded acceleration per axis (u_max)"},
    {kDwell, "0.5 3", "s: 'min max' of the uniform random time between switches (min > 0)"},
    {kSpeedMax, "3", "m/s: speed limit per axis"},
    {kArea, "-40 -40 40 40", "m: box 'x_min y_min x_max y_max' the leader stays inside"},
    {kRamp, "0.3", "m/s: speed band over which the envelope turns the acceleration around"},
    {kSeed, "1", "integer >= 0: random seed (same seed, same path)"},
    {kAltitude, "5", "m: altitude setpoint"},
    {kYaw, "0", "rad: yaw setpoint"},
};

void* BangBangCreate(const mjfCreateContext* ctx) {
  return mjf::plugin::CreateOrExplain(ctx, [ctx]() -> void* {
    const Attributes attributes(ctx);
    mjf::guidance::BangBangGuidance::Config config;
    config.bounds = ReadBounds(attributes);
    const auto dwell = attributes.Numbers(kDwell, 2);
    config.dwell_min = dwell[0];
    config.dwell_max = dwell[1];
    config.envelope = ReadEnvelope(attributes);
    config.seed = ReadSeed(attributes);
    config.altitude = attributes.Number(kAltitude);
    config.yaw = attributes.Number(kYaw);
    return new LeaderInstance<mjf::guidance::BangBangGuidance>{
        CheckVehicle(ctx), mjf::guidance::BangBangGuidance(config)};
  });
}

void BangBangReset(void* instance) {
  static_cast<LeaderInstance<mjf::guidance::BangBangGuidance>*>(instance)->law.Reset();
}

const mjfPlugin kBangBang = {
    MJF_ABI_VERSION,
    "bang_bang",
    MJF_KIND_GUIDANCE,
    "maneuvering leader: acceleration a_min or a_max per axis, switching after seeded random "
    "dwell times; speed limit and area kept",
    static_cast<int>(sizeof(kBangBangAttributes) / sizeof(kBangBangAttributes[0])),
    kBangBangAttributes,
    0,
    nullptr,
    BangBangCreate,
    LeaderCompute<mjf::guidance::BangBangGuidance>,
    BangBangReset,
    LeaderDestroy<mjf::guidance::BangBangGuidance>,
    nullptr};

// lemniscate

constexpr const char* kHalfWidth = "half_width";
const mjfAttribute kLemniscateAttributes[] = {
    {kAMin, "-1", "m/s^2: lower bound of the commanded acceleration per axis (u_min)"},
    {kAMax, "1", "m/s^2: upper bound of the commanded acceleration per axis (u_max)"},
    {kHalfWidth, "20", "m: A, x = cx + A sin(w t + phase), y = cy + A/2 sin(2 (w t + phase))"},
    {kOmega, "0.15", "rad/s: w (peak accelerations A w^2 on x, 2 A w^2 on y)"},
    {kCenter, "0 0", "m: centre x y"},
    {kPhase, "0", "rad"},
    {kAltitude, "5", "m: altitude setpoint"},
    {kYaw, "0", "rad: yaw setpoint"},
    {kKp, "1", "1/s^2: position error gain"},
    {kKd, "2", "1/s: velocity error gain"},
};

void* LemniscateCreate(const mjfCreateContext* ctx) {
  return mjf::plugin::CreateOrExplain(ctx, [ctx]() -> void* {
    const Attributes attributes(ctx);
    mjf::guidance::LemniscateGuidance::Config config;
    config.bounds = ReadBounds(attributes);
    config.half_width = attributes.Number(kHalfWidth);
    config.omega = attributes.Number(kOmega);
    const auto center = attributes.Numbers(kCenter, 2);
    config.center = {center[0], center[1]};
    config.phase = attributes.Number(kPhase);
    config.altitude = attributes.Number(kAltitude);
    config.yaw = attributes.Number(kYaw);
    config.gains = ReadGains(attributes);
    return new LeaderInstance<mjf::guidance::LemniscateGuidance>{
        CheckVehicle(ctx), mjf::guidance::LemniscateGuidance(config)};
  });
}

const mjfPlugin kLemniscate = LeaderPlugin<mjf::guidance::LemniscateGuidance>(
    "lemniscate", "leader figure-eight (Gerono), tracked by PD, command clamped to [a_min, a_max]",
    kLemniscateAttributes, LemniscateCreate);

// waypoints

constexpr const char* kPoints = "points";
constexpr const char* kSpeed = "speed";
constexpr const char* kLoop = "loop";
const mjfAttribute kWaypointAttributes[] = {
    {kAMin, "-1", "m/s^2: lower bound of the commanded acceleration per axis (u_min)"},
    {kAMax, "1", "m/s^2: upper bound of the commanded acceleration per axis (u_max)"},
    {kPoints, "20 0 0 20 -20 0 0 -20", "m: waypoints 'x0 y0 x1 y1 ...' (at least two)"},
    {kSpeed, "2", "m/s: cruise speed (segment time = length / speed)"},
    {kLoop, "true", "'true': back to the first point and around again; 'false': stop at the last"},
    {kAltitude, "5", "m: altitude setpoint"},
    {kYaw, "0", "rad: yaw setpoint"},
    {kKp, "1", "1/s^2: position error gain"},
    {kKd, "2", "1/s: velocity error gain"},
};

void* WaypointCreate(const mjfCreateContext* ctx) {
  return mjf::plugin::CreateOrExplain(ctx, [ctx]() -> void* {
    const Attributes attributes(ctx);
    mjf::guidance::WaypointGuidance::Config config;
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
    return new LeaderInstance<mjf::guidance::WaypointGuidance>{
        CheckVehicle(ctx), mjf::guidance::WaypointGuidance(config)};
  });
}

const mjfPlugin kWaypoints = LeaderPlugin<mjf::guidance::WaypointGuidance>(
    "waypoints",
    "leader on a smooth (C1 cubic) path through waypoints whose acceleration stays in [a_min, "
    "a_max]",
    kWaypointAttributes, WaypointCreate);

// trajectory

constexpr const char* kFile = "file";
constexpr const char* kTimeOffset = "time_offset";
const mjfAttribute kTrajectoryAttributes[] = {
    {kAMin, "-1", "m/s^2: lower bound of the commanded acceleration per axis (u_min)"},
    {kAMax, "1", "m/s^2: upper bound of the commanded acceleration per axis (u_max)"},
    {kFile, "",
     "CSV of rows t,x,y[,z] (optional header; a relative path is relative to the experiment file)"},
    {kTimeOffset, "0", "s: the file's time at simulation time 0"},
    {kAltitude, "5", "m: altitude setpoint when the file has no z"},
    {kYaw, "0", "rad: yaw setpoint"},
    {kKp, "1", "1/s^2: position error gain"},
    {kKd, "2", "1/s: velocity error gain"},
};

void* TrajectoryCreate(const mjfCreateContext* ctx) {
  return mjf::plugin::CreateOrExplain(ctx, [ctx]() -> void* {
    const Attributes attributes(ctx);
    mjf::guidance::TrajectoryGuidance::Config config;
    config.bounds = ReadBounds(attributes);
    const std::string file = attributes.String(kFile);
    if (Blank(file)) throw ConfigError("attribute 'file' is required: a CSV of t,x,y[,z] rows");
    const auto table = mjf::guidance::ReadTrajectoryCsv(file);
    config.time_offset = attributes.Number(kTimeOffset);
    config.altitude = attributes.Number(kAltitude);
    config.yaw = attributes.Number(kYaw);
    config.gains = ReadGains(attributes);
    return new LeaderInstance<mjf::guidance::TrajectoryGuidance>{
        CheckVehicle(ctx), mjf::guidance::TrajectoryGuidance(config, table)};
  });
}

const mjfPlugin kTrajectory = LeaderPlugin<mjf::guidance::TrajectoryGuidance>(
    "trajectory",
    "leader on a recorded path (CSV t,x,y[,z]) interpolated by a C1 spline, command clamped "
    "to [a_min, a_max]",
    kTrajectoryAttributes, TrajectoryCreate);

}  // namespace

MJF_EXPORT_PLUGINS(&kCircle, &kHover, &kRandomAccel, &kBangBang, &kLemniscate, &kWaypoints,
                   &kTrajectory)
