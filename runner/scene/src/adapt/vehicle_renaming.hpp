// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Renaming elements of a vehicle's model together with every reference to them
// (vehicle_adapter.cc's renaming steps), private to scene/.
#ifndef MJFORMATION_SCENE_SRC_VEHICLE_RENAMING_HPP_
#define MJFORMATION_SCENE_SRC_VEHICLE_RENAMING_HPP_

#include <tinyxml2.h>

#include <string>
#include <vector>

namespace mjf::runner {

// The actuator element tags of MJCF.
inline const char* const kActuatorTags[] = {"general",  "motor",       "position",
                                            "velocity", "cylinder",    "muscle",
                                            "adhesion", "intvelocity", "damper"};

// Renames the element of kind `kind` ("body", "site" or "actuator") named `from` to `to` in the
// whole document under `root`, and every attribute that refers to it (mjcf::kReferenceAttributes
// of that kind, and objname/refname whose objtype/reftype is that kind).
void RenameElement(tinyxml2::XMLElement* root, const std::string& kind, const std::string& from,
                   const std::string& to);

// The mapped body `body` (named `name` in the model) becomes `vehicle`. Throws SceneError
// naming `where` if a body inside it already has that name.
void RenameVehicleBody(tinyxml2::XMLElement* root, const tinyxml2::XMLElement* body,
                       const std::string& name, const std::string& model_path,
                       const std::string& where, std::vector<std::string>* notes);

// The contract's site `imu` and sensors pos/vel/quat/gyro are added later; the model's own
// elements of those names keep working under a model_ prefix.
void MakeRoomForContractNames(tinyxml2::XMLElement* root, std::vector<std::string>* notes);

}  // namespace mjf::runner

#endif  // MJFORMATION_SCENE_SRC_VEHICLE_RENAMING_HPP_
