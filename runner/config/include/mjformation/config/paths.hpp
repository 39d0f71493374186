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

// Folder of the file this code was loaded from: the executable, or the shared object (the
// Python module, the native MuJoCo plugin library) when it runs inside another program.
std::string CodeDir();

// The prefix the running code was installed into (wherever it was moved since), or "" when it
// runs from the build tree (or is a test). A prefix holds share/mjformation and
// lib/mjformation/plugins; it is looked for from CodeDir() where each layout puts its files:
// bin/ (the runner), lib/ (the native plugin library), lib/pythonX.Y/dist-packages/mjformation
// (the Python module of `cmake --install`), and the Python package itself, which is the prefix
// in a wheel (`pip install .`: site-packages/mjformation). An installed runner searches
// only its own prefix (and what the user names); the build tree's runner the build and source
// trees.
std::string InstalledPrefix();

// The model folders in search order: $MJF_MJCF_DIR, then <prefix>/share/mjformation/mjcf when
// installed, else the source tree's mjcf/.
std::vector<std::string> ModelSearchPath();

// A vehicle or scene model: a bare name ("quadrotor") is looked up as <name>.xml in the model
// folders (ModelSearchPath); anything with a '/' or ending in .xml is a path relative to the
// experiment file. Throws ConfigError listing where it looked.
std::string ResolveModel(const std::string& name, const std::string& experiment_file);

// Plugin folders in search order: `extra` (from the experiment file / CLI), then each entry of
// $MJF_PLUGIN_PATH (colon-separated), then <prefix>/lib/mjformation/plugins when installed, else
// the build tree's plugins/.
std::vector<std::string> PluginSearchPath(const std::vector<std::string>& extra);

// The MPI transport module of `sweep` (runner/mpi): $MJF_MPI_MODULE, then the prefix's
// lib/mjformation/libmjf_sweep_mpi.so when installed, else the build tree's.
std::vector<std::string> MpiModuleSearchPath();

bool IsDirectory(const std::string& path);
bool IsFile(const std::string& path);

}  // namespace mjf::runner

#endif  // MJFORMATION_CONFIG_PATHS_HPP_
