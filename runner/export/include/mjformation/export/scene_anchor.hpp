// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// How an exported scene's native plugin finds the scene's folder. MuJoCo hands an engine plugin
// the compiled model only, never the file it came from, so relative paths in a <config> value
// would be read against whatever the working folder happens to be. The compiled model does keep
// the resolved path of every asset file (mjModel::paths), found by MuJoCo beside the scene: an
// exported scene declares one tiny texture, this anchor, written beside scene.xml, and the plugin
// reads the paths of its <config> relative to the anchor's folder (docs/PLUGINS.md, "Scenes that
// travel"). Shared by export (runner/export) and the native plugins (mujoco_plugin/src).
#ifndef MJFORMATION_EXPORT_SCENE_ANCHOR_HPP_
#define MJFORMATION_EXPORT_SCENE_ANCHOR_HPP_

namespace mjf {

// The anchor's texture name in the scene and its file beside scene.xml (a 1 x 1 PNG).
inline constexpr char kSceneAnchorTexture[] = "mjformation_scene_folder";
inline constexpr char kSceneAnchorFile[] = "mjformation_scene_folder.png";
// The swarm instance's name in an exported scene. An attach renames the instance and the anchor
// alike (prefix + name + suffix), so the instance finds its own anchor under its own affixes.
inline constexpr char kSwarmInstance[] = "swarm";

}  // namespace mjf

#endif  // MJFORMATION_EXPORT_SCENE_ANCHOR_HPP_
