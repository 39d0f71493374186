// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The estimator plugin family (libmjf_estimator.so): one descriptor per file.
#ifndef MJFORMATION_ESTIMATOR_PLUGIN_ADAPTER_HPP_
#define MJFORMATION_ESTIMATOR_PLUGIN_ADAPTER_HPP_

#include <mjformation/plugin.h>

namespace mjf::estimator::adapter {

extern const mjfPlugin kPassthrough;  // plugin/passthrough.cc
extern const mjfPlugin kKfIns;        // plugin/kf_ins.cc

}  // namespace mjf::estimator::adapter

#endif  // MJFORMATION_ESTIMATOR_PLUGIN_ADAPTER_HPP_
