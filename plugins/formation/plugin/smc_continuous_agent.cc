// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// smc_continuous_agent: eq. (30) per follower (formation::ContinuousSmcAgent), every physics
// step, with smc_continuous's attributes.
#include <mjformation/formation/agent_laws.hpp>

#include "adapter.hpp"
#include "agent_adapter.hpp"

namespace mjf::formation::adapter {
namespace {

void* Create(const mjfCreateContext* ctx) {
  return plugin::CreateOrExplain(ctx, [&]() -> void* {
    RequireNeighbourhood(ctx);
    const formation::ContinuousSmcParams params = ParseContinuousParams(plugin::Attributes(ctx));
    return new AgentInstance<formation::ContinuousSmcAgent>(ctx, params, 1, 0.0);
  });
}

}  // namespace

const mjfPlugin kSmcContinuousAgent = AgentPlugin<formation::ContinuousSmcAgent>(
    "smc_continuous_agent",
    "continuous sliding-mode formation tracking, eq. (30), one instance per follower",
    kContinuousAttributeCount, kContinuousAttributes, &Create);

}  // namespace mjf::formation::adapter
