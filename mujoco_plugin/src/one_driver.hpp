// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// One instance drives a vehicle: checked while the model compiles, over every instance of our
// plugins in the model (after any attach, by the names in the model).
#ifndef MJFORMATION_MUJOCO_PLUGIN_ONE_DRIVER_HPP_
#define MJFORMATION_MUJOCO_PLUGIN_ONE_DRIVER_HPP_

#include <mujoco/mujoco.h>

namespace mjf::native {

// Throws std::runtime_error naming `plugin`'s instance, the other instance and the shared body
// or actuator when two swarms fly the same vehicles (two attached copies under their own
// prefixes fly their own), an actuator is named by two attitude instances, or a body is flown by
// two instances (the later instance's controls would silently replace the earlier's).
void RefuseDrivingTwice(const char* plugin, const mjModel* m, int instance);

}  // namespace mjf::native

#endif  // MJFORMATION_MUJOCO_PLUGIN_ONE_DRIVER_HPP_
