// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The guidance family (libmjf_guidance.so) through the plugin ABI.

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

#include "plugin_loader.hpp"

namespace {

using mjf::test::Context;
using mjf::test::Library;
using mjf::test::NaNSetpoint;

TEST(GuidancePluginTest, CircleWritesItsVehiclesSetpointOnly) {
  Library lib(MJF_GUIDANCE_PLUGIN);
  ASSERT_EQ(lib.size(), 7u);
  const mjfPlugin* p = lib.Get("circle");
  ASSERT_TRUE(p);
  EXPECT_EQ(p->kind, MJF_KIND_GUIDANCE);
  Context c(*p, {{"center", "1 2"}, {"altitude", "4"}, {"yaw", "0.3"}}, nullptr, 0, nullptr);
  void* instance = p->create(&c.ctx);
  ASSERT_NE(instance, nullptr) << c.error;
  mjfVehicleState states[3] = {};
  states[0].pos[0] = 21;  // on the circle at t = 0, at rest
  states[0].pos[1] = 2;
  mjfSetpoint setpoints[3] = {NaNSetpoint(), NaNSetpoint(), NaNSetpoint()};
  mjfStepContext step{};
  step.time = 0;
  step.timestep = 0.001;
  step.n_vehicles = 3;
  step.states = states;
  step.setpoints = setpoints;
  ASSERT_EQ(p->compute(instance, &step), 0);
  const mjfSetpoint& sp = setpoints[0];
  const double w = 0.157, r = 20;
  EXPECT_NEAR(sp.pos[0], 21, 1e-12);
  EXPECT_NEAR(sp.pos[1], 2, 1e-12);
  EXPECT_NEAR(sp.pos[2], 4, 1e-12);
  EXPECT_NEAR(sp.vel[1], r * w, 1e-12);
  // a = a_ref + kp (0) + kd (v_ref - 0) with kd = 2.
  EXPECT_NEAR(sp.acc[0], -r * w * w, 1e-12);
  EXPECT_NEAR(sp.acc[1], 2 * r * w, 1e-12);
  EXPECT_NEAR(sp.yaw, 0.3, 1e-12);
  EXPECT_TRUE(std::isnan(sp.sliding[0]) && std::isnan(sp.sliding[1]));
  EXPECT_TRUE(std::isnan(setpoints[1].acc[0]) && std::isnan(setpoints[2].pos[2]));
  p->destroy(instance);

  for (const auto& [key, value] :
       std::map<std::string, std::string>{{"radius", "-1"}, {"center", "1"}, {"omega", "fast"}}) {
    Context bad(*p, {{key, value}}, nullptr, 0, nullptr);
    EXPECT_EQ(p->create(&bad.ctx), nullptr);
    EXPECT_NE(std::string(bad.error).find(key), std::string::npos) << bad.error;
  }
}

TEST(GuidancePluginTest, HoverHoldsInitialPositionOrAttributes) {
  Library lib(MJF_GUIDANCE_PLUGIN);
  const mjfPlugin* p = lib.Get("hover");
  ASSERT_TRUE(p);
  const double initial[3] = {1, 2, 3};
  mjfVehicleState states[3] = {};
  mjfSetpoint setpoints[3] = {NaNSetpoint(), NaNSetpoint(), NaNSetpoint()};
  mjfStepContext step{};
  step.n_vehicles = 3;
  step.states = states;
  step.setpoints = setpoints;
  {
    Context c(*p, {{"altitude", "7"}}, nullptr, 2, initial);
    void* instance = p->create(&c.ctx);
    ASSERT_NE(instance, nullptr) << c.error;
    states[2].vel[0] = 0.5;
    ASSERT_EQ(p->compute(instance, &step), 0);
    EXPECT_NEAR(setpoints[2].pos[0], 1, 1e-12);
    EXPECT_NEAR(setpoints[2].pos[2], 7, 1e-12);
    EXPECT_NEAR(setpoints[2].acc[0], 1 * (1 - 0) - 2 * 0.5, 1e-12);
    EXPECT_NEAR(setpoints[2].acc[1], 1 * 2, 1e-12);
    EXPECT_TRUE(std::isnan(setpoints[2].sliding[0]));
    p->destroy(instance);
  }
  {
    Context c(*p, {{"position", "4 5 6"}}, nullptr, 0, initial);
    void* instance = p->create(&c.ctx);
    ASSERT_NE(instance, nullptr) << c.error;
    ASSERT_EQ(p->compute(instance, &step), 0);
    EXPECT_NEAR(setpoints[0].pos[1], 5, 1e-12);
    EXPECT_NEAR(setpoints[0].pos[2], 6, 1e-12);
    p->destroy(instance);
  }
  for (const auto& [key, value] :
       std::map<std::string, std::string>{{"position", "1 2"}, {"kp", "-3"}, {"altitude", "x"}}) {
    Context bad(*p, {{key, value}}, nullptr, 0, initial);
    EXPECT_EQ(p->create(&bad.ctx), nullptr);
    EXPECT_NE(std::string(bad.error).find(key), std::string::npos) << bad.error;
  }
  Context no_start(*p, {}, nullptr, 0, nullptr);
  EXPECT_EQ(p->create(&no_start.ctx), nullptr);
  EXPECT_NE(std::string(no_start.error).find("position"), std::string::npos) << no_start.error;
}

}  // namespace

