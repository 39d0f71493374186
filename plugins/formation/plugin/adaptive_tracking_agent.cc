// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// adaptive_tracking_agent: Li, Liu, Ren & Xie (IEEE TAC 2013)'s adaptive-gain tracking per follower
// (formation::AdaptiveTrackingAgent), every physics step, with adaptive_tracking's attributes; its
// row needs e_i only; the gain d_i advances with the host's time.
#include <mjformation/formation/literature_agents.hpp>

#include "adapter.hpp"
#include "agent_adapter.hpp"

namespace mjf::formation::adapter {

const mjfPlugin kAdaptiveTrackingAgent = AgentPlugin<formation::AdaptiveTrackingAgent>(
    "adaptive_tracking_agent",
    "adaptive-gain tracking, Li, Liu, Ren & Xie (TAC 2013), one instance per follower",
    kAdaptiveTrackingAttributeCount, kAdaptiveTrackingAttributes,
    &EveryStepAgentCreate<formation::AdaptiveTrackingAgent, &ParseAdaptiveTrackingParams>);

}  // namespace mjf::formation::adapter
