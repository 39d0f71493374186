// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// smc_continuous_agent: eq. (30) per follower (formation::ContinuousSmcAgent), every physics
// step, with smc_continuous's attributes.
#include <mjformation/formation/agent_laws.hpp>

#include "adapter.hpp"
#include "agent_adapter.hpp"

namespace mjf::formation::adapter {

const mjfPlugin kSmcContinuousAgent = AgentPlugin<formation::ContinuousSmcAgent>(
    "smc_continuous_agent",
    "continuous sliding-mode formation tracking, eq. (30), one instance per follower",
    kContinuousAttributeCount, kContinuousAttributes,
    &EveryStepAgentCreate<formation::ContinuousSmcAgent, &ParseContinuousParams>);

}  // namespace mjf::formation::adapter
