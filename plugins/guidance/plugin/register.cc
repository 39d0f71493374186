// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// libmjf_guidance.so: the list of its plugins, one file each. A new law is one file and one
// line here.
#include <mjformation/plugin_util.hpp>

#include "adapter.hpp"

namespace adapter = mjf::guidance::adapter;

MJF_EXPORT_PLUGINS(&adapter::kCircle, &adapter::kHover, &adapter::kRandomAccel, &adapter::kBangBang,
                   &adapter::kLemniscate, &adapter::kWaypoints, &adapter::kTrajectory)
