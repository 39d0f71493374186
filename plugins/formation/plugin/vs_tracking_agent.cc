// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// vs_tracking_agent: Cao & Ren (IEEE TAC 2012)'s variable-structure tracking per follower
// (formation::VsTrackingAgent), every physics step, with vs_tracking's attributes; its row needs
// e_i only: nothing is exchanged but the states.
#include <mjformation/formation/literature_agents.hpp>

#include "adapter.hpp"
#include "agent_adapter.hpp"

namespace mjf::formation::adapter {

const mjfPlugin kVsTrackingAgent = AgentPlugin<formation::VsTrackingAgent>(
    "vs_tracking_agent",
    "variable-structure coordinated tracking, Cao & Ren (IEEE TAC 2012), one instance per follower",
    kVsTrackingAttributeCount, kVsTrackingAttributes,
    &EveryStepAgentCreate<formation::VsTrackingAgent, &ParseVsTrackingParams>);

}  // namespace mjf::formation::adapter
