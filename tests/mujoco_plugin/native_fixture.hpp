// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// What the tests of the native MuJoCo plugins share: a scratch folder per test, the plugin
// library loaded once into MuJoCo, and an experiment of experiments/ made ready for export.
#ifndef MJFORMATION_TESTS_MUJOCO_PLUGIN_NATIVE_FIXTURE_HPP_
#define MJFORMATION_TESTS_MUJOCO_PLUGIN_NATIVE_FIXTURE_HPP_

#include <mujoco/mujoco.h>
#include <unistd.h>

#include <filesystem>
#include <regex>
#include <string>

#include "test_util.hpp"

namespace mjf::testing {

// A scratch folder per test, removed at the end.
class Scratch {
 public:
  explicit Scratch(const std::string& name)
      : path_(std::filesystem::temp_directory_path() /
              ("mjf_native_" + name + "_" + std::to_string(getpid()))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~Scratch() { std::filesystem::remove_all(path_); }
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;
  std::string operator/(const std::string& leaf) const { return (path_ / leaf).string(); }

 private:
  std::filesystem::path path_;
};

// libmjformation_mujoco.so into MuJoCo's plugin table, once per process (a second load would
// register the plugins twice).
inline void LoadNativePluginsOnce() {
  static const bool loaded = [] {
    mj_loadPluginLibrary(MJF_NATIVE_PLUGIN_LIBRARY);
    return true;
  }();
  (void)loaded;
}

// experiments/<experiment> without [render] (the runner would render; the export notes it),
// flying [vehicles] model = `model` instead of the quadrotor when one is given.
inline std::string NativeExperimentText(const std::string& experiment,
                                        const std::string& model = "") {
  std::string text = ReadFile(std::string(MJF_SOURCE_DIR) + "/experiments/" + experiment);
  const size_t render = text.find("\n[render]");
  if (render != std::string::npos) {
    // Up to the next section ([sensors] may follow it).
    const size_t next = text.find("\n[", render + 1);
    text.erase(render, next == std::string::npos ? std::string::npos : next - render);
  }
  if (!model.empty()) {
    text = std::regex_replace(text, std::regex("\nmodel = \"quadrotor\""),
                              "\nmodel = \"" + model + "\"");
  }
  return text;
}

// examples/vehicles/midge/exp2_midge.toml: a foreign model mapped onto the vehicle contract
// ([vehicles] body, thrust and moments: a thrust-and-moment vehicle), its model named by its
// absolute path, without [render] and [safety] (they watch the flight; the native face carries
// neither).
inline std::string MidgeExperimentText() {
  const std::string example = std::string(MJF_SOURCE_DIR) + "/examples/vehicles/midge/";
  std::string text = ReadFile(example + "exp2_midge.toml");
  text = std::regex_replace(text, std::regex("\nmodel = \"midge.xml\""),
                            "\nmodel = \"" + example + "midge.xml\"");
  for (const char* section : {"\n[render]", "\n[safety]"}) {
    const size_t at = text.find(section);
    if (at != std::string::npos) text.erase(at, text.find("\n[", at + 1) - at);
  }
  return text;
}

// The benchmark's b13 (per-agent execution over lossy links) with Jacobi's exchange rounds
// carried over its late links, with a round timeout: the letters in flight, the exchanges
// waiting for them and their counts are state too. Empty when b13 no longer has the sections.
inline std::string RoundsOverTheLinksText() {
  std::string text = NativeExperimentText("benchmark/b13_lossy_network.toml");
  if (text.find("\n[execution]") == std::string::npos ||
      text.find("\n[network]") == std::string::npos) {
    return "";
  }
  text = std::regex_replace(text, std::regex("\n\\[execution\\]"),
                            "\n[execution]\ncoupling = \"jacobi\"\njacobi_rounds = 3");
  return std::regex_replace(text, std::regex("\n\\[network\\]"),
                            "\n[network]\nrounds = \"over_links\"\nround_timeout = 0.02");
}

}  // namespace mjf::testing

#endif  // MJFORMATION_TESTS_MUJOCO_PLUGIN_NATIVE_FIXTURE_HPP_
