// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// super_twisting_agent: the super-twisting algorithm (Levant 1993) on s_i = K e_i per follower
// (formation::SuperTwistingAgent), every physics step, with super_twisting's attributes; the
// swarm-wide solve L_H^-1 is closed row by row like smc_continuous_agent's; the integral w_i
// advances with the host's time.
#include <mjformation/formation/literature_agents.hpp>

#include "adapter.hpp"
#include "agent_adapter.hpp"

namespace mjf::formation::adapter {

const mjfPlugin kSuperTwistingAgent = AgentPlugin<formation::SuperTwistingAgent>(
    "super_twisting_agent",
    "super-twisting on s_i = K e_i (Levant 1993), one instance per follower",
    kSuperTwistingAttributeCount, kSuperTwistingAttributes,
    &EveryStepAgentCreate<formation::SuperTwistingAgent, &ParseSuperTwistingParams>);

}  // namespace mjf::formation::adapter
