// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Plugin family libmjf_guidance.so: thin adapters from the plugin ABI to CircleGuidance and
// HoverGuidance. Each writes setpoints[its vehicle] (acc, pos, vel, yaw), never sliding.
#include <mjformation/plugin.h>

#include <cmath>
#include <mjformation/plugin_util.hpp>
#include <string>

#include "mjformation/guidance/guidance.hpp"

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

}  // namespace

MJF_EXPORT_PLUGINS(&kCircle, &kHover)
