// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Bad input: every case gets one clear message naming the file (and line/key) and is refused
// before any simulation starts.
#include "mjformation/runner/config.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mjformation/runner/plugin_host.hpp"
#include "mjformation/runner/scene.hpp"
#include "mjformation/runner/simulation.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

using mjf::testing::HoverExperiment;
using mjf::testing::Parse;
using ::testing::AllOf;
using ::testing::HasSubstr;

// The message of the exception `statement` throws (empty if none).
template <typename F>
std::string ErrorOf(F statement) {
  try {
    statement();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

TEST(ConfigTest, ValidFileParses) {
  ExperimentConfig c = Parse(HoverExperiment(3, 5.0));
  EXPECT_EQ(c.followers, 3);
  EXPECT_DOUBLE_EQ(c.duration, 5.0);
  EXPECT_EQ(c.leader.plugin, "hover");
  EXPECT_EQ(c.name, "hover");
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

TEST(ConfigTest, MissingModelFile) {
  EXPECT_THAT(ErrorOf([] { Parse("[vehicles]\nmodel = \"nothere.xml\"\n"); }),
              AllOf(HasSubstr("nothere.xml"), HasSubstr("not found")));
}

// --- Checks that need the plugins and the model: still before the first step. ---

TEST(SetupErrorTest, UnknownPluginListsAvailable) {
  std::string text = HoverExperiment();
  text.replace(text.find("plugin = \"pd_cascade\""), 21, "plugin = \"pd_cascad\"");
  ExperimentConfig c = Parse(text, "p.toml");
  EXPECT_THAT(ErrorOf([&] { Simulation sim(c); }),
              AllOf(HasSubstr("p.toml:"), HasSubstr("[attitude]"), HasSubstr("'pd_cascad'"),
                    HasSubstr("available:"), HasSubstr("pd_cascade")));
}

TEST(SetupErrorTest, AbiMismatchIsNamed) {
  std::string text = HoverExperiment();
  text.replace(text.find("[leader]\nplugin = \"hover\""), 25, "[leader]\nplugin = \"future_abi\"");
  ExperimentConfig c = Parse(text);
  EXPECT_THAT(ErrorOf([&] { Simulation sim(c); }),
              AllOf(HasSubstr("future_abi"), HasSubstr("libmjf_test_badabi.so"),
                    HasSubstr("ABI 99"), HasSubstr("speaks ABI 2")));
}

TEST(SetupErrorTest, MissingRequiredAttribute) {
  std::string text = HoverExperiment();
  text.replace(text.find("[leader]\nplugin = \"hover\""), 25,
               "[leader]\nplugin = \"test_required\"");
  ExperimentConfig c = Parse(text);
  EXPECT_THAT(ErrorOf([&] { Simulation sim(c); }),
              AllOf(HasSubstr("[leader] value"), HasSubstr("requires attribute 'value'")));
}

TEST(SetupErrorTest, UnknownAttributeListsDeclared) {
  std::string text = HoverExperiment();
  text += "";
  text.replace(text.find("plugin = \"pd_cascade\""), 21, "plugin = \"pd_cascade\"\nkp_attt = 3.0");
  ExperimentConfig c = Parse(text);
  EXPECT_THAT(ErrorOf([&] { Simulation sim(c); }),
              AllOf(HasSubstr("[attitude] kp_attt"), HasSubstr("no attribute 'kp_attt'"),
                    HasSubstr("its attributes:")));
}

// A gain the geometric attitude plugin refuses (att_bw above rate_bw / 2 breaks the cascade):
// FILE:LINE: [attitude], the key and the reason, before the first step.
TEST(SetupErrorTest, GeometricBadGainNamesFileSectionAndKey) {
  std::string text = HoverExperiment();
  text.replace(text.find("plugin = \"pd_cascade\""), 21, "plugin = \"geometric\"\natt_bw = 50.0");
  ExperimentConfig c = Parse(text, "p.toml");
  EXPECT_THAT(ErrorOf([&] { Simulation sim(c); }),
              AllOf(HasSubstr("p.toml:"), HasSubstr("[attitude]"), HasSubstr("'geometric'"),
                    HasSubstr("att_bw"), HasSubstr("cascade separation")));
}

TEST(SetupErrorTest, PluginOfWrongKind) {
  std::string text = HoverExperiment();
  text.replace(text.find("[leader]\nplugin = \"hover\""), 25, "[leader]\nplugin = \"pd_cascade\"");
  EXPECT_THAT(ErrorOf([&] { Simulation sim(Parse(text)); }),
              AllOf(HasSubstr("[leader]"), HasSubstr("needs a guidance plugin")));
}

TEST(SetupErrorTest, MjcfThatFailsToLoad) {
  const std::string dir = mjf::testing::TempDir("mjcf");
  mjf::testing::WriteFile(dir + "/broken.xml",
                          "<mujoco><worldbody><body name=\"vehicle\"><geom type=\"sphere\" "
                          "size=\"-1\"/><freejoint/></body></worldbody></mujoco>");
  std::string text = HoverExperiment();
  text.replace(text.find("model = \"quadrotor\""), 19, "model = \"broken.xml\"");
  ExperimentConfig c = mjf::runner::LoadExperiment(mjf::testing::WriteFile(dir + "/e.toml", text));
  EXPECT_THAT(ErrorOf([&] { Simulation sim(c); }),
              AllOf(HasSubstr("broken.xml"), HasSubstr("MuJoCo cannot load")));
  mjf::testing::WriteFile(dir + "/notxml.xml", "<mujoco><worldbody>");
  text.replace(text.find("broken.xml"), 10, "notxml.xml");
  c = mjf::runner::LoadExperiment(mjf::testing::WriteFile(dir + "/e.toml", text));
  EXPECT_THAT(ErrorOf([&] { Simulation sim(c); }),
              AllOf(HasSubstr("notxml.xml:"), HasSubstr("cannot read the vehicle model")));
}

TEST(SetupErrorTest, VehicleWithoutSensors) {
  const std::string dir = mjf::testing::TempDir("nosensor");
  mjf::testing::WriteFile(
      dir + "/bare.xml",
      "<mujoco><worldbody><body name=\"vehicle\"><freejoint/><geom type=\"sphere\" size=\"0.1\"/>"
      "<site name=\"rotor0\"/><site name=\"rotor1\"/><site name=\"rotor2\"/><site name=\"rotor3\"/>"
      "</body></worldbody><actuator><general name=\"rotor0\" site=\"rotor0\" gear=\"0 0 1 0 0 0\"/>"
      "<general name=\"rotor1\" site=\"rotor1\" gear=\"0 0 1 0 0 0\"/><general name=\"rotor2\" "
      "site=\"rotor2\" gear=\"0 0 1 0 0 0\"/><general name=\"rotor3\" site=\"rotor3\" "
      "gear=\"0 0 1 0 0 0\"/></actuator></mujoco>");
  std::string text = HoverExperiment();
  text.replace(text.find("model = \"quadrotor\""), 19, "model = \"bare.xml\"");
  ExperimentConfig c = mjf::runner::LoadExperiment(mjf::testing::WriteFile(dir + "/e.toml", text));
  EXPECT_THAT(ErrorOf([&] { Simulation sim(c); }),
              AllOf(HasSubstr("bare.xml"), HasSubstr("needs a sensor named 'pos'")));
}

TEST(SetupErrorTest, VehicleWithoutThePluginsActuators) {
  std::string text = HoverExperiment();
  text.replace(text.find("model = \"quadrotor\""), 19, "model = \"pointmass\"");
  EXPECT_THAT(ErrorOf([&] { Simulation sim(Parse(text)); }),
              AllOf(HasSubstr("pointmass.xml"), HasSubstr("'pd_cascade'"), HasSubstr("'rotor0'"),
                    HasSubstr("lacks")));
}

TEST(SetupErrorTest, TopologyWithoutSpanningTree) {
  std::string text =
      "[vehicles]\nfollowers = 4\n[topology]\nleader_links = [1]\nedges = [[1, 2], [4, 3]]\n"
      "[leader]\nplugin = \"circle\"\n[formation]\nplugin = \"smc_discrete\"\n"
      "[formation.shape]\ntype = \"circle\"\n";
  EXPECT_THAT(ErrorOf([&] { Simulation sim(Parse(text, "tree.toml")); }),
              AllOf(HasSubstr("tree.toml"), HasSubstr("[topology]"), HasSubstr("spanning tree"),
                    HasSubstr("3, 4")));
}

TEST(SetupErrorTest, ParametersBreakingTheoremTwo) {
  std::string text =
      "[vehicles]\nfollowers = 2\n[topology]\nleader_links = [1]\nedges = [[1, 2]]\n"
      "[leader]\nplugin = \"circle\"\n[formation]\nplugin = \"smc_discrete\"\nperiod = 0.05\n"
      "q = 30.0\n[formation.shape]\ntype = \"circle\"\n";
  EXPECT_THAT(ErrorOf([&] { Simulation sim(Parse(text, "q.toml")); }),
              AllOf(HasSubstr("q.toml"), HasSubstr("[formation]"), HasSubstr("smc_discrete"),
                    HasSubstr("1 - q*T")));
}

}  // namespace
}  // namespace mjf::runner
