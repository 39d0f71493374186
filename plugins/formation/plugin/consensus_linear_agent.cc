// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// consensus_linear_agent: the linear consensus baseline per follower
// (formation::LinearConsensusAgent), every physics step, with consensus_linear's attributes.
#include <mjformation/formation/agent_laws.hpp>

#include "adapter.hpp"
#include "agent_adapter.hpp"

namespace mjf::formation::adapter {

const mjfPlugin kConsensusLinearAgent = AgentPlugin<formation::LinearConsensusAgent>(
    "consensus_linear_agent", "linear consensus formation tracking, one instance per follower",
    kConsensusAttributeCount, kConsensusAttributes,
    &EveryStepAgentCreate<formation::LinearConsensusAgent, &ParseConsensusParams>);

}  // namespace mjf::formation::adapter
