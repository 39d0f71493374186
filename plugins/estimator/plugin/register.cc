// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// libmjf_estimator.so: the list of its plugins, one file each.
#include <mjformation/plugin_util.hpp>

#include "adapter.hpp"

namespace adapter = mjf::estimator::adapter;

MJF_EXPORT_PLUGINS(&adapter::kPassthrough, &adapter::kKfIns)
