// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The runner tests' helpers (the library mjf_runner_testing): temporary files, a small
// experiment, parsing with the test plugins on the path, the command line in-process, PNGs.
#ifndef MJFORMATION_TESTS_RUNNER_TEST_UTIL_HPP_
#define MJFORMATION_TESTS_RUNNER_TEST_UTIL_HPP_

#include <png.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "mjformation/app/cli.hpp"
#include "mjformation/config/config.hpp"

namespace mjf::testing {

// A fresh temporary folder per call.
inline std::string TempDir(const std::string& tag) {
  std::string pattern = "/tmp/mjf_" + tag + "_XXXXXX";
  char* made = mkdtemp(pattern.data());
  return made ? std::string(made) : std::string("/tmp");
}

inline std::string WriteFile(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

inline std::string ReadFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

// A small experiment: leader + followers hovering, quadrotors, 2 s. Sections can be replaced by
// appending TOML after it (later keys in the same table would be duplicates, so tests build
// their own text from the pieces instead).
inline std::string HoverExperiment(int followers = 2, double duration = 2.0,
                                   const std::string& extra_run = "") {
  std::ostringstream t;
  t << "[run]\nname = \"hover\"\nduration = " << duration << "\n"
    << extra_run << "[vehicles]\nmodel = \"quadrotor\"\nfollowers = " << followers
    << "\naltitude = 2.0\nleader_start = [0.0, 0.0]\n"
    << "[topology]\nleader_links = [1]\n"
    << "[leader]\nplugin = \"hover\"\n[formation]\nplugin = \"hover\"\n"
    << "[attitude]\nplugin = \"pd_cascade\"\n";
  return t.str();
}

// Parses `text` as if it were the file `name` in a temporary folder, with the test plugins on
// the search path.
inline runner::ExperimentConfig Parse(const std::string& text,
                                      const std::string& name = "exp.toml") {
  const std::string dir = TempDir("cfg");
  runner::ExperimentConfig c = runner::LoadExperiment(WriteFile(dir + "/" + name, text));
  c.plugin_path.push_back(MJF_TEST_PLUGIN_DIR);
  return c;
}

// Runs `mjformation args...` in-process, as main() does; returns the exit code.
inline int Cli(std::vector<std::string> args) {
  args.insert(args.begin(), "mjformation");
  std::vector<const char*> argv;
  for (const auto& a : args) argv.push_back(a.c_str());
  return runner::RunCommandLine(static_cast<int>(argv.size()), argv.data());
}

// Reads a PNG as 8-bit RGB (libpng's simplified API); empty when it cannot be read.
inline std::vector<unsigned char> ReadPng(const std::string& path, int* width, int* height) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  std::vector<unsigned char> pixels;
  if (!png_image_begin_read_from_file(&image, path.c_str())) return pixels;
  image.format = PNG_FORMAT_RGB;
  pixels.resize(PNG_IMAGE_SIZE(image));
  png_image_finish_read(&image, nullptr, pixels.data(), 0, nullptr);
  *width = static_cast<int>(image.width);
  *height = static_cast<int>(image.height);
  return pixels;
}

}  // namespace mjf::testing

#endif  // MJFORMATION_TESTS_RUNNER_TEST_UTIL_HPP_
