// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The mapping of a vehicle model's actuators onto the names the attitude plugin drives
// (vehicle_adapter.cc's actuator step), private to scene/.
#ifndef MJFORMATION_SCENE_SRC_ACTUATOR_MAPPING_HPP_
#define MJFORMATION_SCENE_SRC_ACTUATOR_MAPPING_HPP_

#include <tinyxml2.h>

#include <string>
#include <vector>

#include "mjformation/scene/vehicle_adapter.hpp"

namespace mjf::runner {

// Checks that `mapping.rotors` are actuators of the model under `root`, each once, as many as
// the plugin drives, each on a site of the vehicle `body`; then renames them (and every
// reference) to `mapping.actuator_names`, in order. A non-rotor actuator that has a contract
// name already steps aside under a model_ prefix. Throws SceneError naming the experiment key.
void MapRotors(tinyxml2::XMLElement* root, const tinyxml2::XMLElement* body,
               const VehicleMapping& mapping, std::vector<std::string>* notes);

}  // namespace mjf::runner

#endif  // MJFORMATION_SCENE_SRC_ACTUATOR_MAPPING_HPP_
