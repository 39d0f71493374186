// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/scene/scene.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <ctime>
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

// Vehicles 8..30: composed in blocks across decades (9 alone, 10..19 and 20..29 as blocks of
// ten, 30 alone). The text is the scene one attach per vehicle writes: each vehicle in a frame
// of its own, its classes directly in the scene's, none of the blocks' wrappers; it compiles
// to the very model the run uses; every vehicle is where it was asked to be.
TEST(SceneTest, VehiclesComposedInBlocksAreTheSceneOfOneAttachEach) {
  SceneRequest r = Request(23);
  r.first_vehicle = 8;
  for (size_t i = 0; i < r.positions.size(); ++i) r.positions[i] = {0.5 * i, -0.25 * i, 2.0};
  ComposedScene scene = ComposeScene(r, "test");
  EXPECT_EQ(scene.xml.find("mjf_block"), std::string::npos);
  size_t frames = 0;
  for (size_t at = 0; (at = scene.xml.find("<frame>", at)) != std::string::npos; ++at) ++frames;
  EXPECT_EQ(frames, 23u);
  EXPECT_THAT(scene.xml, HasSubstr("\n    <default class=\"uav30_main\">"));
  mjModel* reloaded = CompileModel(scene.xml, "reloaded");
  auto bytes = [](const mjModel* m) {
    std::vector<char> out(mj_sizeModel(m));
    mj_saveModel(m, nullptr, out.data(), static_cast<int>(out.size()));
    return out;
  };
  EXPECT_TRUE(bytes(reloaded) == bytes(scene.model.get()));
  mj_deleteModel(reloaded);
  const mjModel* m = scene.model.get();
  for (int i = 0; i < 23; ++i) {
    const std::string p = VehiclePrefix(8 + i);
    const int body = mj_name2id(m, mjOBJ_BODY, (p + "vehicle").c_str());
    ASSERT_EQ(body, 1 + i) << p;  // in vehicle order, as the actuators and sensors
    EXPECT_EQ(mj_name2id(m, mjOBJ_ACTUATOR, (p + "rotor3").c_str()), 4 * i + 3) << p;
    EXPECT_DOUBLE_EQ(m->body_pos[3 * body], 0.5 * i) << p;
    EXPECT_DOUBLE_EQ(m->body_pos[3 * body + 1], -0.25 * i) << p;
    const int hull = mj_name2id(m, mjOBJ_GEOM, (p + "hull").c_str());
    EXPECT_EQ(m->geom_matid[hull], mj_name2id(m, mjOBJ_MATERIAL, "quad_frame")) << p;
  }
  EXPECT_EQ(m->nmat, 1 + 5);
}

// Without its text (a partition's scene): the same compiled model, byte for byte, in blocks
// (23 vehicles from 8) and alone (one vehicle), and no text.
TEST(SceneTest, WithoutTheTextTheModelIsTheSame) {
  auto bytes = [](const mjModel* m) {
    std::vector<char> out(mj_sizeModel(m));
    mj_saveModel(m, nullptr, out.data(), static_cast<int>(out.size()));
    return out;
  };
  for (const int vehicles : {23, 1}) {
    SceneRequest r = Request(vehicles);
    r.first_vehicle = 8;
    const ComposedScene with = ComposeScene(r, "test");
    r.write_text = false;
    const ComposedScene without = ComposeScene(r, "test");
    EXPECT_FALSE(with.xml.empty());
    EXPECT_TRUE(without.xml.empty()) << vehicles;
    EXPECT_TRUE(bytes(with.model.get()) == bytes(without.model.get())) << vehicles;
  }
}

// Composition costs O(N) (O(N log N) attaches, one pass for the rest): four times the vehicles
// take about four times the processor time; one attach per vehicle took sixteen (each attach
// rebuilds every list of the scene). The point-mass vehicle keeps MuJoCo's own compilation
// linear too (its bodies need no dense inverse inertia, mj_setConst), so the ratio is ours.
TEST(SceneCostTest, ComposingIsLinearInTheNumberOfVehicles) {
  auto seconds = [](int vehicles) {
    SceneRequest r = Request(vehicles);
    r.vehicle_path = std::string(MJF_SOURCE_DIR) + "/mjcf/pointmass.xml";
    const std::clock_t start = std::clock();
    ComposeScene(r, "test");
    return static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
  };
  const double small = std::min(seconds(501), seconds(501));  // the less disturbed of two
  const double large = seconds(2001);
  EXPECT_LT(large / small, 7.0) << "501 vehicles: " << small << " s, 2001: " << large << " s";
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