// The maneuvering leaders through the ABI: defaults create and command inside the bounds; bad
// input is refused at create() with the attribute's name (the host adds FILE:LINE: [leader]).
TEST(GuidancePluginTest, ManeuveringLeadersCreateComputeAndRefuseBadInput) {
  Library lib(MJF_GUIDANCE_PLUGIN);
  const std::string csv = ::testing::TempDir() + "/leader_path.csv";
  {
    std::FILE* f = std::fopen(csv.c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fputs("t,x,y\n0,0,0\n5,3,1\n10,6,0\n", f);
    std::fclose(f);
  }
  for (const char* name : {"random_accel", "bang_bang", "lemniscate", "waypoints", "trajectory"}) {
    const mjfPlugin* p = lib.Get(name);
    ASSERT_TRUE(p) << name;
    EXPECT_EQ(p->kind, MJF_KIND_GUIDANCE);
    std::map<std::string, std::string> attributes = {{"a_min", "-0.5"}, {"a_max", "0.7"}};
    if (std::string(name) == "trajectory") attributes["file"] = csv;
    if (std::string(name) == "lemniscate") attributes["omega"] = "0.1";  // 2 A w^2 = 0.4
    if (std::string(name) == "waypoints") attributes["speed"] = "1";
    Context c(*p, attributes, nullptr, 0, nullptr);
    void* instance = p->create(&c.ctx);
    ASSERT_NE(instance, nullptr) << name << ": " << c.error;
    mjfVehicleState states[3] = {};
    states[0].pos[0] = 3;
    states[0].vel[1] = -2;
    mjfSetpoint setpoints[3] = {NaNSetpoint(), NaNSetpoint(), NaNSetpoint()};
    char error[128] = {0};
    mjfStepContext step{};
    step.timestep = 0.001;
    step.n_vehicles = 3;
    step.states = states;
    step.setpoints = setpoints;
    step.error = error;
    step.error_size = sizeof(error);
    for (int k = 0; k < 3000; ++k) {
      step.time = k * 0.001;
      step.step = k;
      ASSERT_EQ(p->compute(instance, &step), 0) << name << ": " << error;
      for (int i = 0; i < 2; ++i) {
        ASSERT_GE(setpoints[0].acc[i], -0.5) << name;
        ASSERT_LE(setpoints[0].acc[i], 0.7) << name;
      }
    }
    EXPECT_TRUE(std::isnan(setpoints[1].acc[0]));
    if (p->reset) p->reset(instance);
    p->destroy(instance);

    Context equal(*p, {{"a_min", "1"}, {"a_max", "1"}, {"file", csv}}, nullptr, 0, nullptr);
    EXPECT_EQ(p->create(&equal.ctx), nullptr) << name;
    EXPECT_NE(std::string(equal.error).find("a_min"), std::string::npos) << equal.error;
  }
  const std::vector<std::tuple<std::string, std::string, std::string>> bad = {
      {"bang_bang", "dwell", "0 1"},
      {"bang_bang", "dwell", "-1 1"},
      {"random_accel", "seed", "-3"},
      {"random_accel", "seed", "1.5"},
      {"random_accel", "area", "0 0 -1 5"},
      {"waypoints", "points", "0 0 1 0 1 1"},  // too close at 2 m/s
      {"waypoints", "points", "0 0 1"},
      {"trajectory", "file", "/nonexistent.csv"},
      {"trajectory", "file", ""},
  };
  for (const auto& [name, key, value] : bad) {
    Context c(*lib.Get(name), {{key, value}}, nullptr, 0, nullptr);
    EXPECT_EQ(lib.Get(name)->create(&c.ctx), nullptr) << name << " " << key << " = " << value;
    EXPECT_NE(std::string(c.error).find("'" + key + "'"), std::string::npos) << c.error;
  }
}
