// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The scene plan: where each vehicle starts, and where its sensors, body and actuators live in
// the composed model (resolved once, before any step; a missing name fails here, never mid-run).
#ifndef MJFORMATION_SCENE_VEHICLE_BINDING_HPP_
#define MJFORMATION_SCENE_VEHICLE_BINDING_HPP_

#include <mjformation/plugin.h>
#include <mujoco/mujoco.h>

#include <array>
#include <string>
#include <vector>

#include "mjformation/config/experiment.hpp"

namespace mjf::runner {

// Where vehicle i's sensor values and actuators live in the composed model.
struct VehicleBinding {
  int body = -1;
  int sensor_pos = -1, sensor_vel = -1, sensor_quat = -1, sensor_gyro = -1;  // sensordata adr
  std::vector<int> actuators;  // ids in the composed model (actuator rotor model)
  std::vector<int> sites;      // site of each driven actuator (wrench rotor model)
  std::vector<mjfActuatorInfo> actuator_info;
  mjfVehicleInfo info{};  // points into actuator_info: do not copy a binding
};

// How a vehicle's element names read in the model bound: `prefix + name + suffix`. Empty in the
// runner's own scene; a scene attached into another (MuJoCo's mjs_attach) renames every element
// this way, and a native plugin binds through the names its instance was attached with.
struct SceneNames {
  std::string prefix, suffix;
  std::string operator()(const std::string& name) const { return prefix + name + suffix; }
};

struct VehicleBindings {
  std::vector<VehicleBinding> vehicles;  // 0 = leader
  std::vector<double> wrench_gain;       // actuator gain per driven actuator (same per vehicle)
  int actuators_per_vehicle = 0;
  // The vehicle model's actuators that act on it but that the attitude plugin does not name (a
  // gimbal's servo): never driven, they keep the model's own ctrl (0 unless set).
  std::vector<std::string> undriven_actuators;
};

// Initial positions: the leader at leader_start, followers at follower_start or, by default,
// on a ring about the origin with at least 1.5 m between neighbours; all at the altitude.
// start_jitter adds a seeded uniform perturbation (same seed, same positions).
std::vector<std::array<double, 3>> InitialPositions(const ExperimentConfig& config);

// Reads mass, inertia and actuator geometry from the vehicle model alone (`vehicle_xml`, the
// adapted foreign model, or else the file [vehicles] model), then binds every vehicle of the
// composed model. Throws SceneError / PluginError naming what is missing. `first` and `count`
// (-1: all 1 + N): the vehicles the composed model holds (a partition of the swarm). `names`:
// how the vehicles' names read in `composed` (SceneNames).
VehicleBindings BindVehicles(const mjModel* composed, const ExperimentConfig& config,
                             const mjfPlugin& attitude, const std::string& vehicle_xml = "",
                             int first = 0, int count = -1, const SceneNames& names = {});
// The same vehicle info (mass, inertia, actuators; gravity from `model`), without binding any
// sensor, actuator or site of `model` (ids stay -1): what a plugin's create() needs, for a
// model whose sensors and actuators are not compiled yet (a native plugin's nstate).
VehicleBindings DescribeVehicles(const mjModel* model, const ExperimentConfig& config,
                                 const mjfPlugin& attitude, const std::string& vehicle_xml = "");

// The vehicles' true states from MuJoCo's sensors (after mj_step1 or mj_forward).
void ReadTrueStates(const mjData* data, const VehicleBindings& bindings,
                    std::vector<mjfVehicleState>* states);

}  // namespace mjf::runner

#endif  // MJFORMATION_SCENE_VEHICLE_BINDING_HPP_
