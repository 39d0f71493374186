// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The bridge for one vehicle of any MJCF model (a Menagerie-style drone in the user's own
// scene): one guidance instance and one attitude instance of our plugin ABI, loaded by name, fly
// the body named in the configuration with the actuators named there.
#ifndef MJFORMATION_MUJOCO_PLUGIN_VEHICLE_HOST_HPP_
#define MJFORMATION_MUJOCO_PLUGIN_VEHICLE_HOST_HPP_

#include <mujoco/mujoco.h>

#include <memory>
#include <string>
#include <vector>

namespace mjf::native {

struct VehicleHostConfig {
  std::string where;                   // "MJCF plugin 'mjformation.attitude' instance 'x'"
  std::string attitude;                // body of a TOML inline table: plugin = "geometric", ...
  std::string guidance;                // same, for the guidance law (default: hover in place)
  std::string body;                    // the vehicle's root body
  std::vector<std::string> actuators;  // in the attitude plugin's actuator order
  std::string plugin_path;             // extra folder searched for our plugins ("" = default path)
  // "rotors" (default: the actuators are rotors at their sites) or "thrust_moments" (a
  // collective thrust along body z, then moments about body x, y, z: Menagerie's Crazyflie 2).
  std::string actuation;
};

// The attribute names of mjformation.attitude, in declaration order.
const std::vector<const char*>& VehicleAttributes();
VehicleHostConfig VehicleConfigFromModel(const mjModel* m, int instance, const char* plugin_name);

class VehicleHost {
 public:
  // Checks everything (sections, plugin attributes, body, actuators); throws std::runtime_error
  // with `config.where` and the key.
  VehicleHost(const mjModel* m, VehicleHostConfig config);
  ~VehicleHost();
  VehicleHost(const VehicleHost&) = delete;
  VehicleHost& operator=(const VehicleHost&) = delete;

  // One tick (guidance, then attitude) on the body's state in `d`; controls[actuator id].
  void Tick(int64_t step, const mjModel* m, const mjData* d, double* controls);
  // What a tick leaves for the next: the setpoint, then the guidance's and the attitude
  // plugin's declared state (ABI 4).
  size_t state_size() const;
  void GetState(double* out) const;
  void SetState(const double* in);

 private:
  // The constructor's work: reads the sections, loads the plugins, binds body and actuators.
  void Build(const mjModel* m);
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mjf::native

#endif  // MJFORMATION_MUJOCO_PLUGIN_VEHICLE_HOST_HPP_
