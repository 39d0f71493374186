// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// What the guidance adapters share: the attribute keys, the attribute rows several laws list
// alike, the readers of the shared attributes (gains, bounds, seed, envelope) and the one
// instance, compute and destroy every law with Update(t, pos, vel) uses. Each adapter writes
// setpoints[its vehicle] (acc, pos, vel, yaw), never sliding.
#ifndef MJFORMATION_GUIDANCE_PLUGIN_ADAPTER_HPP_
#define MJFORMATION_GUIDANCE_PLUGIN_ADAPTER_HPP_

#include <mjformation/plugin.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <mjformation/plugin_contract.hpp>
#include <mjformation/plugin_util.hpp>
#include <string>

#include "mjformation/guidance/bounds.hpp"
#include "mjformation/guidance/envelope.hpp"
#include "mjformation/guidance/types.hpp"

namespace mjf::guidance::adapter {

// Attribute keys.
constexpr const char* kRadius = "radius";
constexpr const char* kOmega = "omega";
constexpr const char* kCenter = "center";
constexpr const char* kPhase = "phase";
constexpr const char* kAltitude = "altitude";
constexpr const char* kPosition = "position";
constexpr const char* kYaw = "yaw";
constexpr const char* kKp = "kp";
constexpr const char* kKd = "kd";
constexpr const char* kAMin = plugin::contract::kAMin;  // the runner reads both
constexpr const char* kAMax = plugin::contract::kAMax;
constexpr const char* kSeed = "seed";
constexpr const char* kSpeedMax = "speed_max";
constexpr const char* kArea = "area";
constexpr const char* kRamp = "ramp";

// Attribute rows (key, default, doc) that several laws list alike.
namespace rows {
constexpr mjfAttribute kAltitude = {adapter::kAltitude, "5", "m: altitude setpoint"};
constexpr mjfAttribute kYaw = {adapter::kYaw, "0", "rad: yaw setpoint"};
constexpr mjfAttribute kKp = {adapter::kKp, "1", "1/s^2: position error gain"};
constexpr mjfAttribute kKd = {adapter::kKd, "2", "1/s: velocity error gain"};
constexpr mjfAttribute kAMin = {
    adapter::kAMin, "-1", "m/s^2: lower bound of the commanded acceleration per axis (u_min)"};
constexpr mjfAttribute kAMax = {
    adapter::kAMax, "1", "m/s^2: upper bound of the commanded acceleration per axis (u_max)"};
constexpr mjfAttribute kSpeedMax = {adapter::kSpeedMax, "3", "m/s: speed limit per axis"};
constexpr mjfAttribute kArea = {adapter::kArea, "-40 -40 40 40",
                                "m: box 'x_min y_min x_max y_max' the leader stays inside"};
constexpr mjfAttribute kRamp = {
    adapter::kRamp, "0.3", "m/s: speed band over which the envelope turns the acceleration around"};
constexpr mjfAttribute kSeed = {adapter::kSeed, "1",
                                "integer >= 0: random seed (same seed, same path)"};
}  // namespace rows

// The vehicle this per-vehicle plugin drives; ConfigError when the host gave none.
int CheckVehicle(const mjfCreateContext* ctx);
bool Blank(const std::string& s);
Vec3 Get(const double* v);
void Write(const GuidanceOutput& out, mjfSetpoint* sp);

// Readers of the attributes several laws share; each refuses a bad value naming the key.
TrackingGains ReadGains(const mjf::plugin::Attributes& attributes);        // kp, kd
AccelBounds ReadBounds(const mjf::plugin::Attributes& attributes);         // a_min, a_max
uint64_t ReadSeed(const mjf::plugin::Attributes& attributes);              // seed
Envelope::Config ReadEnvelope(const mjf::plugin::Attributes& attributes);  // speed_max, area, ramp

// The attribute table of a maneuvering leader (bang_bang, random_accel): its acceleration bounds,
// the one row of its own (what times its random signal), the envelope, the seed and the setpoints.
constexpr std::array<mjfAttribute, 9> ManeuveringAttributes(mjfAttribute own) {
  return {rows::kAMin, rows::kAMax,     own,       rows::kSpeedMax, rows::kArea, rows::kRamp,
          rows::kSeed, rows::kAltitude, rows::kYaw};
}

// Reads the attributes every maneuvering leader's Config shares (bounds, envelope, seed,
// altitude, yaw); the law's own row is read by its adapter.
template <typename Config>
void ReadManeuvering(const mjf::plugin::Attributes& attributes, Config* config) {
  config->bounds = ReadBounds(attributes);
  config->envelope = ReadEnvelope(attributes);
  config->seed = ReadSeed(attributes);
  config->altitude = attributes.Number(kAltitude);
  config->yaw = attributes.Number(kYaw);
}

// The instance of a law with Update(t, pos, vel) for one vehicle.
template <typename Law>
struct LeaderInstance {
  int vehicle;
  Law law;
  template <typename Visit>
  void VisitState(Visit& visit) {
    law.VisitState(visit);
  }
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

// The descriptor of a leader guidance plugin whose instance is LeaderInstance<Guidance>
// (reset: null for a stateless law); attributes: an array of static storage (a C array, or
// ManeuveringAttributes' std::array).
template <typename Guidance, typename AttributeArray>
constexpr mjfPlugin LeaderPlugin(const char* name, const char* doc,
                                 const AttributeArray& attributes,
                                 void* (*create)(const mjfCreateContext*),
                                 void (*reset)(void*) = nullptr) {
  static_assert(mjf::plugin::kHasVisitState<Guidance>,
                "a guidance law lists its state: template <typename Visit> void VisitState(Visit&) "
                "(mjformation/plugin_state.hpp)");
  return {MJF_ABI_VERSION,
          name,
          MJF_KIND_GUIDANCE,
          doc,
          static_cast<int>(std::size(attributes)),
          std::data(attributes),
          0,
          nullptr,
          create,
          LeaderCompute<Guidance>,
          reset,
          LeaderDestroy<Guidance>,
          nullptr,
          &mjf::plugin::StateSizeOf<LeaderInstance<Guidance>>,
          &mjf::plugin::GetStateOf<LeaderInstance<Guidance>>,
          &mjf::plugin::SetStateOf<LeaderInstance<Guidance>>};
}

// The descriptors, one per file (register.cc lists them).
extern const mjfPlugin kCircle;       // circle.cc
extern const mjfPlugin kHover;        // hover.cc
extern const mjfPlugin kRandomAccel;  // random_accel.cc
extern const mjfPlugin kBangBang;     // bang_bang.cc
extern const mjfPlugin kLemniscate;   // lemniscate.cc
extern const mjfPlugin kWaypoints;    // waypoints.cc
extern const mjfPlugin kTrajectory;   // trajectory.cc

}  // namespace mjf::guidance::adapter

#endif  // MJFORMATION_GUIDANCE_PLUGIN_ADAPTER_HPP_
