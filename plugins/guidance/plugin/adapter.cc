// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "adapter.hpp"

#include <cmath>

namespace mjf::guidance::adapter {

using mjf::plugin::Attributes;
using mjf::plugin::ConfigError;
using mjf::plugin::Require;

int CheckVehicle(const mjfCreateContext* ctx) {
  if (ctx->vehicle < 0 || ctx->vehicle >= ctx->n_vehicles) {
    throw ConfigError("no valid vehicle index: this is a per-vehicle plugin");
  }
  return ctx->vehicle;
}

bool Blank(const std::string& s) { return s.find_first_not_of(" \t") == std::string::npos; }

Vec3 Get(const double* v) { return {v[0], v[1], v[2]}; }

void Write(const GuidanceOutput& out, mjfSetpoint* sp) {
  for (int i = 0; i < 3; ++i) {
    sp->acc[i] = out.acc[i];
    sp->pos[i] = out.pos[i];
    sp->vel[i] = out.vel[i];
  }
  sp->yaw = out.yaw;
}

TrackingGains ReadGains(const Attributes& attributes) {
  TrackingGains gains;
  gains.kp = attributes.Number(kKp);
  Require(gains.kp >= 0, kKp, ">= 0", gains.kp);
  gains.kd = attributes.Number(kKd);
  Require(gains.kd >= 0, kKd, ">= 0", gains.kd);
  return gains;
}

AccelBounds ReadBounds(const Attributes& attributes) {
  AccelBounds bounds{attributes.Number(kAMin), attributes.Number(kAMax)};
  bounds.Validate();
  return bounds;
}

uint64_t ReadSeed(const Attributes& attributes) {
  const double seed = attributes.Number(kSeed);
  Require(seed >= 0 && seed == std::floor(seed) && seed < 9007199254740992.0, kSeed,
          "an integer >= 0", seed);
  return static_cast<uint64_t>(seed);
}

Envelope::Config ReadEnvelope(const Attributes& attributes) {
  Envelope::Config envelope;
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

}  // namespace mjf::guidance::adapter
