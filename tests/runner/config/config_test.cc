// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Bad input in the experiment file: every case gets one clear message naming the file (and
// line/key) and is refused before any simulation starts.
#include "mjformation/config/config.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "error_of.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

using mjf::testing::HoverExperiment;
using mjf::testing::Parse;
using ::testing::AllOf;
using ::testing::HasSubstr;

using mjf::testing::ErrorOf;

TEST(ConfigTest, ValidFileParses) {
  ExperimentConfig c = Parse(HoverExperiment(3, 5.0));
  EXPECT_EQ(c.followers, 3);
  EXPECT_DOUBLE_EQ(c.duration, 5.0);
  EXPECT_EQ(c.leader.plugin, "hover");
  EXPECT_EQ(c.name, "hover");
}

// At the experiments' 45 m a vehicle's shadow is a dark blob on the ground that reads as one
// more object: snapshots are drawn without shadows unless a file asks for them.
TEST(ConfigTest, SnapshotsHaveNoShadowsByDefault) {
  EXPECT_FALSE(Parse(HoverExperiment()).render.shadows);
  EXPECT_TRUE(Parse(HoverExperiment() + "[render]\nshadows = true\n").render.shadows);
}

TEST(ConfigTest, MissingFile) {
  EXPECT_THAT(ErrorOf([] { LoadExperiment("/nonexistent/exp.toml"); }),
              AllOf(HasSubstr("/nonexistent/exp.toml"), HasSubstr("cannot open")));
}

TEST(ConfigTest, MalformedTomlNamesLine) {
  EXPECT_THAT(ErrorOf([] { Parse("[run]\nduration = 4.0\nseed = = 3\n", "bad.toml"); }),
              AllOf(HasSubstr("bad.toml:3:"), HasSubstr("TOML syntax error")));
}

TEST(ConfigTest, UnknownKeyNamesLineAndKey) {
  const std::string text = HoverExperiment() + "[render]\nwidht = 640\n";
  EXPECT_THAT(
      ErrorOf([&] { Parse(text, "typo.toml"); }),
      AllOf(HasSubstr("typo.toml:"), HasSubstr("[render] widht"), HasSubstr("unknown key")));
}

TEST(ConfigTest, UnknownSection) {
  EXPECT_THAT(ErrorOf([] { Parse("[runn]\nduration = 1.0\n"); }),
              AllOf(HasSubstr("exp.toml:1"), HasSubstr("[runn]"), HasSubstr("unknown section")));
}

TEST(ConfigTest, WrongTypeNamesKey) {
  EXPECT_THAT(ErrorOf([] { Parse("[run]\nduration = \"forty\"\n"); }),
              AllOf(HasSubstr("exp.toml:2"), HasSubstr("[run] duration"),
                    HasSubstr("expected a number, got a string")));
  EXPECT_THAT(ErrorOf([] { Parse("[vehicles]\nfollowers = 2.5\n"); }),
              AllOf(HasSubstr("[vehicles] followers"), HasSubstr("expected an integer")));
}

TEST(ConfigTest, OutOfRangeValues) {
  EXPECT_THAT(ErrorOf([] { Parse("[run]\nduration = -1.0\n"); }), HasSubstr("must be > 0"));
  EXPECT_THAT(ErrorOf([] { Parse("[run]\ntimestep = 0.5\n"); }), HasSubstr("[run] timestep"));
  EXPECT_THAT(ErrorOf([] { Parse("[vehicles]\nfollowers = 2\n[topology]\nleader_links = [3]\n"); }),
              AllOf(HasSubstr("[topology] leader_links"), HasSubstr("1..2")));
  EXPECT_THAT(
      ErrorOf([] {
        Parse("[vehicles]\nfollowers = 2\n[topology]\nleader_links = [1]\nedges = [[1, 7]]\n");
      }),
      AllOf(HasSubstr("exp.toml:5"), HasSubstr("[topology] edges")));
}

TEST(ConfigTest, OverridesApplyAndAreChecked) {
  const std::string dir = mjf::testing::TempDir("ovr");
  const std::string path = mjf::testing::WriteFile(dir + "/e.toml", HoverExperiment());
  ExperimentConfig c = LoadExperiment(path, {"run.duration=7.5", "formation.gain=2"});
  EXPECT_DOUBLE_EQ(c.duration, 7.5);
  EXPECT_EQ(c.formation.attributes.at("gain").text, "2");
  // A whole section can be replaced with an inline table.
  c = LoadExperiment(path, {"attitude={plugin=\"pointmass_direct\"}"});
  EXPECT_EQ(c.attitude.plugin, "pointmass_direct");
  EXPECT_TRUE(c.attitude.attributes.empty());
  EXPECT_THAT(ErrorOf([&] { LoadExperiment(path, {"attitude=3"}); }),
              HasSubstr("expected section.key=value"));
  EXPECT_THAT(ErrorOf([&] { LoadExperiment(path, {"run.duration"}); }),
              HasSubstr("expected section.key=value"));
  EXPECT_THAT(ErrorOf([&] { LoadExperiment(path, {"run.duration=fast"}); }), HasSubstr("not TOML"));
}

