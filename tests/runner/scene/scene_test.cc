// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/scene/scene.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <string>
#include <vector>

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
  ComposedScene scene = ComposeScene(Request(7), "test");
  mjModel* m = scene.model.get();
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
}

TEST(SceneTest, WrenchModelHasNoActuators) {
  SceneRequest r = Request(3);
  r.strip_actuators = true;
  ComposedScene scene = ComposeScene(r, "test");
  EXPECT_EQ(scene.model->nu, 0);
  EXPECT_GE(mj_name2id(scene.model.get(), mjOBJ_SITE, "uav2_rotor0"), 0);
}

TEST(SceneTest, VehicleWithoutVehicleBodyIsRefused) {
  const std::string dir = mjf::testing::TempDir("scene");
  SceneRequest r = Request(2);
  r.vehicle_path = mjf::testing::WriteFile(
      dir + "/v.xml", "<mujoco><worldbody><body name=\"drone\"/></worldbody></mujoco>");
  try {
    ComposeScene(r, "test");
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_THAT(e.what(), HasSubstr("v.xml"));
    EXPECT_THAT(e.what(), HasSubstr("<body name=\"vehicle\">"));
  }
}

// `check` lists a model's <option timestep> that [run] timestep replaces, also one equal to
// MuJoCo's default 0.002 (the model wrote it; comparing with the default hid it).
TEST(SceneTest, AReplacedTimestepIsNotedEvenAtMuJoCosDefault) {
  const std::string dir = mjf::testing::TempDir("scene_dt");
  const std::string quad =
      mjf::testing::ReadFile(std::string(MJF_SOURCE_DIR) + "/mjcf/quadrotor.xml");
  const std::string ours = "timestep=\"0.001\"";
  ASSERT_NE(quad.find(ours), std::string::npos);
  for (const char* dt : {"0.002", "0.004"}) {
    std::string text = quad;
    text.replace(text.find(ours), ours.size(), std::string("timestep=\"") + dt + "\"");
    SceneRequest r = Request(1);
    r.vehicle_path = mjf::testing::WriteFile(dir + "/v" + dt + ".xml", text);
    const ComposedScene scene = ComposeScene(r, "test");
    EXPECT_THAT(scene.notes, ::testing::Contains(HasSubstr(
                                 std::string("the model's <option timestep=\"") + dt +
                                 "\"> is replaced by the experiment's ([run] timestep = 0.001)")))
        << dt;
  }
  // The stock model's own 0.001 is the experiment's: nothing to say.
  EXPECT_TRUE(ComposeScene(Request(1), "test").notes.empty());
}

// The written scene is the composed spec as MuJoCo writes it: alone, it compiles to the very
// model the run uses, byte for byte.
TEST(SceneTest, WrittenSceneCompilesToTheSameModel) {
  ComposedScene scene = ComposeScene(Request(3), "test");
  mjModel* reloaded = CompileModel(scene.xml, "reloaded");
  auto bytes = [](const mjModel* m) {
    std::vector<char> out(mj_sizeModel(m));
    mj_saveModel(m, nullptr, out.data(), static_cast<int>(out.size()));
    return out;
  };
  EXPECT_TRUE(bytes(reloaded) == bytes(scene.model.get()));
  mj_deleteModel(reloaded);
}

// mjs_attach carries every asset of the vehicle and one copy per vehicle; the scene keeps one
// shared copy of what the vehicle uses.
TEST(SceneTest, UnusedAssetsOfTheVehicleAreNotCarried) {
  const std::string dir = mjf::testing::TempDir("scene_assets");
  std::string xml = mjf::testing::ReadFile(std::string(MJF_SOURCE_DIR) + "/mjcf/quadrotor.xml");
  xml.replace(xml.find("<asset>"), 7, "<asset>\n<material name=\"unused_paint\"/>");
  SceneRequest r = Request(3);
  r.vehicle_path = mjf::testing::WriteFile(dir + "/v.xml", xml);
  ComposedScene scene = ComposeScene(r, "test");
  EXPECT_EQ(mj_name2id(scene.model.get(), mjOBJ_MATERIAL, "unused_paint"), -1);
  EXPECT_EQ(mj_name2id(scene.model.get(), mjOBJ_MATERIAL, "uav1_unused_paint"), -1);
  EXPECT_EQ(scene.model->nmat, 1 + 5);  // the floor's and the quadrotor's five, once
  const int hull = mj_name2id(scene.model.get(), mjOBJ_GEOM, "uav2_hull");
  ASSERT_GE(hull, 0);
  EXPECT_EQ(scene.model->geom_matid[hull],
            mj_name2id(scene.model.get(), mjOBJ_MATERIAL, "quad_frame"));
}

}  // namespace
}  // namespace mjf::runner
