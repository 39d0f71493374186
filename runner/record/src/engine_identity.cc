// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/record/engine_identity.hpp"

#include <dlfcn.h>
#include <mujoco/mujoco.h>

#include <climits>
#include <cstdlib>
#include <fstream>
#include <iterator>

#include "mjformation/record/output.hpp"

namespace mjf::runner {
namespace {

// The file the dynamic loader mapped mj_version from: the library every MuJoCo call goes to.
std::string LoadedLibraryPath() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&mj_version), &info) == 0 || !info.dli_fname) return "";
  // Canonical: the loader spells it through the RPATH ($ORIGIN/../lib) or a symlink.
  char resolved[PATH_MAX];
  return realpath(info.dli_fname, resolved) ? resolved : info.dli_fname;
}

std::string FileSha256(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "";
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return Sha256Hex(bytes);
}

}  // namespace

const EngineIdentity& RunningEngine() {
  static const EngineIdentity identity = [] {
    EngineIdentity e;
    e.version = mj_versionString();
    e.library_path = LoadedLibraryPath();
    e.library_sha256 = e.library_path.empty() ? "" : FileSha256(e.library_path);
    return e;
  }();
  return identity;
}

}  // namespace mjf::runner
