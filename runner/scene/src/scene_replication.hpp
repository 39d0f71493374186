// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Composition linear in the number of vehicles (scene.cc), private to scene/. mjs_attach
// rebuilds every list of the scene it attaches into (names, ids, plugins, keyframes), so N
// attaches cost O(N^2). Instead, one vehicle is attached and MuJoCo writes the scene with it
// (MJCF text, one vehicle) and without it; the difference, the vehicle's elements section by
// section, is copied once per vehicle with its names prefixed, and MuJoCo reads the text once.
// What MuJoCo wrote reads back to the same spec, so the scene is the one N attaches would build.
#ifndef MJFORMATION_SCENE_SRC_SCENE_REPLICATION_HPP_
#define MJFORMATION_SCENE_SRC_SCENE_REPLICATION_HPP_

#include <optional>
#include <string>
#include <vector>

namespace mjf::runner {

// `without`: the scene's MJCF as MuJoCo wrote it; `with_one`: the same with one vehicle attached
// with prefix prefixes[0]. Returns the scene's MJCF with one copy of the vehicle's elements per
// prefix, in prefix order within each section (the order N attaches give), each copy's names
// (and every reference to them) under its own prefix; the shared assets once. Returns nothing
// when the text holds a section whose copies would not be a plain repetition (keyframes sized
// to the whole model, plugins, custom data, ...): the caller then attaches vehicle by vehicle.
std::optional<std::string> ReplicateVehicle(const std::string& without, const std::string& with_one,
                                            const std::vector<std::string>& prefixes);

}  // namespace mjf::runner

#endif  // MJFORMATION_SCENE_SRC_SCENE_REPLICATION_HPP_
