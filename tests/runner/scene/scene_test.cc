// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/scene/scene.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include "test_util.hpp"

namespace mjf::runner {
namespace {

using ::testing::HasSubstr;

SceneRequest Request(int vehicles) {
  SceneRequest r;
  r.scene_path = std::string(MJF_SOURCE_DIR) + "/mjcf/scene.xml";
  r.vehicle_path = std::string(MJF_SOURCE_DIR) + "/mjcf/quadrotor.xml";
  for (int i = 0; i < vehicles; ++i) r.positions.push_back({1.0 * i, 0.0, 2.0});
  return r;
}

TEST(SceneTest, ComposesPrefixedCopies) {
  const std::string xml = ComposeScene(Request(7));
  mjModel* m = CompileModel(xml, "test");
  for (int i = 0; i < 7; ++i) {
    const std::string p = VehiclePrefix(i);
    EXPECT_GE(mj_name2id(m, mjOBJ_BODY, (p + "vehicle").c_str()), 0) << p;
    EXPECT_GE(mj_name2id(m, mjOBJ_SENSOR, (p + "pos").c_str()), 0) << p;
    EXPECT_GE(mj_name2id(m, mjOBJ_ACTUATOR, (p + "rotor3").c_str()), 0) << p;
  }
  EXPECT_EQ(m->nu, 7 * 4);
  EXPECT_DOUBLE_EQ(m->opt.timestep, 0.001);
  // Vehicle 3 starts where it was asked to.
  mjData* d = mj_makeData(m);
  mj_forward(m, d);
  const int body = mj_name2id(m, mjOBJ_BODY, "uav3_vehicle");
  EXPECT_NEAR(d->xpos[3 * body], 3.0, 1e-12);
  EXPECT_NEAR(d->xpos[3 * body + 2], 2.0, 1e-12);
  mj_deleteData(d);
  mj_deleteModel(m);
}

TEST(SceneTest, WrenchModelHasNoActuators) {
  SceneRequest r = Request(3);
  r.strip_actuators = true;
  mjModel* m = CompileModel(ComposeScene(r), "test");
  EXPECT_EQ(m->nu, 0);
  EXPECT_GE(mj_name2id(m, mjOBJ_SITE, "uav2_rotor0"), 0);
  mj_deleteModel(m);
}

TEST(SceneTest, VehicleWithoutVehicleBodyIsRefused) {
  const std::string dir = mjf::testing::TempDir("scene");
  SceneRequest r = Request(2);
  r.vehicle_path = mjf::testing::WriteFile(
      dir + "/v.xml", "<mujoco><worldbody><body name=\"drone\"/></worldbody></mujoco>");
  try {
    ComposeScene(r);
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_THAT(e.what(), HasSubstr("v.xml"));
    EXPECT_THAT(e.what(), HasSubstr("<body name=\"vehicle\">"));
  }
}

}  // namespace
}  // namespace mjf::runner
