// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// runner/config/src/paths.cc: relative paths, the vehicle model look-up and the plugin search path.
#include "mjformation/config/paths.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>

#include "error_of.hpp"
#include "mjformation/config/config_error.hpp"
#include "mjformation/config/experiment.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

using mjf::testing::TempDir;
using mjf::testing::WriteFile;
using ::testing::AllOf;
using ::testing::EndsWith;
using ::testing::HasSubstr;

std::string ConfigErrorOf(const std::string& name, const std::string& experiment) {
  return mjf::testing::ErrorOf<ConfigError>([&] { ResolveModel(name, experiment); },
                                            "(nothing thrown)");
}

// Sets an environment variable for one scope, restoring the previous value.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old, had_ = true;
    if (value) {
      setenv(name, value, 1);
    } else {
      unsetenv(name);
    }
  }
  ~ScopedEnv() {
    if (had_) {
      setenv(name_, old_.c_str(), 1);
    } else {
      unsetenv(name_);
    }
  }

 private:
  const char* name_;
  std::string old_;
  bool had_ = false;
};

TEST(PathsTest, ResolveRelative) {
  EXPECT_EQ(ResolveRelative("/abs/model.xml", "/exp/e.toml"), "/abs/model.xml");
  EXPECT_EQ(ResolveRelative("models/q.xml", "/exp/dir/e.toml"), "/exp/dir/models/q.xml");
  EXPECT_EQ(ResolveRelative("../q.xml", "rel/e.toml"), "rel/../q.xml");
  EXPECT_EQ(ResolveRelative("q.xml", "e.toml"), "q.xml");  // the file has no folder
  EXPECT_EQ(ResolveRelative("", "/exp/e.toml"), "");
}

TEST(PathsTest, FilesAndDirectories) {
  const std::string dir = TempDir("paths_kind");
  const std::string file = WriteFile(dir + "/f.txt", "x");
  EXPECT_TRUE(IsDirectory(dir));
  EXPECT_FALSE(IsFile(dir));
  EXPECT_TRUE(IsFile(file));
  EXPECT_FALSE(IsDirectory(file));
  EXPECT_FALSE(IsFile(dir + "/absent"));
  EXPECT_FALSE(IsDirectory(dir + "/absent"));
}

TEST(PathsTest, ExecutableDirIsTheFolderOfThisTestBinary) {
  // This test executable is built into the build tree's tests/runner/config folder.
  EXPECT_TRUE(std::filesystem::equivalent(ExecutableDir(),
                                          std::string(MJF_BINARY_DIR) + "/tests/runner/config"))
      << ExecutableDir();
}

TEST(PathsTest, ABareModelNameIsFoundInTheModelFolders) {
  ScopedEnv env("MJF_MJCF_DIR", nullptr);
  const std::string found = ResolveModel("quadrotor", "/nowhere/exp.toml");
  EXPECT_THAT(found, EndsWith("/quadrotor.xml"));
  EXPECT_TRUE(IsFile(found));
}

TEST(PathsTest, MjfMjcfDirComesFirst) {
  const std::string dir = TempDir("paths_mjcf");
  WriteFile(dir + "/quadrotor.xml", "<mujoco/>");
  ScopedEnv env("MJF_MJCF_DIR", dir.c_str());
  EXPECT_EQ(ResolveModel("quadrotor", "/nowhere/exp.toml"), dir + "/quadrotor.xml");
}

TEST(PathsTest, APathIsRelativeToTheExperimentFile) {
  const std::string dir = TempDir("paths_rel");
  std::filesystem::create_directories(dir + "/models");
  WriteFile(dir + "/models/mine.xml", "<mujoco/>");
  WriteFile(dir + "/flat.xml", "<mujoco/>");
  EXPECT_EQ(ResolveModel("models/mine.xml", dir + "/exp.toml"), dir + "/models/mine.xml");
  // A name ending in .xml is a path too, not a look-up in the model folders.
  EXPECT_EQ(ResolveModel("flat.xml", dir + "/exp.toml"), dir + "/flat.xml");
}

TEST(PathsTest, MissingModelsNameWhereTheyWereLookedFor) {
  const std::string dir = TempDir("paths_missing");
  EXPECT_THAT(ConfigErrorOf("models/none.xml", dir + "/exp.toml"),
              AllOf(HasSubstr(dir + "/exp.toml: model file 'models/none.xml' not found"),
                    HasSubstr("looked at " + dir + "/models/none.xml")));
  ScopedEnv env("MJF_MJCF_DIR", dir.c_str());
  EXPECT_THAT(
      ConfigErrorOf("nosuchvehicle", dir + "/exp.toml"),
      AllOf(HasSubstr("model 'nosuchvehicle' not found"), HasSubstr(dir + "/nosuchvehicle.xml"),
            HasSubstr(std::string(MJF_SOURCE_DIR) + "/mjcf/nosuchvehicle.xml")));
}

TEST(PathsTest, PluginSearchPathOrder) {
  ScopedEnv env("MJF_PLUGIN_PATH", "/env/a::/env/b:");  // empty entries are skipped
  const std::vector<std::string> path = PluginSearchPath({"/extra/1", "/extra/2"});
  ASSERT_EQ(path.size(), 5u);
  EXPECT_EQ(path[0], "/extra/1");
  EXPECT_EQ(path[1], "/extra/2");
  EXPECT_EQ(path[2], "/env/a");
  EXPECT_EQ(path[3], "/env/b");
  // A test runs from the build tree: the build tree's plugin folder, where the project's own
  // plugins are, and no install folder (an installed runner: tests/runner/cmake_package.sh).
  EXPECT_EQ(InstalledPrefix(), "");
  EXPECT_TRUE(IsDirectory(path[4])) << path[4];
  EXPECT_EQ(path[4].find(ExecutableDir()), std::string::npos) << path[4];
}

TEST(PathsTest, PluginSearchPathWithoutEnvironment) {
  ScopedEnv env("MJF_PLUGIN_PATH", nullptr);
  const std::vector<std::string> path = PluginSearchPath({});
  ASSERT_EQ(path.size(), 1u);
  EXPECT_TRUE(IsDirectory(path[0])) << path[0];
}

}  // namespace
}  // namespace mjf::runner
