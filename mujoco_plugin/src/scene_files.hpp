// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Where a native plugin finds the files and libraries a scene names: the scene's folder (from
// the anchor of an exported scene, mjformation/export/scene_anchor.hpp) for the relative paths of
// its <config> values, and the library's own folder for our plugin libraries.
#ifndef MJFORMATION_MUJOCO_PLUGIN_SCENE_FILES_HPP_
#define MJFORMATION_MUJOCO_PLUGIN_SCENE_FILES_HPP_

#include <mujoco/mujoco.h>

#include <string>
#include <vector>

namespace mjf::native {

// The absolute folder of the scene `m` was compiled from, read from the path MuJoCo resolved
// for the anchor texture (made absolute against the working folder when the scene was loaded by
// a relative name); "" when the scene has no anchor (a scene not written by export). The anchor
// of swarm instance `instance` carries the instance's affixes: an attach renames both alike
// (a/swarm and a/mjformation_scene_folder), and two copies may come from two folders.
std::string SceneFolder(const mjModel* m, int instance);

// Overrides ("section.key=value", the experiment parser's --set form) that put `folder` in front
// of every relative path of `toml_text` (the swarm's <config> pairs as one TOML document): [run]
// plugin_path, [vehicles] model and scene when they are paths, a plugin's `file` and
// [formation.shape] file. None when `folder` is "" or the text does not parse (the experiment
// parser then words the syntax error).
std::vector<std::string> RebasedPathOverrides(const std::string& toml_text,
                                              const std::string& folder);

// Our plugin folders for a native plugin: those of runner::PluginSearchPath with, when the
// library does not lie in an installed prefix, the library's own folder (dladdr) before the build
// tree's: the library copied into a folder with the plugin libraries flies from there.
std::vector<std::string> NativePluginSearchPath(const std::vector<std::string>& extra);

}  // namespace mjf::native

#endif  // MJFORMATION_MUJOCO_PLUGIN_SCENE_FILES_HPP_
