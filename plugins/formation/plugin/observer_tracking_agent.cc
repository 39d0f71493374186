// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// observer_tracking_agent: Hong, Hu & Gao (Automatica 2006)'s tracking with a leader-velocity
// estimator per follower (formation::ObserverTrackingAgent), every physics step, with
// observer_tracking's attributes; its row needs e_ip and the own velocity; the estimate vbar_i
// advances with the host's time.
#include <mjformation/formation/literature_agents.hpp>

#include "adapter.hpp"
#include "agent_adapter.hpp"

namespace mjf::formation::adapter {

const mjfPlugin kObserverTrackingAgent = AgentPlugin<formation::ObserverTrackingAgent>(
    "observer_tracking_agent",
    "tracking with a leader-velocity estimator, Hong, Hu & Gao (Automatica 2006), one instance per "
    "follower",
    kObserverTrackingAttributeCount, kObserverTrackingAttributes,
    &EveryStepAgentCreate<formation::ObserverTrackingAgent, &ParseObserverTrackingParams>);

}  // namespace mjf::formation::adapter
