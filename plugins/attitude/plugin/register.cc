// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// libmjf_attitude.so: the list of its plugins, one file each. A new controller is one file and
// one line here.
#include <mjformation/plugin_util.hpp>

#include "adapter.hpp"

namespace adapter = mjf::attitude::adapter;

MJF_EXPORT_PLUGINS(&adapter::kPdCascade, &adapter::kGeometric, &adapter::kPointMassDirect)
