// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// [formation.shape] -> the core's Shape (runner/config/src/shape_config.cc).
#ifndef MJFORMATION_CONFIG_SHAPE_CONFIG_HPP_
#define MJFORMATION_CONFIG_SHAPE_CONFIG_HPP_

#include <memory>

#include "mjformation/config/experiment.hpp"

namespace mjf::formation {
class Shape;
}  // namespace mjf::formation

namespace mjf::runner {

// The desired formation f_i(t) of [formation.shape]; nullptr for type "none". Reads the table
// file for type "table". Throws ConfigError naming the file (and row) on bad input.
std::unique_ptr<formation::Shape> MakeShape(const ExperimentConfig& config);

}  // namespace mjf::runner

#endif  // MJFORMATION_CONFIG_SHAPE_CONFIG_HPP_
