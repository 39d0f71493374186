// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Attaching many vehicles in few attaches (scene.cc), private to scene/. Each mjs_attach costs
// a pass over the whole scene it attaches into, and so does each element MuJoCo's MJCF reader
// adds; N vehicles attached one by one cost O(N^2). Here vehicles are attached in decimal
// blocks: block k holds 10^k vehicles named with k digits (block 0: the vehicle under prefix
// "_"; block k: ten copies of block k-1 under prefixes "0".."9"), so vehicles 120..129 are
// block 1 attached once under prefix "uav12" (names uav12<d>_...). Every attach is into a
// spec at most the size of the scene, and there are O(log N) of them per decade: composition
// is O(N log N).
#ifndef MJFORMATION_SCENE_SRC_SCENE_BLOCKS_HPP_
#define MJFORMATION_SCENE_SRC_SCENE_BLOCKS_HPP_

#include <mujoco/mujoco.h>

#include <functional>
#include <set>
#include <string>
#include <vector>

#include "mjspec_util.hpp"

namespace mjf::runner {

// In the name of every default class a block brings (uav12mjf_block1: block 1 under prefix
// uav12), and in no other.
inline constexpr char kBlockMarker[] = "mjf_block";

// Attaches vehicles first+1 .. last (vehicle `first` is in the scene already, with the assets)
// as copies of `vehicle_body` (its spec holds no assets any more), each under the prefix
// VehiclePrefix(i), in index order within every list (the order one attach per vehicle gives).
// `globals` makes a new spec's global settings the scene's. Returns the block specs, which
// must outlive the compilation of the scene. Throws SceneError with MuJoCo's message.
std::vector<spec::SpecPtr> AttachInBlocks(mjSpec* scene, mjsBody* vehicle_body, int first, int last,
                                          const std::function<void(mjSpec*)>& globals,
                                          const std::string& vehicle_path);

// Every reference of the scene to a copy's asset (uav<i>_<asset>, `vehicle_assets` naming the
// assets) now names the one shared asset <asset>, in one pass over the scene.
void ShareAssetReferences(mjSpec* scene, const std::set<std::string>& vehicle_assets,
                          bool defaults_refer_to_assets);

}  // namespace mjf::runner

#endif  // MJFORMATION_SCENE_SRC_SCENE_BLOCKS_HPP_
