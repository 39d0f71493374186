// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include <mjformation/plugin_util.hpp>

#include "plugins.hpp"

MJF_EXPORT_PLUGINS(&mjf::formation::kSmcContinuous, &mjf::formation::kSmcDiscrete,
                   &mjf::formation::kConsensusLinear, &mjf::formation::kSmcDiscreteAgent,
                   &mjf::formation::kSmcContinuousAgent, &mjf::formation::kConsensusLinearAgent)
