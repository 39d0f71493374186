// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The assets of an adapted vehicle (vehicle_adapter.cc): what the vehicle uses is kept, with
// its files as absolute paths; private to scene/.
#ifndef MJFORMATION_SCENE_SRC_VEHICLE_ASSETS_HPP_
#define MJFORMATION_SCENE_SRC_VEHICLE_ASSETS_HPP_

#include <tinyxml2.h>

#include <string>
#include <vector>

namespace mjf::runner {

// Asset files as MuJoCo finds them: the model's folder `dir` + meshdir (meshes, height fields,
// skins) or texturedir (textures), each defaulting to assetdir; absolute paths as given.
// Assets `body` does not use, and skyboxes, are dropped; returns `notes` with what was dropped.
std::vector<std::string> ResolveAssets(tinyxml2::XMLElement* root, const tinyxml2::XMLElement* body,
                                       const std::string& model_path, const std::string& dir,
                                       std::vector<std::string> notes);

}  // namespace mjf::runner

#endif  // MJFORMATION_SCENE_SRC_VEHICLE_ASSETS_HPP_
