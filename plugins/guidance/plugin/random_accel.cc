// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// random_accel: the adapter of RandomAccelGuidance.
#include "mjformation/guidance/random_accel.hpp"

#include "adapter.hpp"

namespace mjf::guidance::adapter {
namespace {

constexpr const char* kCorrelationTime = "correlation_time";
constexpr auto kRandomAccelAttributes = ManeuveringAttributes(
    {kCorrelationTime, "2", "s: spacing of the random knots (band limit ~ 1 / (2 x it) Hz)"});

void* RandomAccelCreate(const mjfCreateContext* ctx) {
  return mjf::plugin::CreateOrExplain(ctx, [ctx]() -> void* {
    const mjf::plugin::Attributes attributes(ctx);
    RandomAccelGuidance::Config config;
    ReadManeuvering(attributes, &config);
    config.correlation_time = attributes.Number(kCorrelationTime);
    return new LeaderInstance<RandomAccelGuidance>{CheckVehicle(ctx), RandomAccelGuidance(config)};
  });
}

}  // namespace

const mjfPlugin kRandomAccel = LeaderPlugin<RandomAccelGuidance>(
    "random_accel",
    "maneuvering leader: smooth seeded random acceleration per axis in [a_min, a_max], speed "
    "limit and area kept",
    kRandomAccelAttributes, RandomAccelCreate);

}  // namespace mjf::guidance::adapter
