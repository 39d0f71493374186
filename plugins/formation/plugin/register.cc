// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include <mjformation/plugin_util.hpp>

#include "plugins.hpp"

MJF_EXPORT_PLUGINS(&mjf::formation::adapter::kSmcContinuous, &mjf::formation::adapter::kSmcDiscrete,
                   &mjf::formation::adapter::kConsensusLinear,
                   &mjf::formation::adapter::kSmcDiscreteAgent,
                   &mjf::formation::adapter::kSmcContinuousAgent,
                   &mjf::formation::adapter::kConsensusLinearAgent,
                   &mjf::formation::adapter::kVsTracking, &mjf::formation::adapter::kSuperTwisting,
                   &mjf::formation::adapter::kAdaptiveTracking,
                   &mjf::formation::adapter::kObserverTracking,
                   &mjf::formation::adapter::kTerminalSmc)
