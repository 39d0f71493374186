// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Which MuJoCo this process runs: the version the library reports and the library file itself,
// so a result names the exact engine binary that produced it (--version, summary.json).
#ifndef MJFORMATION_RECORD_ENGINE_IDENTITY_HPP_
#define MJFORMATION_RECORD_ENGINE_IDENTITY_HPP_

#include <string>

namespace mjf::runner {

struct EngineIdentity {
  std::string version;         // mj_versionString(), e.g. "4.0.1"
  std::string library_path;    // the loaded libmujoco file, canonical (realpath)
  std::string library_sha256;  // SHA-256 of that file's bytes (hex); empty if it cannot be read
};

// Found once per process (the loaded library does not change) and cached.
const EngineIdentity& RunningEngine();

}  // namespace mjf::runner

#endif  // MJFORMATION_RECORD_ENGINE_IDENTITY_HPP_
