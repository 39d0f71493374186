// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Bad input found while a simulation is set up (plugins, MJCF, topology, parameters): every case
// gets one clear message naming the file (and line/key) and is refused before anything runs.
#include "mjformation/sim/simulation.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mjformation/control/plugin_host.hpp"
#include "mjformation/config/config.hpp"
#include "mjformation/scene/scene.hpp"
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
