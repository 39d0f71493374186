// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The plugin wiring without physics: real plugins from the build tree, vehicles described by
// hand (as BindVehicles would), no MuJoCo model.
#include "mjformation/control/control_wiring.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "mjformation/config/config.hpp"
#include "mjformation/config/paths.hpp"
#include "mjformation/control/errors.hpp"
#include "mjformation/formation/shape.hpp"
#include "point_mass_info.hpp"

namespace mjf::runner {
namespace {

using ::testing::HasSubstr;

using mjf::testing::PointMassInfo;

ExperimentConfig Exp2(std::vector<std::string> overrides) {
  overrides.insert(overrides.begin(),
                   {"vehicles.model=\"pointmass\"", "attitude={plugin=\"pointmass_direct\"}"});
  return LoadExperiment(std::string(MJF_SOURCE_DIR) + "/experiments/exp2.toml", overrides);
}

class ControlWiringTest : public ::testing::Test {
 protected:
  // The wiring of `config` over identical point masses placed at x = 2 i, y = -i.
  ControlWiring Wire(const ExperimentConfig& config) {
    config_ = config;
    registry_ = std::make_unique<PluginRegistry>(PluginSearchPath(config_.plugin_path));
    VehicleContexts vehicles;
    for (int i = 0; i <= config_.followers; ++i) {
      vehicles.info.push_back(&vehicle_.info);
      vehicles.initial_positions.push_back({2.0 * i, -1.0 * i, 0.0});
    }
    return ControlWiring(config_, *registry_, std::move(vehicles));
  }
  const LoadedPlugin& Attitude() const {
    return FindPlugin(*registry_, config_, config_.attitude, {MJF_KIND_ATTITUDE}, "attitude");
  }

  ExperimentConfig config_;
  std::unique_ptr<PluginRegistry> registry_;
  PointMassInfo vehicle_;
};

// passthrough (named, or the default of an [estimator] that names no plugin) has no attributes:
// a key given to it is refused at its --set origin, as kf_ins refuses a key it does not know,
// instead of being dropped unread.
TEST_F(ControlWiringTest, PassthroughRefusesAnyAttributeAtItsOrigin) {
  for (const std::string set :
       {"estimator={plugin=\"passthrough\", gate_sigma=5.0}", "estimator={gate_sigma=-5.0}"}) {
    ControlWiring wiring = Wire(Exp2({set}));
    try {
      wiring.MakeSensors();
      ADD_FAILURE() << set << " was accepted";
    } catch (const PluginError& e) {
      EXPECT_THAT(e.what(), HasSubstr("--set " + set +
                                      ": [estimator] gate_sigma: plugin 'passthrough' has no "
                                      "attribute 'gate_sigma' (its attributes: none)"));
    }
  }
  ControlWiring plain = Wire(Exp2({"estimator={plugin=\"passthrough\"}"}));
  EXPECT_NE(plain.MakeSensors(), nullptr);
}

TEST_F(ControlWiringTest, CentralModeWiresOneFormationLawAndAnAttitudeInstancePerVehicle) {
  ControlWiring wiring = Wire(Exp2({}));
  EXPECT_EQ(wiring.MakeChannel(), nullptr);
  ControlPlugins plugins = wiring.CreatePlugins(Attitude(), nullptr);
  ASSERT_NE(plugins.leader, nullptr);
  ASSERT_NE(plugins.formation, nullptr);
  EXPECT_TRUE(plugins.formation_agents.empty());
  EXPECT_TRUE(plugins.follower_guidance.empty());
  EXPECT_EQ(plugins.attitude.size(), 7u);
  ASSERT_NE(wiring.shape(), nullptr);
}

TEST_F(ControlWiringTest, PerAgentModeWiresOneAgentPerFollowerOverTheChannel) {
  ControlWiring wiring = Wire(Exp2({"execution={mode=\"per_agent\"}"}));
  std::unique_ptr<AgentChannel> channel = wiring.MakeChannel();
  ASSERT_NE(channel, nullptr);
  ControlPlugins plugins = wiring.CreatePlugins(Attitude(), channel.get());
  EXPECT_EQ(plugins.formation, nullptr);
  EXPECT_EQ(plugins.formation_agents.size(), 6u);
}

TEST_F(ControlWiringTest, InitialSetpointsHoldEachStartAtTheAltitude) {
  ControlWiring wiring = Wire(Exp2({}));
  const std::vector<mjfSetpoint> setpoints = wiring.InitialSetpoints();
  ASSERT_EQ(setpoints.size(), 7u);
  for (int i = 0; i < 7; ++i) {
    EXPECT_EQ(setpoints[i].pos[0], 2.0 * i);
    EXPECT_EQ(setpoints[i].pos[1], -1.0 * i);
    EXPECT_EQ(setpoints[i].pos[2], 5.0);
    EXPECT_TRUE(std::isnan(setpoints[i].sliding[0]));
  }
}

TEST_F(ControlWiringTest, AFormationLawWithoutASpanningTreeIsRefusedNamingTheTopology) {
  // Follower 3 hears nobody: no directed spanning tree rooted at the leader (Assumption 2).
  ControlWiring wiring = Wire(Exp2({"vehicles.followers=3", "vehicles.follower_start=[]",
                                    "topology={leader_links=[1], edges=[[1,2]]}"}));
  try {
    wiring.CreatePlugins(Attitude(), nullptr);
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("exp2.toml"));
    EXPECT_THAT(e.what(), HasSubstr("[topology]"));
  }
}

TEST_F(ControlWiringTest, AnAttitudePluginAsTheFormationLawIsRefusedNamingItsKind) {
  ControlWiring wiring = Wire(Exp2({"formation={plugin=\"pointmass_direct\"}"}));
  try {
    wiring.CreatePlugins(Attitude(), nullptr);
    FAIL() << "no error";
  } catch (const PluginError& e) {
    EXPECT_THAT(e.what(), HasSubstr("[formation] plugin: 'pointmass_direct' is a"));
    EXPECT_THAT(e.what(), HasSubstr("attitude plugin"));
  }
}

}  // namespace
}  // namespace mjf::runner
