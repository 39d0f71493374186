// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// smc_discrete_agent: eq. (48) per follower (formation::DiscreteSmcAgent), sampled every T and
// held in between, with smc_discrete's attributes.
#include <cmath>
#include <mjformation/formation/discrete_smc_agent.hpp>
#include <stdexcept>

#include "adapter.hpp"
#include "agent_adapter.hpp"

namespace mjf::formation::adapter {
namespace {

void* Create(const mjfCreateContext* ctx) {
  return plugin::CreateOrExplain(ctx, [&]() -> void* {
    RequireNeighbourhood(ctx);
    const formation::DiscreteSmcParams params = ParseDiscreteParams(plugin::Attributes(ctx));
    if (std::isfinite(params.accel_limit)) {
      // The constrained law needs c_i and z_i = (L_H^-1 e)_i, the swarm-wide solve (C1).
      throw std::invalid_argument(
          "attribute 'accel_limit': the per-agent protocol has no input-constrained variant "
          "(it needs the swarm-wide solve with L_H); use mode = \"central\" or accel_limit = "
          "\"none\"");
    }
    return new AgentInstance<formation::DiscreteSmcAgent>(
        ctx, params, StepsPerSample(params.period, ctx->timestep), params.period);
  });
}

void Report(void* instance, mjfReportFn emit, void* user) {
  const auto& a = *static_cast<const AgentInstance<formation::DiscreteSmcAgent>*>(instance);
  emit(user, plugin::contract::kDelta,
       a.core.delta());  // the host reports the largest over the followers
  emit(user, plugin::contract::kPeriod, a.core.params().period);
  emit(user, "steps_per_sample", static_cast<double>(a.steps_per_sample));
  emit(user, plugin::contract::kQ,
       a.core.params().q);  // for the predicted delay margin (docs/NETWORK.md)
}

}  // namespace

const mjfPlugin kSmcDiscreteAgent = AgentPlugin<formation::DiscreteSmcAgent>(
    "smc_discrete_agent",
    "discrete sliding-mode formation tracking, eq. (48), one instance per follower",
    kDiscreteAttributeCount, kDiscreteAttributes, &Create, &Report);

}  // namespace mjf::formation::adapter
