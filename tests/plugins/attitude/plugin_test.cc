// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The attitude family (libmjf_attitude.so) through the plugin ABI.

#include <gtest/gtest.h>
#include <mjformation/plugin.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "mjformation/attitude/geometric.hpp"
#include "mjformation/attitude/pd_cascade.hpp"
#include "mjformation/attitude/pointmass_direct.hpp"
#include "plugin_loader.hpp"

namespace {

using mjf::test::Context;
using mjf::test::Default;
using mjf::test::kNaN;
using mjf::test::Library;
using mjf::test::NaNSetpoint;
using mjf::test::VehicleInfo;

// A 1 ms step of n vehicles over the caller's arrays.
mjfStepContext StepOver(int n_vehicles, mjfVehicleState* states, mjfSetpoint* setpoints,
                        double* controls) {
  mjfStepContext step{};
  step.timestep = 0.001;
  step.n_vehicles = n_vehicles;
  step.states = states;
  step.setpoints = setpoints;
  step.controls = controls;
  return step;
}

TEST(AttitudePluginTest, ExportsThePluginsWithTheirActuators) {
  Library lib(MJF_ATTITUDE_PLUGIN);
  ASSERT_EQ(lib.size(), 3u);
  const mjfPlugin* cascade = lib.Get("pd_cascade");
  const mjfPlugin* pm = lib.Get("pointmass_direct");
  ASSERT_TRUE(cascade && pm);
  EXPECT_EQ(cascade->abi_version, MJF_ABI_VERSION);
  EXPECT_EQ(cascade->kind, MJF_KIND_ATTITUDE);
  ASSERT_EQ(cascade->n_actuators, 4);
  for (int k = 0; k < 4; ++k)
    EXPECT_EQ(std::string(cascade->actuators[k]), "rotor" + std::to_string(k));
  ASSERT_EQ(pm->n_actuators, 3);
  EXPECT_STREQ(pm->actuators[2], "fz");
  // Declared defaults are the pure classes' defaults.
  const mjf::attitude::PdCascade::Gains g;
  const std::map<std::string, double> expected = {
      {"tilt_max", g.tilt_max}, {"kp_att", g.kp_att}, {"kd_att", g.kd_att},
      {"kp_yaw", g.kp_yaw},     {"kd_yaw", g.kd_yaw}, {"kp_z", g.kp_z},
      {"ki_z", g.ki_z},         {"kd_z", g.kd_z},     {"imax_z", g.imax_z}};
  ASSERT_EQ(cascade->n_attributes, static_cast<int>(expected.size()) + 2);
  for (const auto& [key, value] : expected) {
    EXPECT_EQ(std::stod(Default(*cascade, key.c_str())), value) << key;
  }
  EXPECT_EQ(Default(*cascade, "damping"), g.euler_rate_damping ? "euler_rates" : "body_rates");
  EXPECT_EQ(Default(*cascade, "allocation"),
            g.allocation == mjf::attitude::Mixer::Priority::kThrustFirst ? "thrust_first"
                                                                         : "roll_pitch_first");
  const mjfPlugin* geometric = lib.Get("geometric");
  ASSERT_TRUE(geometric);
  ASSERT_EQ(geometric->n_actuators, 4);
  EXPECT_STREQ(geometric->actuators[3], "rotor3");
  const mjf::attitude::Geometric::Gains gg;
  const std::map<std::string, double> expected_geometric = {{"tilt_max", gg.tilt_max},
                                                            {"rate_bw", gg.rate_bw},
                                                            {"att_bw", gg.att_bw},
                                                            {"yaw_bw", gg.yaw_bw},
                                                            {"z_bw", gg.z_bw},
                                                            {"rate_ki", gg.rate_ki},
                                                            {"thrust_margin", gg.thrust_margin}};
  ASSERT_EQ(geometric->n_attributes, static_cast<int>(expected_geometric.size()));
  for (const auto& [key, value] : expected_geometric) {
    EXPECT_EQ(std::stod(Default(*geometric, key.c_str())), value) << key;
  }
  const mjf::attitude::PointMassDirect::Gains pg;
  EXPECT_EQ(std::stod(Default(*pm, "kp_z")), pg.kp_z);
  EXPECT_EQ(std::stod(Default(*pm, "kd_z")), pg.kd_z);
}

TEST(AttitudePluginTest, QuadrotorPluginsHoverOnTheModelsInfo) {
  Library lib(MJF_ATTITUDE_PLUGIN);
  for (const char* name : {"pd_cascade", "geometric"}) {
    SCOPED_TRACE(name);
    const mjfPlugin* p = lib.Get(name);
    ASSERT_TRUE(p);
    VehicleInfo info("quadrotor.xml", *p);
    EXPECT_NEAR(info.actuators[0].time_constant, 0.025, 1e-12);
    Context c(*p, {}, &info.vehicle, 1, nullptr);
    void* instance = p->create(&c.ctx);
    ASSERT_NE(instance, nullptr) << c.error;
    mjfVehicleState states[3] = {};
    for (auto& s : states) s.quat[0] = 1;
    states[1].pos[2] = 5;
    mjfSetpoint setpoints[3] = {NaNSetpoint(), NaNSetpoint(), NaNSetpoint()};
    mjfSetpoint& sp = setpoints[1];
    sp.acc[0] = sp.acc[1] = sp.acc[2] = 0;
    sp.pos[2] = 5;
    sp.vel[2] = 0;
    sp.yaw = 0;
    double controls[4] = {kNaN, kNaN, kNaN, kNaN};
    mjfStepContext step = StepOver(3, states, setpoints, controls);
    ASSERT_EQ(p->compute(instance, &step), 0);
    for (double u : controls) EXPECT_NEAR(u, 1.5 * 9.81 / 4, 1e-9);
    // A non-finite setpoint stops the run instead of producing garbage.
    sp.pos[2] = kNaN;
    EXPECT_NE(p->compute(instance, &step), 0);
    p->reset(instance);
    p->destroy(instance);
  }
}

TEST(AttitudePluginTest, PointMassDirectGivesMassTimesCommand) {
  Library lib(MJF_ATTITUDE_PLUGIN);
  const mjfPlugin* p = lib.Get("pointmass_direct");
  ASSERT_TRUE(p);
  VehicleInfo info("pointmass.xml", *p);
  EXPECT_NEAR(info.vehicle.mass, 1, 1e-12);
  Context c(*p, {}, &info.vehicle, 0, nullptr);
  void* instance = p->create(&c.ctx);
  ASSERT_NE(instance, nullptr) << c.error;
  mjfVehicleState state{};
  state.quat[0] = 1;
  state.pos[2] = 2;
  mjfSetpoint sp = NaNSetpoint();
  sp.acc[0] = 0.3;
  sp.acc[1] = -0.4;
  sp.acc[2] = 0.1;
  sp.pos[2] = 2;
  sp.vel[2] = 0;
  sp.yaw = 0;
  double controls[3];
  mjfStepContext step = StepOver(1, &state, &sp, controls);
  ASSERT_EQ(p->compute(instance, &step), 0);
  EXPECT_DOUBLE_EQ(controls[0], 0.3);
  EXPECT_DOUBLE_EQ(controls[1], -0.4);
  EXPECT_NEAR(controls[2], 9.81 + 0.1, 1e-12);
  p->destroy(instance);
}

// The family's compute refuses a step it cannot fly: without controls (1) and with a setpoint
// that is not finite (2), each with its message, the same before and after the family's layout.
TEST(AttitudePluginTest, ComputeRefusesAStepItCannotFlyWithItsMessage) {
  Library lib(MJF_ATTITUDE_PLUGIN);
  const char* const kRotorSetpoint = "non-finite setpoint (acc, pos[2], vel[2] or yaw)";
  const std::tuple<const char*, const char*, const char*> cases[] = {
      {"pd_cascade", "quadrotor.xml", kRotorSetpoint},
      {"geometric", "quadrotor.xml", kRotorSetpoint},
      {"pointmass_direct", "pointmass.xml", "the setpoint is not finite"}};
  for (const auto& [name, model, setpoint_message] : cases) {
    SCOPED_TRACE(name);
    const mjfPlugin* p = lib.Get(name);
    ASSERT_TRUE(p);
    VehicleInfo info(model, *p);
    Context c(*p, {}, &info.vehicle, 0, nullptr);
    void* instance = p->create(&c.ctx);
    ASSERT_NE(instance, nullptr) << c.error;
    mjfVehicleState state{};
    state.quat[0] = 1;
    mjfSetpoint sp = NaNSetpoint();
    double controls[4] = {kNaN, kNaN, kNaN, kNaN};
    char error[128] = "";
    mjfStepContext step = StepOver(1, &state, &sp, controls);
    step.error = error;
    step.error_size = sizeof(error);
    EXPECT_EQ(p->compute(instance, &step), 2);
    EXPECT_STREQ(error, setpoint_message);
    for (double u : controls) EXPECT_TRUE(std::isnan(u));  // nothing written
    step.controls = nullptr;
    EXPECT_EQ(p->compute(instance, &step), 1);
    EXPECT_STREQ(error, "called for a vehicle the step does not have, or without controls");
    p->reset(instance);
    p->destroy(instance);
  }
}

TEST(AttitudePluginTest, BadAttributesAreRefusedByName) {
  Library lib(MJF_ATTITUDE_PLUGIN);
  const mjfPlugin* p = lib.Get("pd_cascade");
  ASSERT_TRUE(p);
  VehicleInfo info("quadrotor.xml", *p);
  const std::map<std::string, std::string> bad[] = {
      {{"kp_att", "abc"}},          {{"tilt_max", "2"}},    {{"kd_z", "-1"}},
      {{"imax_z", "nan"}},          {{"tilt_max", "0.78"}}, {{"damping", "euler"}},
      {{"allocation", "yaw_first"}}};
  for (const auto& overrides : bad) {
    Context c(*p, overrides, &info.vehicle, 0, nullptr);
    EXPECT_EQ(p->create(&c.ctx), nullptr);
    EXPECT_NE(std::string(c.error).find(overrides.begin()->first), std::string::npos) << c.error;
  }
  // Above 0.65 rad only with both large-tilt fixes.
  Context fixed(
      *p, {{"tilt_max", "0.78"}, {"damping", "euler_rates"}, {"allocation", "roll_pitch_first"}},
      &info.vehicle, 0, nullptr);
  void* instance = p->create(&fixed.ctx);
  EXPECT_NE(instance, nullptr) << fixed.error;
  if (instance) p->destroy(instance);
  // A vehicle whose rotors all sit on one line cannot roll: refused at create().
  VehicleInfo flat("quadrotor.xml", *p);
  for (auto& a : flat.actuators) a.site_pos[1] = 0;
  Context c(*p, {}, &flat.vehicle, 0, nullptr);
  EXPECT_EQ(p->create(&c.ctx), nullptr);
  EXPECT_NE(std::string(c.error).find("no roll torque authority"), std::string::npos) << c.error;
  // No vehicle info.
  Context none(*p, {}, nullptr, 0, nullptr);
  EXPECT_EQ(p->create(&none.ctx), nullptr);
  EXPECT_STRNE(none.error, "");
}

TEST(AttitudePluginTest, GeometricRefusesBadGainsByName) {
  Library lib(MJF_ATTITUDE_PLUGIN);
  const mjfPlugin* p = lib.Get("geometric");
  ASSERT_TRUE(p);
  VehicleInfo info("quadrotor.xml", *p);
  // Each: the attribute set, and the key the message must name (derived-bandwidth checks name
  // the key whose value breaks the cascade).
  const std::pair<std::map<std::string, std::string>, std::string> bad[] = {
      {{{"tilt_max", "1.6"}}, "tilt_max"}, {{{"rate_bw", "-1"}}, "rate_bw"},
      {{{"rate_bw", "60"}}, "rate_bw"},    {{{"att_bw", "20"}}, "att_bw"},
      {{{"z_bw", "9"}}, "z_bw"},           {{{"yaw_bw", "x"}}, "yaw_bw"},
      {{{"rate_ki", "0.9"}}, "rate_ki"},   {{{"thrust_margin", "0.6"}}, "thrust_margin"}};
  for (const auto& [overrides, key] : bad) {
    Context c(*p, overrides, &info.vehicle, 0, nullptr);
    EXPECT_EQ(p->create(&c.ctx), nullptr) << key;
    EXPECT_NE(std::string(c.error).find(key), std::string::npos) << c.error;
  }
}

}  // namespace
