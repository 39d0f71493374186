// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/config/paths.hpp"

#include <dlfcn.h>
#include <link.h>
#include <sys/stat.h>
#include <unistd.h>

#include <climits>
#include <cstdlib>

#include "mjformation/config/config_error.hpp"

namespace mjf::runner {

std::string ExecutableDir() {
  char buf[4096];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof(buf) - 1);
  if (n <= 0) return ".";
  std::string exe(buf, static_cast<size_t>(n));
  return exe.substr(0, exe.find_last_of('/'));
}

bool IsDirectory(const std::string& path) {
  struct stat st;
  return stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode);
}

bool IsFile(const std::string& path) {
  struct stat st;
  return stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

std::string ResolveRelative(const std::string& path, const std::string& relative_to_file) {
  if (path.empty() || path[0] == '/') return path;
  const auto slash = relative_to_file.find_last_of('/');
  if (slash == std::string::npos) return path;
  return relative_to_file.substr(0, slash + 1) + path;
}

std::string CodeDir() {
  Dl_info info{};
  link_map* map = nullptr;
  if (dladdr1(reinterpret_cast<void*>(&CodeDir), &info, reinterpret_cast<void**>(&map),
              RTLD_DL_LINKMAP) == 0 ||
      map == nullptr || map->l_name == nullptr || map->l_name[0] == '\0') {
    return ExecutableDir();  // the main program: its link map has no name
  }
  char resolved[PATH_MAX];
  if (realpath(map->l_name, resolved) == nullptr) return ExecutableDir();
  const std::string path(resolved);
  return path.substr(0, path.find_last_of('/'));
}

std::string InstalledPrefix() {
  // Resolved once: the code does not move while it runs.
  static const std::string prefix = [] {
    const std::string dir = CodeDir();
    for (const std::string& candidate :
         {dir + "/" MJF_INSTALL_BIN_TO_PREFIX, dir + "/..", dir + "/../../../..", dir}) {
      char resolved[PATH_MAX];
      if (IsDirectory(candidate + "/" MJF_INSTALL_DATA_DIR) &&
          IsDirectory(candidate + "/" MJF_INSTALL_PLUGIN_DIR) &&
          realpath(candidate.c_str(), resolved) != nullptr) {
        return std::string(resolved);
      }
    }
    return std::string();
  }();
  return prefix;
}

std::vector<std::string> ModelSearchPath() {
  std::vector<std::string> dirs;
  if (const char* env = std::getenv("MJF_MJCF_DIR")) dirs.push_back(env);
  const std::string prefix = InstalledPrefix();
  dirs.push_back(prefix.empty() ? MJF_SOURCE_MJCF_DIR : prefix + "/" MJF_INSTALL_DATA_DIR "/mjcf");
  return dirs;
}

std::string ResolveModel(const std::string& name, const std::string& experiment_file) {
  const bool is_path = name.find('/') != std::string::npos ||
                       (name.size() > 4 && name.compare(name.size() - 4, 4, ".xml") == 0);
  if (is_path) {
    const std::string resolved = ResolveRelative(name, experiment_file);
    if (IsDirectory(resolved)) {
      throw ConfigError(experiment_file + ": model file '" + name + "' is a folder (" + resolved +
                        "), not an MJCF file");
    }
    if (!IsFile(resolved)) {
      throw ConfigError(experiment_file + ": model file '" + name + "' not found (looked at " +
                        resolved + ")");
    }
    return resolved;
  }
  const std::vector<std::string> dirs = ModelSearchPath();
  std::string looked;
  for (const auto& dir : dirs) {
    const std::string candidate = dir + "/" + name + ".xml";
    if (IsFile(candidate)) return candidate;
    looked += (looked.empty() ? "" : ", ") + candidate;
  }
  throw ConfigError(experiment_file + ": model '" + name + "' not found (looked at " + looked +
                    ")");
}

std::vector<std::string> PluginSearchPath(const std::vector<std::string>& extra) {
  std::vector<std::string> dirs = extra;
  if (const char* env = std::getenv("MJF_PLUGIN_PATH")) {
    std::string all(env);
    size_t start = 0;
    while (start <= all.size()) {
      const size_t colon = all.find(':', start);
      const std::string dir = all.substr(start, colon - start);
      if (!dir.empty()) dirs.push_back(dir);
      if (colon == std::string::npos) break;
      start = colon + 1;
    }
  }
  const std::string prefix = InstalledPrefix();
  dirs.push_back(prefix.empty() ? MJF_PLUGIN_BUILD_DIR : prefix + "/" MJF_INSTALL_PLUGIN_DIR);
  return dirs;
}

std::vector<std::string> MpiModuleSearchPath() {
  std::vector<std::string> paths;
  if (const char* env = std::getenv("MJF_MPI_MODULE")) paths.push_back(env);
  const std::string prefix = InstalledPrefix();
  paths.push_back(prefix.empty() ? MJF_MPI_MODULE_BUILD_PATH : prefix + "/" MJF_INSTALL_MPI_MODULE);
  return paths;
}

}  // namespace mjf::runner
