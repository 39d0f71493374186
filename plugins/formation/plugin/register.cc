// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// libmjf_formation.so: the list of its plugins, one file each. A new law is one file and one
// line here.
#include <mjformation/plugin_util.hpp>

#include "adapter.hpp"

namespace adapter = mjf::formation::adapter;

MJF_EXPORT_PLUGINS(&adapter::kSmcContinuous, &adapter::kSmcDiscrete, &adapter::kConsensusLinear,
                   &adapter::kSmcDiscreteAgent, &adapter::kSmcContinuousAgent,
                   &adapter::kConsensusLinearAgent, &adapter::kVsTracking, &adapter::kSuperTwisting,
                   &adapter::kAdaptiveTracking, &adapter::kObserverTracking, &adapter::kTerminalSmc,
                   &adapter::kVsTrackingAgent, &adapter::kSuperTwistingAgent,
                   &adapter::kAdaptiveTrackingAgent, &adapter::kObserverTrackingAgent,
                   &adapter::kTerminalSmcAgent)
