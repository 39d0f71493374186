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

// Where export lists what it wrote into a folder (SceneBundle::kManifest).
constexpr char kManifest[] = "mjformation_export.txt";

// The message of the ExportError `export_to` throws ("" when it throws none).
template <typename F>
std::string ExportRefusal(F export_to) {
  try {
    export_to();
  } catch (const ExportError& e) {
    return e.what();
  }
  return "";
}

// -o naming a file is refused as a file, with or without --overwrite, and the file is kept.
TEST(ExportOptions, AFileIsRefusedAsNotAFolder) {
  const std::string experiment = WriteFile(TempDir("export") + "/e.toml", HoverExperiment());
  const std::string file = WriteFile(TempDir("export_file") + "/plain.txt", "mine");
  for (const bool overwrite : {false, true}) {
    ExportOptions options;
    options.overwrite = overwrite;
    const std::string e = ExportRefusal([&] { ExportExperiment(experiment, file, options); });
    EXPECT_NE(e.find(file + ": is a file, not a folder"), std::string::npos) << e;
  }
  EXPECT_EQ(ReadFile(file), "mine");
}

// --overwrite replaces what an export wrote (its manifest says so) and refuses a scene.xml, or
// a manifest, of the user's, naming it, before anything is written.
TEST(ExportOptions, OverwriteRefusesAScenesXmlExportDidNotWrite) {
  const std::string experiment = WriteFile(TempDir("export") + "/e.toml", HoverExperiment());
  ExportOptions overwrite;
  overwrite.overwrite = true;
  const std::string users = TempDir("export_users_scene");
  WriteFile(users + "/scene.xml", "<mujoco/>  <!-- mine -->");
  std::string e = ExportRefusal([&] { ExportExperiment(experiment, users, overwrite); });
  EXPECT_NE(e.find(users + "/scene.xml: exists and was not written by export"), std::string::npos)
      << e;
  EXPECT_EQ(ReadFile(users + "/scene.xml"), "<mujoco/>  <!-- mine -->");
  EXPECT_FALSE(fs::exists(users + "/" + kManifest));

  const std::string listed = TempDir("export_users_list");
  WriteFile(listed + "/" + kManifest, "scene.xml\n");
  WriteFile(listed + "/scene.xml", "<mujoco/>  <!-- mine -->");
  // A manifest without export's header line is the user's: it vouches for nothing.
  e = ExportRefusal([&] { ExportExperiment(experiment, listed, overwrite); });
  EXPECT_NE(e.find(listed + "/scene.xml: exists and was not written by export"), std::string::npos)
      << e;
  EXPECT_EQ(ReadFile(listed + "/scene.xml"), "<mujoco/>  <!-- mine -->");
  EXPECT_EQ(ReadFile(listed + "/" + kManifest), "scene.xml\n");

  const std::string exported = TempDir("export_again");
  ExportExperiment(experiment, exported);
  ExportExperiment(experiment, exported, overwrite);  // its own scene.xml: replaced
  EXPECT_NE(ReadFile(exported + "/scene.xml").find("<mujoco"), std::string::npos);
}

}  // namespace
}  // namespace mjf::runner
