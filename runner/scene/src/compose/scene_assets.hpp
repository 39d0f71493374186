// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// A vehicle's assets in the composed scene (scene.cc), private to scene/: only what the vehicle
// uses, its files as absolute paths, one copy shared by all vehicles.
#ifndef MJFORMATION_SCENE_SRC_SCENE_ASSETS_HPP_
#define MJFORMATION_SCENE_SRC_SCENE_ASSETS_HPP_

#include <mujoco/mujoco.h>

#include <set>
#include <string>
#include <vector>

namespace mjf::runner {

// Deletes from the vehicle's spec the meshes, height fields, materials and textures that
// `body` (geoms, sites, lights), the tendons and skins do not use: mjs_attach would carry them
// all. Mesh, skin and height-field files are made absolute from the model's folder `dir` and
// meshdir, texture files from texturedir, so the scene's text finds them wherever it is written.
void PrepareVehicleAssets(mjSpec* vehicle, mjsBody* body, const std::string& dir);

// mjs_attach gives every copy its own prefixed assets (uav3_canopy): one copy of each is kept
// under the model's own name, or the scene's asset of that name if it has one (as the scene
// composed in MJCF did), and every reference to another copy points at it.
void ShareVehicleAssets(mjSpec* scene, const std::set<std::string>& vehicle_assets,
                        const std::vector<std::string>& prefixes);

}  // namespace mjf::runner

#endif  // MJFORMATION_SCENE_SRC_SCENE_ASSETS_HPP_
