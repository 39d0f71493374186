// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// An exported scene (`mjformation export`, runner/export) after a user edited it by hand:
// the scene is compiled by MuJoCo with the native plugins (libmjformation_mujoco.so, loaded
// once with mj_loadPluginLibrary as a user's program does), which read their <config> while the
// model compiles, build their hosts in mj_makeData and fly a few steps. The input is the scene's
// text; `@SOURCE@` in it stands for the source tree (the seeds were exported there: the vehicle
// model's path in <config key="vehicles">). A refusal is MuJoCo's compile error (nothing returned)
// or a MujocoError from the handlers the runner installs; anything else escaping is a finding.
#include <dirent.h>
#include <dlfcn.h>
#include <mujoco/mujoco.h>

#include <memory>
#include <string>

#include "fuzz_util.hpp"
#include "mjformation/sim/mujoco_errors.hpp"

namespace {

constexpr int kSteps = 5;  // enough for every instance's first ticks and a commit

mjf::fuzz::ScratchDir& Scratch() {
  static mjf::fuzz::ScratchDir dir;
  return dir;
}

std::string WithSource(std::string text) {
  const std::string token = "@SOURCE@";
  for (size_t at = text.find(token); at != std::string::npos; at = text.find(token, at)) {
    text.replace(at, token.size(), MJF_SOURCE_DIR);
    at += sizeof(MJF_SOURCE_DIR) - 1;
  }
  return text;
}

// Each host's plugin registry dlopen()s our plugin families and dlclose()s them when it goes;
// libFuzzer keeps the coverage counters of every instrumented library it saw, and reads them
// after each input, so a family unmapped between inputs would be read after it is gone. Opened
// once here with RTLD_NODELETE, the families stay mapped for the process's life.
void PinPluginFamilies() {
  DIR* dir = opendir(MJF_PLUGIN_BUILD_DIR);
  if (!dir) return;
  while (const dirent* entry = readdir(dir)) {
    const std::string name = entry->d_name;
    if (name.rfind("lib", 0) != 0 || name.size() < 4 || name.substr(name.size() - 3) != ".so") {
      continue;
    }
    dlopen((std::string(MJF_PLUGIN_BUILD_DIR) + "/" + name).c_str(), RTLD_NOW | RTLD_NODELETE);
  }
  closedir(dir);
}

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > 256 * 1024) return 0;  // an exported scene of a few vehicles is tens of kB
  static const bool installed = [] {
    mjf::runner::InstallMujocoHandlers();
    mj_loadPluginLibrary(MJF_NATIVE_PLUGIN_LIBRARY);
    PinPluginFamilies();
    return true;
  }();
  (void)installed;
  const std::string path = Scratch().Write("scene.xml", WithSource(mjf::fuzz::AsText(data, size)));
  try {
    char error[1024] = {0};
    std::unique_ptr<mjModel, ModelDeleter> m(
        mj_loadXML(path.c_str(), nullptr, error, sizeof(error)));
    if (!m) return 0;  // refused while compiling, with MuJoCo's message
    std::unique_ptr<mjData, DataDeleter> d(mj_makeData(m.get()));
    if (!d) return 0;  // a plugin refused in its init (the warning says why)
    for (int k = 0; k < kSteps; ++k) mj_step(m.get(), d.get());
  } catch (const mjf::runner::MujocoError&) {
    // An engine error (a plugin's refusal while stepping): the runner's clean error.
  }
  return 0;
}
