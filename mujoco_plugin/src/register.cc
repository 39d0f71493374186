// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
// Registers mjformation's native engine plugins when MuJoCo loads this library
// (mj_loadPluginLibrary, mujoco.MjModel after mujoco.mj_loadPluginLibrary, or a link).
#include <mujoco/mjplugin.h>

#include "attitude_plugin.hpp"
#include "swarm_plugin.hpp"

mjPLUGIN_LIB_INIT(mjformation) {
  mjf::native::SwarmPlugin::Register();
  mjf::native::AttitudePlugin::Register();
}
