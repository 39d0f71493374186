// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// consensus_linear_agent: the linear consensus baseline per follower
// (formation::LinearConsensusAgent), every physics step, with consensus_linear's attributes.
#include <mjformation/formation/agent_laws.hpp>

#include "adapter.hpp"
#include "agent_adapter.hpp"

namespace mjf::formation::adapter {
namespace {

void* Create(const mjfCreateContext* ctx) {
  return plugin::CreateOrExplain(ctx, [&]() -> void* {
    RequireNeighbourhood(ctx);
    const formation::LinearConsensusParams params = ParseConsensusParams(plugin::Attributes(ctx));
    return new AgentInstance<formation::LinearConsensusAgent>(ctx, params, 1, 0.0);
  });
}

}  // namespace

const mjfPlugin kConsensusLinearAgent = AgentPlugin<formation::LinearConsensusAgent>(
    "consensus_linear_agent", "linear consensus formation tracking, one instance per follower",
    kConsensusAttributeCount, kConsensusAttributes, &Create);

}  // namespace mjf::formation::adapter
