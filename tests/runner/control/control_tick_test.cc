// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The control tick driven alone, with no MuJoCo model or data: plain state arrays in, controls
// out (as PX4's PositionControl is tested without its module). Real plugins are loaded from the
// build tree; the sensor stage is swapped for test ones.
#include "mjformation/control/control_tick.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <map>

#include "mjformation/config/paths.hpp"
#include "mjformation/control/errors.hpp"
#include "point_mass_info.hpp"

namespace mjf::runner {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

using PointMass = mjf::testing::PointMassInfo;
constexpr double kMass = PointMass::kMass, kGravity = PointMass::kGravity;

PluginSection Section(const std::string& name, const std::string& plugin,
                      std::map<std::string, AttributeValue> attributes = {}) {
  PluginSection s;
  s.section = name;
  s.plugin = plugin;
  s.attributes = std::move(attributes);
  return s;
}

// Sees every vehicle `bias` m further along x than it is.
class BiasedSensors final : public SensorStage {
 public:
  explicit BiasedSensors(double bias) : bias_(bias) {}
  void Measure(int64_t, double, const std::vector<mjfVehicleState>& truth,
               std::vector<mjfVehicleState>* measured) override {
    *measured = truth;
    for (auto& s : *measured) s.pos[0] += bias_;
  }

 private:
  double bias_;
};

class ControlTickTest : public ::testing::Test {
 protected:
  static constexpr int kVehicles = 3;  // leader + 2 followers hovering
  ControlTickTest()
      : registry_(PluginSearchPath({MJF_TEST_PLUGIN_DIR})),
        positions_{{{0, 0, 5}, {2, 0, 5}, {0, 2, 5}}} {}

  // leader: `leader_plugin`, followers: hover, attitude: pointmass_direct.
  std::unique_ptr<ControlTick> MakeTick(std::unique_ptr<SensorStage> sensors,
                                        const PluginSection& leader) {
    ControlPlugins p;
    p.leader = Create(leader, 0);
    for (int i = 1; i < kVehicles; ++i)
      p.follower_guidance.push_back(Create(Section("formation", "hover"), i));
    for (int i = 0; i < kVehicles; ++i)
      p.attitude.push_back(Create(Section("attitude", "pointmass_direct"), i));
    std::vector<mjfSetpoint> setpoints(kVehicles);
    for (int i = 0; i < kVehicles; ++i) {
      for (int k = 0; k < 3; ++k) setpoints[i].pos[k] = positions_[i][k];
    }
    return std::make_unique<ControlTick>(std::move(p), std::move(sensors), setpoints, 3, 5.0, 0.01);
  }
  std::unique_ptr<PluginInstance> Create(const PluginSection& s, int vehicle) {
    mjfCreateContext ctx{};
    ctx.timestep = 0.01;
    ctx.vehicle = vehicle;
    ctx.n_vehicles = kVehicles;
    ctx.vehicle_info = &vehicle_.info;
    ctx.initial_pos = positions_[vehicle].data();
    return std::make_unique<PluginInstance>(registry_.Find(s.plugin, "test"), s, "test.toml", ctx);
  }
  std::vector<mjfVehicleState> AtRest() const {
    std::vector<mjfVehicleState> states(kVehicles);
    for (int i = 0; i < kVehicles; ++i) {
      states[i] = mjfVehicleState{};
      for (int k = 0; k < 3; ++k) states[i].pos[k] = positions_[i][k];
      states[i].quat[0] = 1;
    }
    return states;
  }

  PluginRegistry registry_;
  PointMass vehicle_;
  std::array<std::array<double, 3>, kVehicles> positions_;
};

TEST_F(ControlTickTest, IdealSensorsHandTheTruthToThePluginsAndHoverHolds) {
  auto tick = MakeTick(std::make_unique<IdealSensors>(), Section("leader", "hover"));
  const auto truth = AtRest();
  tick->Run(0, truth);
  for (int i = 0; i < kVehicles; ++i) {
    EXPECT_EQ(std::memcmp(&tick->measured()[i], &truth[i], sizeof(mjfVehicleState)), 0);
    // At rest on its hold point: no horizontal force, weight carried by fz.
    EXPECT_NEAR(tick->controls()[3 * i + 0], 0.0, 1e-12);
    EXPECT_NEAR(tick->controls()[3 * i + 1], 0.0, 1e-12);
    EXPECT_NEAR(tick->controls()[3 * i + 2], kMass * kGravity, 1e-9);
  }
  // The host's bus contract for followers: altitude held, sliding variables not applicable.
  EXPECT_EQ(tick->setpoints()[1].pos[2], 5.0);
  EXPECT_TRUE(std::isnan(tick->setpoints()[1].sliding[0]));
}

TEST_F(ControlTickTest, ASensorStageIsWhatTheControllersSee) {
  // Every vehicle believes it is 1 m too far along +x: hover pushes it back, along -x.
  auto tick = MakeTick(std::make_unique<BiasedSensors>(1.0), Section("leader", "hover"));
  tick->Run(0, AtRest());
  EXPECT_DOUBLE_EQ(tick->measured()[1].pos[0], positions_[1][0] + 1.0);
  for (int i = 0; i < kVehicles; ++i) {
    EXPECT_LT(tick->controls()[3 * i + 0], -0.1) << "vehicle " << i;
    EXPECT_NEAR(tick->controls()[3 * i + 1], 0.0, 1e-12);
  }
}

TEST_F(ControlTickTest, APluginFailureNamesPluginVehicleTimeAndReason) {
  auto tick = MakeTick(std::make_unique<IdealSensors>(),
                       Section("leader", "test_fail_message", {{"after", {"0.05", 0, ""}}}));
  const auto truth = AtRest();
  for (int step = 0; step < 5; ++step) tick->Run(step, truth);  // t < 0.05 s: holds
  try {
    tick->Run(5, truth);
    FAIL() << "the failing plugin was not reported";
  } catch (const SimulationError& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr("t = 0.050 s"), HasSubstr("'test_fail_message'"),
                                HasSubstr("(vehicle 0)"), HasSubstr("code 7"),
                                HasSubstr("rotor 2 reports an over-temperature")));
  }
}

TEST_F(ControlTickTest, AnExceptionThrownByAPluginBecomesASimulationError) {
  auto tick = MakeTick(std::make_unique<IdealSensors>(),
                       Section("leader", "test_throw", {{"after", {"0", 0, ""}}}));
  EXPECT_THROW(tick->Run(0, AtRest()), SimulationError);
}

}  // namespace
}  // namespace mjf::runner