// One --set is one key: a line break would carry a second key in (and into config.toml's header
// comment as a live line). The message shows the break as an escape, on one line.
TEST(ConfigTest, AnOverrideWithALineBreakOrControlCharacterIsRefused) {
  const std::string dir = mjf::testing::TempDir("ovr_ctl");
  const std::string path = mjf::testing::WriteFile(dir + "/e.toml", HoverExperiment());
  EXPECT_THAT(ErrorOf([&] { LoadExperiment(path, {"run.seed=7\nduration=0.2"}); }),
              HasSubstr("override 'run.seed=7\\nduration=0.2': holds a line break"));
  EXPECT_THAT(ErrorOf([&] { LoadExperiment(path, {"run.seed\r=7"}); }),
              HasSubstr("override 'run.seed\\r=7': holds a line break"));
  EXPECT_THAT(ErrorOf([&] {
                LoadExperiment(path, {"run.name=\"a\x01"
                                      "b\""});
              }),
              HasSubstr("'run.name=\"a\\x01b\"': holds a line break or other control character"));
  // A TOML escape inside a string is text, not a control character.
  const ExperimentConfig c = LoadExperiment(path, {"formation.note=\"a\\tb\""});
  EXPECT_THAT(c.formation.attributes.at("note").text, HasSubstr("a\tb"));
}

// A `section={...}` override replaces the section's plain keys but keeps its sub-tables, so the
// README's `--set 'formation={plugin="consensus_linear"}'` keeps exp2's [formation.shape].
TEST(ConfigTest, ReplacingASectionKeepsItsSubTables) {
  const std::string dir = mjf::testing::TempDir("ovr_sub");
  std::string text =
      HoverExperiment() + "[formation.shape]\ntype = \"circle\"\nradius = 4.0\nomega = 0.5\n";
  const std::string formation = "[formation]\nplugin = \"hover\"\n";
  text.replace(text.find(formation), formation.size(), formation + "kp = 3.0\n");
  const std::string path = mjf::testing::WriteFile(dir + "/e.toml", text);
  const ExperimentConfig before = LoadExperiment(path);
  ASSERT_DOUBLE_EQ(before.shape.radius, 4.0);
  ASSERT_FALSE(before.formation.attributes.empty());
  const ExperimentConfig c = LoadExperiment(path, {"formation={plugin=\"consensus_linear\"}"});
  EXPECT_EQ(c.formation.plugin, "consensus_linear");
  EXPECT_TRUE(c.formation.attributes.empty());  // the old plugin's keys are gone
  EXPECT_DOUBLE_EQ(c.shape.radius, 4.0);        // the sub-table stays
  EXPECT_DOUBLE_EQ(c.shape.omega, 0.5);
  // A sub-table given in the new value replaces the old one.
  const ExperimentConfig d = LoadExperiment(
      path, {"formation={plugin=\"consensus_linear\", shape={type=\"circle\", radius=2.0}}"});
  EXPECT_DOUBLE_EQ(d.shape.radius, 2.0);
  EXPECT_NE(d.shape.omega, 0.5);
}

// 0 or no key means "the law's delta"; a negative band was read the same way and widened.
TEST(ConfigTest, NegativeReachingBandIsRefused) {
  EXPECT_THAT(ErrorOf([] { Parse(HoverExperiment(2, 2.0, "reaching_band = -0.5\n")); }),
              AllOf(HasSubstr("[run] reaching_band"), HasSubstr("must be >= 0")));
}

// A plugin folder that is not there is named, with where the file put it: a typo would otherwise
// surface only as a plugin "not found".
TEST(ConfigTest, APluginPathFolderThatIsNotThereIsRefused) {
  const std::string dir = mjf::testing::TempDir("plugin_path_missing");
  const std::string path = mjf::testing::WriteFile(
      dir + "/e.toml", HoverExperiment(2, 2.0, "plugin_path = [\"plugins\", \"nope\"]\n"));
  std::filesystem::create_directory(dir + "/plugins");
  EXPECT_THAT(ErrorOf([&] { LoadExperiment(path); }),
              HasSubstr("e.toml:4: [run] plugin_path: 'nope' is not a folder (" + dir + "/nope)"));
  std::filesystem::create_directory(dir + "/nope");
  EXPECT_EQ(LoadExperiment(path).plugin_path.back(), dir + "/nope");
}

// A folder opens as a stream that reads as empty: it was refused as "[formation] plugin: missing".
TEST(ConfigTest, FolderAsExperimentFileIsNamed) {
  const std::string dir = mjf::testing::TempDir("folder_exp");
  EXPECT_THAT(ErrorOf([&] { LoadExperiment(dir); }),
              AllOf(HasSubstr(dir), HasSubstr("is a folder, not an experiment file")));
}

TEST(ConfigTest, MissingModelFile) {
  EXPECT_THAT(ErrorOf([] { Parse("[vehicles]\nmodel = \"nothere.xml\"\n"); }),
              AllOf(HasSubstr("nothere.xml"), HasSubstr("not found")));
}

}  // namespace
}  // namespace mjf::runner
