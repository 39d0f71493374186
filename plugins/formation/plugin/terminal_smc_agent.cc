// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// terminal_smc_agent: Feng, Yu & Man (Automatica 2002)'s nonsingular terminal sliding mode per
// follower (formation::TerminalSmcAgent), every physics step, with terminal_smc's attributes; the
// swarm-wide solve L_H^-1 is closed row by row like smc_continuous_agent's.
#include <mjformation/formation/literature_agents.hpp>

#include "adapter.hpp"
#include "agent_adapter.hpp"

namespace mjf::formation::adapter {

const mjfPlugin kTerminalSmcAgent = AgentPlugin<formation::TerminalSmcAgent>(
    "terminal_smc_agent",
    "nonsingular terminal sliding mode, Feng, Yu & Man (Automatica 2002), one instance per "
    "follower",
    kTerminalSmcAttributeCount, kTerminalSmcAttributes,
    &EveryStepAgentCreate<formation::TerminalSmcAgent, &ParseTerminalSmcParams>);

}  // namespace mjf::formation::adapter
