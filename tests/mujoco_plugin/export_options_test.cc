// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// `mjformation export` reads the experiment as `run` does (--set, --plugin-path), writes every
// path resolved so the scene flies the same files from any working folder, and refuses what a
// scene cannot do (stop at a safety event) by the key's name.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "mjformation/export/export.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

namespace fs = std::filesystem;
using testing::HoverExperiment;
using testing::ReadFile;
using testing::TempDir;
using testing::WriteFile;

std::string SceneOf(const std::string& experiment, const ExportOptions& options) {
  std::vector<std::string> notes;
  return ExportedSceneXml(experiment, options, &notes);
}

TEST(ExportOptions, SetReachesTheScene) {
  const std::string file = WriteFile(TempDir("export") + "/e.toml", HoverExperiment());
  ExportOptions options;
  EXPECT_EQ(SceneOf(file, options).find("0.375"), std::string::npos);
  options.overrides = {"vehicles.altitude=2.375"};
  EXPECT_NE(SceneOf(file, options).find("altitude = 2.375"), std::string::npos);
}

TEST(ExportOptions, BadSetIsRefusedNamingIt) {
  const std::string file = WriteFile(TempDir("export") + "/e.toml", HoverExperiment());
  ExportOptions options;
  options.overrides = {"vehicles.altitude=[oops"};
  try {
    SceneOf(file, options);
    FAIL() << "a value that is not TOML was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("vehicles.altitude=[oops"), std::string::npos) << e.what();
  }
}

TEST(ExportOptions, PluginPathIsCarried) {
  const std::string file = WriteFile(TempDir("export") + "/e.toml", HoverExperiment());
  const std::string folder = TempDir("export_plugins");
  ExportOptions options;
  options.plugin_path = {folder};
  EXPECT_NE(SceneOf(file, options).find("plugin_path = [&quot;" + folder + "&quot;]"),
            std::string::npos);
}

TEST(ExportOptions, StopOnIsRefusedUnlessEmptied) {
  const std::string file =
      WriteFile(TempDir("export") + "/e.toml", HoverExperiment(2, 2.0, "stop_on = [\"flip\"]\n"));
  try {
    SceneOf(file, {});
    FAIL() << "stop_on was exported though nothing stops MuJoCo's stepping";
  } catch (const ExportError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(file + ":4: [run] stop_on"), std::string::npos) << message;
    EXPECT_NE(message.find("--set 'run.stop_on=[]'"), std::string::npos) << message;
  }
  ExportOptions emptied;
  emptied.overrides = {"run.stop_on=[]"};
  EXPECT_NO_THROW(SceneOf(file, emptied));
}

// The leader's recorded path is named relative to the experiment file; the scene must name the
// same file wherever it is loaded from.
TEST(ExportOptions, DataFilesAreWrittenResolved) {
  const std::string experiment =
      std::string(MJF_SOURCE_DIR) + "/experiments/leaders/exp2_trajectory.toml";
  ExportOptions options;
  options.overrides = {"run.duration=1.0", "run.metric_window=[0.5,1.0]"};
  const std::string xml = SceneOf(experiment, options);
  const std::string csv = fs::weakly_canonical(std::string(MJF_SOURCE_DIR) +
                                               "/experiments/leaders/data/recorded_path.csv")
                              .string();
  const size_t at = xml.find("recorded_path.csv");
  ASSERT_NE(at, std::string::npos);
  const size_t open = xml.rfind("&quot;", at);
  const std::string named = xml.substr(open + 6, at + 17 - open - 6);
  EXPECT_TRUE(fs::path(named).is_absolute()) << named;
  EXPECT_EQ(fs::weakly_canonical(named).string(), csv);
}

}  // namespace
}  // namespace mjf::runner
