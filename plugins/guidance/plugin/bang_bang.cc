// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// bang_bang: the adapter of BangBangGuidance (stateful: the host's reset restarts its dwells).
#include "mjformation/guidance/bang_bang.hpp"

#include "adapter.hpp"

namespace mjf::guidance::adapter {
namespace {

constexpr const char* kDwell = "dwell";
constexpr auto kBangBangAttributes = ManeuveringAttributes(
    {kDwell, "0.5 3", "s: 'min max' of the uniform random time between switches (min > 0)"});

void* BangBangCreate(const mjfCreateContext* ctx) {
  return mjf::plugin::CreateOrExplain(ctx, [ctx]() -> void* {
    const mjf::plugin::Attributes attributes(ctx);
    BangBangGuidance::Config config;
    ReadManeuvering(attributes, &config);
    const auto dwell = attributes.Numbers(kDwell, 2);
    config.dwell_min = dwell[0];
    config.dwell_max = dwell[1];
    return new LeaderInstance<BangBangGuidance>{CheckVehicle(ctx), BangBangGuidance(config)};
  });
}

void BangBangReset(void* instance) {
  static_cast<LeaderInstance<BangBangGuidance>*>(instance)->law.Reset();
}

}  // namespace

const mjfPlugin kBangBang = LeaderPlugin<BangBangGuidance>(
    "bang_bang",
    "maneuvering leader: acceleration a_min or a_max per axis, switching after seeded random "
    "dwell times; speed limit and area kept",
    kBangBangAttributes, BangBangCreate, BangBangReset);

}  // namespace mjf::guidance::adapter
