// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Where things are found: vehicle models, plugins, the executable's own folder.
#ifndef MJFORMATION_CONFIG_PATHS_HPP_
#define MJFORMATION_CONFIG_PATHS_HPP_

#include <string>
#include <vector>

namespace mjf::runner {

// Folder of the running executable (or of the library's user), from /proc/self/exe.
std::string ExecutableDir();

// `path` as given if absolute; else relative to the folder of `relative_to_file`.
std::string ResolveRelative(const std::string& path, const std::string& relative_to_file);

// A vehicle or scene model: a bare name ("quadrotor") is looked up as <name>.xml in the model
// folders (MJF_MJCF_DIR, the source tree's mjcf/, <prefix>/share/mjformation/mjcf); anything
// with a '/' or ending in .xml is a path relative to the experiment file. Throws ConfigError
// listing where it looked.
std::string ResolveModel(const std::string& name, const std::string& experiment_file);

// Plugin folders in search order: `extra` (from the experiment file / CLI), then each entry of
// $MJF_PLUGIN_PATH (colon-separated), the build tree's plugins/, and the install folder.
std::vector<std::string> PluginSearchPath(const std::vector<std::string>& extra);

bool IsDirectory(const std::string& path);
bool IsFile(const std::string& path);

}  // namespace mjf::runner

#endif  // MJFORMATION_CONFIG_PATHS_HPP_
