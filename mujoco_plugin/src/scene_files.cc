// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "scene_files.hpp"

#include <toml++/toml.h>

#include <cstring>
#include <filesystem>
#include <sstream>

#include "mjformation/config/paths.hpp"
#include "mjformation/export/scene_anchor.hpp"

namespace mjf::native {
namespace {

namespace fs = std::filesystem;

bool IsRelative(const std::string& path) { return !path.empty() && path[0] != '/'; }

std::string TomlString(const std::string& text) {
  std::ostringstream out;
  out << toml::value<std::string>(text);
  return out.str();
}

// runner::ResolveModel's rule: a bare name ("quadrotor") is looked up in the model folders,
// anything with a '/' or ending in .xml is a path.
bool IsModelPath(const std::string& name) {
  return name.find('/') != std::string::npos ||
         (name.size() > 4 && name.compare(name.size() - 4, 4, ".xml") == 0);
}

// "section.key=[...]" with `folder` in front of each relative folder; "" when none is relative
// or an entry is not a string (the parser refuses it, naming the key).
std::string RebasedFolders(const toml::array& dirs, const std::string& folder) {
  std::string list;
  bool rebased = false;
  for (const toml::node& dir : dirs) {
    const auto text = dir.value_exact<std::string>();
    if (!text) return "";
    rebased = rebased || IsRelative(*text);
    list +=
        (list.empty() ? "" : ", ") + TomlString(IsRelative(*text) ? folder + "/" + *text : *text);
  }
  return rebased ? "run.plugin_path=[" + list + "]" : "";
}

}  // namespace

std::string SceneFolder(const mjModel* m, int instance) {
  const char* name = mj_id2name(m, mjOBJ_PLUGIN, instance);
  const std::string instance_name = name ? name : "";
  const size_t at = instance_name.rfind(kSwarmInstance);
  const std::string texture_name = at == std::string::npos
                                       ? std::string(kSceneAnchorTexture)
                                       : instance_name.substr(0, at) + kSceneAnchorTexture +
                                             instance_name.substr(at + std::strlen(kSwarmInstance));
  const int texture = mj_name2id(m, mjOBJ_TEXTURE, texture_name.c_str());
  if (texture < 0 || m->tex_pathadr[texture] < 0) return "";
  std::error_code ec;
  const fs::path anchor = fs::absolute(fs::path(m->paths + m->tex_pathadr[texture]), ec);
  return ec ? "" : anchor.lexically_normal().parent_path().string();
}

std::vector<std::string> RebasedPathOverrides(const std::string& toml_text,
                                              const std::string& folder) {
  std::vector<std::string> out;
  if (folder.empty()) return out;
  toml::table doc;
  try {
    doc = toml::parse(toml_text);
  } catch (const toml::parse_error&) {
    return out;
  }
  auto rebase = [&](const char* key, bool model) {
    const auto path = doc.at_path(key).value_exact<std::string>();
    if (path && IsRelative(*path) && (!model || IsModelPath(*path))) {
      out.push_back(std::string(key) + "=" + TomlString(folder + "/" + *path));
    }
  };
  if (const toml::array* dirs = doc.at_path("run.plugin_path").as_array()) {
    if (std::string folders = RebasedFolders(*dirs, folder); !folders.empty()) {
      out.push_back(folders);
    }
  }
  rebase("vehicles.model", true);
  rebase("vehicles.scene", true);
  for (const char* key :
       {"leader.file", "formation.file", "attitude.file", "estimator.file", "formation.shape.file"})
    rebase(key, false);
  return out;
}

std::vector<std::string> NativePluginSearchPath(const std::vector<std::string>& extra) {
  std::vector<std::string> dirs = runner::PluginSearchPath(extra);
  // The last folder is the default (the prefix's or the build tree's); an installed library
  // keeps to its prefix, as the runner does.
  if (runner::InstalledPrefix().empty()) dirs.insert(dirs.end() - 1, runner::CodeDir());
  return dirs;
}

}  // namespace mjf::native
