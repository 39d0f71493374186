// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Small helpers over MuJoCo's model editing API (mjSpec) shared by the scene composition
// (scene.cc) and the vehicle adapter, private to scene/.
#ifndef MJFORMATION_SCENE_SRC_MJSPEC_UTIL_HPP_
#define MJFORMATION_SCENE_SRC_MJSPEC_UTIL_HPP_

#include <mujoco/mujoco.h>

#include <memory>
#include <set>
#include <string>
#include <vector>

namespace mjf::runner::spec {

struct SpecDeleter {
  void operator()(mjSpec* s) const { mj_deleteSpec(s); }
};
using SpecPtr = std::unique_ptr<mjSpec, SpecDeleter>;

// The text of a spec string ("" for none).
inline std::string Str(const mjString* s) { return s ? mjs_getString(s) : ""; }

// The element's name.
inline std::string Name(mjsElement* e) { return Str(mjs_getName(e)); }

// Reads an MJCF file (`xml` empty) or text into a spec. Throws SceneError "what_file:LINE:
// cannot read the <what>: <MuJoCo's first line>", the line taken from MuJoCo's message.
SpecPtr Parse(const std::string& path, const std::string& xml, const std::string& what_file,
              const char* what);

// The elements of one type, in the spec's order (a copy: safe to delete while walking it).
std::vector<mjsElement*> Elements(mjSpec* s, mjtObj type);

// Deletes every element of `type` from the spec.
void DeleteAll(mjSpec* s, mjtObj type);

// The asset types a vehicle can bring (meshes, skins, height fields, textures, materials).
inline constexpr mjtObj kAssetTypes[] = {mjOBJ_MESH, mjOBJ_SKIN, mjOBJ_HFIELD, mjOBJ_TEXTURE,
                                         mjOBJ_MATERIAL};

// Names of the assets in the spec.
std::set<std::string> AssetNames(mjSpec* s);

// The MJCF text of the spec as written (MuJoCo's own writer, compiler savecompiled="false", so
// the text compiles to exactly the model the spec compiles to). `size_hint`: the text's
// expected length; MuJoCo writes the whole text again when its buffer was too small. Throws
// SceneError.
std::string SaveXml(mjSpec* s, const std::string& name, size_t size_hint = 1 << 16);

}  // namespace mjf::runner::spec

#endif  // MJFORMATION_SCENE_SRC_MJSPEC_UTIL_HPP_
