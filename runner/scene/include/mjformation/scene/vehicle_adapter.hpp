// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Bring your own quadrotor (docs/VEHICLES.md): turns a foreign MJCF model of one vehicle (any
// body name, any rotor actuator names, its own sensors, meshes, lights and floor) into the
// project's vehicle contract (docs/ARCHITECTURE.md, "Vehicle model contract"):
//   - the mapped body becomes the top-level body `vehicle`, alone in <worldbody>;
//   - the mapped rotor actuators are renamed to the names the attitude plugin drives;
//   - a site `imu` at the body's centre of mass and the sensors pos, vel, quat, gyro on it are
//     added;
//   - asset files are resolved as MuJoCo does (model file folder + meshdir/texturedir/assetdir)
//     and written as absolute paths, so the text compiles from anywhere;
//   - what a vehicle must not bring into a shared scene is dropped, and listed in `notes`:
//     world-level geoms (floors), lights, other world bodies, cameras and sites, keyframes,
//     skyboxes, contact pairs and equalities with dropped elements, assets nothing uses.
// The rest of the pipeline (scene composition, binding, plugins) sees a contract model.
#ifndef MJFORMATION_SCENE_VEHICLE_ADAPTER_HPP_
#define MJFORMATION_SCENE_VEHICLE_ADAPTER_HPP_

#include <mjformation/plugin.h>

#include <string>
#include <vector>

#include "mjformation/config/experiment.hpp"

namespace mjf::runner {

struct VehicleMapping {
  std::string model_path;                   // the foreign MJCF file
  std::string body;                         // its vehicle body (top-level, with a free joint)
  std::vector<std::string> rotors;          // its rotor actuators, in the plugin's order
  std::vector<std::string> actuator_names;  // the names the attitude plugin drives
  std::string body_where;    // "exp.toml:7: [vehicles] body", prefix of body messages
  std::string rotors_where;  // same for rotor messages
};

struct AdaptedVehicle {
  std::string xml;                 // contract MJCF text; loads alone (asset paths absolute)
  std::vector<std::string> notes;  // what was dropped, renamed or added, one line each
};

// Throws SceneError naming the experiment key, the model file (and XML line) and the element:
// mapped body missing or without a free joint, a rotor missing, repeated or of the wrong count,
// an asset file missing, a name taken by another element.
AdaptedVehicle AdaptVehicle(const VehicleMapping& mapping);

// The experiment's mapping ([vehicles] body, rotors, or thrust and moments) of its model onto the
// actuators `attitude` drives, adapted; empty (no text, no notes) when the model follows the
// contract. Both faces fly the same adapted text: the runner's Simulation and the native swarm
// plugin, which reads the vehicle's facts from it (BindVehicles' `vehicle_xml`).
AdaptedVehicle AdaptConfiguredVehicle(const ExperimentConfig& config, const mjfPlugin& attitude);

}  // namespace mjf::runner

#endif  // MJFORMATION_SCENE_VEHICLE_ADAPTER_HPP_
