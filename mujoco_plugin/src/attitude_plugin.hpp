// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// mjformation.attitude: flies one vehicle of any MJCF model (a Menagerie-style drone in the
// user's own scene) with a guidance and an attitude plugin of ours (VehicleHost), on the body
// and actuators its <config> names; the body references the instance, so an attach keeps it
// and renames what it drives (attach_names.hpp). Timing, state and actuation:
// actuator_plugin.hpp.
#ifndef MJFORMATION_MUJOCO_PLUGIN_ATTITUDE_PLUGIN_HPP_
#define MJFORMATION_MUJOCO_PLUGIN_ATTITUDE_PLUGIN_HPP_

#include <mujoco/mujoco.h>

#include <memory>

#include "actuator_plugin.hpp"
#include "vehicle_host.hpp"

namespace mjf::native {

class AttitudePlugin {
 public:
  static constexpr char kName[] = "mjformation.attitude";
  // The state a vehicle's guidance and attitude plugins may declare together, in doubles: a
  // fixed bound, since the vehicle's actuators (which their create() reads) are not compiled
  // when MuJoCo asks for the size. The stock plugins declare at most a few tens.
  static constexpr size_t kStateBound = 256;
  // Registers the plugin with MuJoCo (its attributes: VehicleAttributes()).
  static void Register();

  // The callbacks' plugin-specific part (PluginKind): a holder with a VehicleHost of the
  // instance's configuration (refused when its plugins declare more than kStateBound doubles),
  // and the state's size (kStateBound, once the configuration reads).
  static std::unique_ptr<Holder> Make(const mjModel* m, int instance);
  static size_t StateSize(const mjModel* m, int instance);

  // The instance's configuration with its body and actuators named as they read in `m`: as
  // written, or renamed by an attach, read from the body that references the instance.
  static VehicleHostConfig Config(const mjModel* m, int instance);
};

extern const PluginKind kAttitudeKind;

}  // namespace mjf::native

#endif  // MJFORMATION_MUJOCO_PLUGIN_ATTITUDE_PLUGIN_HPP_
