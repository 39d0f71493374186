// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "adapter.hpp"

#include <cmath>
#include <string>

namespace mjf::attitude::adapter {

using mjf::plugin::ConfigError;

const char* const kRotorNames[Mixer::kRotors] = {"rotor0", "rotor1", "rotor2", "rotor3"};

VehicleState ToState(const mjfVehicleState& s) {
  VehicleState out;
  for (int i = 0; i < 3; ++i) {
    out.pos[i] = s.pos[i];
    out.vel[i] = s.vel[i];
    out.gyro[i] = s.gyro[i];
  }
  for (int i = 0; i < 4; ++i) out.quat[i] = s.quat[i];
  return out;
}

bool ToSetpoint(const mjfSetpoint& s, Setpoint* out) {
  for (int i = 0; i < 3; ++i) {
    out->acc[i] = s.acc[i];
    out->pos[i] = s.pos[i];
    out->vel[i] = s.vel[i];
  }
  out->yaw = s.yaw;
  return std::isfinite(s.acc[0]) && std::isfinite(s.acc[1]) && std::isfinite(s.acc[2]) &&
         std::isfinite(s.pos[2]) && std::isfinite(s.vel[2]) && std::isfinite(s.yaw);
}

const mjfVehicleInfo& RequireVehicle(const mjfCreateContext* ctx, int n_actuators) {
  if (!ctx->vehicle_info) throw ConfigError("no vehicle info: this is a per-vehicle plugin");
  if (ctx->vehicle < 0) throw ConfigError("no vehicle index: this is a per-vehicle plugin");
  if (ctx->vehicle_info->n_actuators != n_actuators || !ctx->vehicle_info->actuators) {
    throw ConfigError("expected " + std::to_string(n_actuators) + " actuators, got " +
                      std::to_string(ctx->vehicle_info->n_actuators));
  }
  return *ctx->vehicle_info;
}

std::array<RotorGeometry, Mixer::kRotors> ToRotors(const mjfVehicleInfo& info) {
  std::array<RotorGeometry, Mixer::kRotors> rotors;
  for (int k = 0; k < Mixer::kRotors; ++k) {
    const mjfActuatorInfo& a = info.actuators[k];
    for (int i = 0; i < 3; ++i) rotors[k].pos[i] = a.site_pos[i];
    for (int i = 0; i < 6; ++i) rotors[k].gear[i] = a.gear[i];
    rotors[k].ctrl_min = a.ctrl_min;
    rotors[k].ctrl_max = a.ctrl_max;
  }
  return rotors;
}

double ReadTiltMax(const mjf::plugin::Attributes& attributes) {
  const double tilt_max = attributes.Number(kTiltMax);
  mjf::plugin::Require(tilt_max >= 0 && tilt_max < M_PI / 2, kTiltMax,
                       "0 <= tilt_max < pi/2 (0: derived)", tilt_max);
  return tilt_max;
}

}  // namespace mjf::attitude::adapter
