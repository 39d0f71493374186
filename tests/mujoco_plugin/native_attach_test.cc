// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// An exported scene attached into a user's world with MuJoCo's own model editing (mjs_attach,
// what Python's MjSpec.attach calls) keeps its controllers: the vehicles' bodies reference the
// swarm instance, so the attach copies it, and the plugin finds its vehicles under whatever
// prefix and suffix the attach gave them (mujoco_plugin/src/attach_names.hpp).
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "drone_mjcf.hpp"
#include "mjformation/export/export.hpp"
#include "native_fixture.hpp"

namespace mjf::native {
namespace {

using mjf::testing::LoadNativePluginsOnce;
using mjf::testing::NativeExperimentText;
using mjf::testing::ReadFile;
using mjf::testing::Scratch;

// A user's world: a floor, a static crate away from the swarm, Exp 2's timestep (an attach
// keeps the parent's <option>, so the world sets the scene's own step).
constexpr char kWorld[] = R"(<mujoco model="world">
  <option timestep="0.001"/>
  <worldbody>
    <geom name="floor" type="plane" size="60 60 0.1"/>
    <body name="crate" pos="40 40 0.5"><geom type="box" size="0.5 0.5 0.5"/></body>
  </worldbody>
</mujoco>)";

constexpr int kVehicles = 7;           // Exp 2: the leader and six followers
constexpr int64_t kSteps = 1500;       // 1.5 s: the formation turns on the leader's circle
constexpr double kClimbOrFall = 0.05;  // m: a drone without its controller falls 11 m in 1.5 s

class NativeAttach : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    LoadNativePluginsOnce();
    dir_ = new Scratch("attach");
    std::ofstream(*dir_ / "experiment.toml") << NativeExperimentText("exp2.toml");
    runner::ExportExperiment(*dir_ / "experiment.toml", *dir_ / "export");
    std::ofstream(*dir_ / "rounds.toml") << mjf::testing::RoundsOverTheLinksText();
    runner::ExportExperiment(*dir_ / "rounds.toml", *dir_ / "rounds");
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static std::string Scene() { return *dir_ / "export/scene.xml"; }
  // b13 with Jacobi's rounds over its lossy links (RoundsOverTheLinksText), exported.
  static std::string RoundsScene() { return *dir_ / "rounds/scene.xml"; }

  // The world with one copy of the exported `scene` per (prefix, suffix), each at the origin.
  static mjModel* Attached(const std::vector<std::pair<std::string, std::string>>& affixes,
                           std::string* error, const std::string& scene = Scene()) {
    char text[2048] = {0};
    mjSpec* world = mj_parseXMLString(kWorld, nullptr, text, sizeof(text));
    std::vector<mjSpec*> children;
    for (const auto& [prefix, suffix] : affixes) {
      mjSpec* child = mj_parseXML(scene.c_str(), nullptr, text, sizeof(text));
      children.push_back(child);
      mjsFrame* frame = mjs_addFrame(mjs_findBody(world, "world"), nullptr);
      if (!mjs_attach(frame->element, child->element, prefix.c_str(), suffix.c_str())) {
        *error = mjs_getError(world);
      }
    }
    mjModel* m = mj_compile(world, nullptr);
    if (!m) *error = mjs_getError(world);
    mj_deleteSpec(world);
    for (mjSpec* child : children) mj_deleteSpec(child);
    return m;
  }

  static Scratch* dir_;
};

Scratch* NativeAttach::dir_ = nullptr;

// Vehicle i's free joint and motor lags, in one model under `names` (prefix, suffix).
struct VehicleState {
  std::vector<mjtNum> qpos, act;
};

VehicleState StateOf(const mjModel* m, const mjData* d, int i, const std::string& prefix,
                     const std::string& suffix) {
  const std::string vehicle = "uav" + std::to_string(i) + "_";
  VehicleState s;
  const int joint = mj_name2id(m, mjOBJ_JOINT, (prefix + vehicle + "root" + suffix).c_str());
  EXPECT_GE(joint, 0) << prefix << vehicle << "root" << suffix;
  if (joint < 0) return s;
  s.qpos.assign(d->qpos + m->jnt_qposadr[joint], d->qpos + m->jnt_qposadr[joint] + 7);
  for (int k = 0; k < 4; ++k) {
    const std::string rotor = prefix + vehicle + "rotor" + std::to_string(k) + suffix;
    const int a = mj_name2id(m, mjOBJ_ACTUATOR, rotor.c_str());
    EXPECT_GE(a, 0) << rotor;
    if (a >= 0) s.act.push_back(d->act[m->actuator_actadr[a]]);
  }
  return s;
}

bool SameBits(const VehicleState& a, const VehicleState& b) {
  return a.qpos.size() == b.qpos.size() && a.act.size() == b.act.size() &&
         !std::memcmp(a.qpos.data(), b.qpos.data(), a.qpos.size() * sizeof(mjtNum)) &&
         !std::memcmp(a.act.data(), b.act.data(), a.act.size() * sizeof(mjtNum));
}

// Steps the unattached scene and the world side by side; every vehicle of every copy must hold
// the unattached scene's state, bit for bit, at every step. An attach renames and adds bodies
// that touch no drone (the crate stands 25 m from the swarm's circle, and the copies' drones
// do not collide with each other: contype 2, conaffinity 1), so the drones' dynamics are the
// same operations on the same numbers.
void ExpectEachCopyFliesTheScene(const std::string& scene, mjModel* world,
                                 const std::vector<std::pair<std::string, std::string>>& affixes) {
  mjModel* plain = mj_loadXML(scene.c_str(), nullptr, nullptr, 0);
  ASSERT_NE(plain, nullptr);
  ASSERT_EQ(world->nplugin, static_cast<int>(affixes.size()));
  mjData* d = mj_makeData(world);
  mjData* p = mj_makeData(plain);
  const VehicleState start = StateOf(plain, p, 1, "", "");
  bool same = true;
  for (int64_t k = 0; k < kSteps && same; ++k) {
    mj_step(world, d);
    mj_step(plain, p);
    for (int i = 0; i < kVehicles; ++i) {
      for (const auto& [prefix, suffix] : affixes) {
        same = same && SameBits(StateOf(world, d, i, prefix, suffix), StateOf(plain, p, i, "", ""));
        EXPECT_TRUE(same) << "vehicle " << i << " of copy '" << prefix << "' at step " << k;
      }
    }
  }
  // It flew: a follower held its altitude (a drone without controller falls 11 m in 1.5 s)
  // and moved along the formation.
  const VehicleState end = StateOf(plain, p, 1, "", "");
  EXPECT_NEAR(end.qpos[2], start.qpos[2], kClimbOrFall);
  EXPECT_GT(std::hypot(end.qpos[0] - start.qpos[0], end.qpos[1] - start.qpos[1]), 0.5);
  mj_deleteData(p);
  mj_deleteData(d);
  mj_deleteModel(plain);
}

TEST_F(NativeAttach, WithoutPrefixTheSwarmFliesTheScenesBits) {
  std::string error;
  mjModel* m = Attached({{"", ""}}, &error);
  ASSERT_NE(m, nullptr) << error;
  ExpectEachCopyFliesTheScene(Scene(), m, {{"", ""}});
  mj_deleteModel(m);
}

TEST_F(NativeAttach, UnderAPrefixAndSuffixTheSwarmFindsItsVehicles) {
  std::string error;
  mjModel* m = Attached({{"fleet/", "-1"}}, &error);
  ASSERT_NE(m, nullptr) << error;
  EXPECT_STREQ(mj_id2name(m, mjOBJ_PLUGIN, 0), "fleet/swarm-1");
  ExpectEachCopyFliesTheScene(Scene(), m, {{"fleet/", "-1"}});
  mj_deleteModel(m);
}

// Two copies under their own prefixes: two instances, each flying its own seven drones.
TEST_F(NativeAttach, TwoCopiesUnderTheirOwnPrefixesEachFly) {
  std::string error;
  mjModel* m = Attached({{"a/", ""}, {"b/", ""}}, &error);
  ASSERT_NE(m, nullptr) << error;
  ExpectEachCopyFliesTheScene(Scene(), m, {{"a/", ""}, {"b/", ""}});
  mj_deleteModel(m);
}

// Per-agent execution with its exchange rounds carried over lossy links (queues, letters in
// flight, random streams in plugin_state), two copies attached: each flies the scene's bits.
TEST_F(NativeAttach, RoundsOverTheLinksUnderTwoPrefixesEachFly) {
  std::string error;
  mjModel* m = Attached({{"a/", ""}, {"b/", ""}}, &error, RoundsScene());
  ASSERT_NE(m, nullptr) << error;
  ExpectEachCopyFliesTheScene(RoundsScene(), m, {{"a/", ""}, {"b/", ""}});
  mj_deleteModel(m);
}

// One vehicle attached alone (its body references the swarm instance, which comes along) would
// fly without its swarm: refused at compile, naming the vehicles that are missing.
TEST_F(NativeAttach, OneVehicleWithoutItsSwarmIsRefusedNamingTheOthers) {
  char text[2048] = {0};
  mjSpec* world = mj_parseXMLString(kWorld, nullptr, text, sizeof(text));
  mjSpec* child = mj_parseXML(Scene().c_str(), nullptr, text, sizeof(text));
  mjsFrame* frame = mjs_addFrame(mjs_findBody(world, "world"), nullptr);
  ASSERT_NE(mjs_attach(frame->element, mjs_findBody(child, "uav3_vehicle")->element, "x/", ""),
            nullptr)
      << mjs_getError(world);
  mjModel* m = mj_compile(world, nullptr);
  const std::string error = mjs_getError(world);
  EXPECT_EQ(m, nullptr);
  if (m) mj_deleteModel(m);
  mj_deleteSpec(world);
  mj_deleteSpec(child);
  EXPECT_NE(error.find("instance 'x/swarm'"), std::string::npos) << error;
  EXPECT_NE(error.find("'x/uav0_vehicle'"), std::string::npos) << error;
  EXPECT_NE(error.find("Attach the exported scene's whole worldbody"), std::string::npos) << error;
}

// A world that already holds an instance of the attached one's name (here the scene itself,
// its instance renamed 'b/swarm', and a copy attached under 'b/'): MuJoCo keeps the world's
// instance and copies not the other, so one instance would be referenced by both swarms'
// bodies. Refused at compile, naming the other copy's bodies, never flown half uncontrolled.
TEST_F(NativeAttach, AnInstanceNameAlreadyTakenIsRefused) {
  std::string scene = ReadFile(Scene());
  for (const std::string from : {"instance name=\"swarm\"", "plugin instance=\"swarm\""}) {
    const std::string to = from.substr(0, from.size() - 6) + "b/swarm\"";
    for (size_t at = scene.find(from); at != std::string::npos; at = scene.find(from, at)) {
      scene.replace(at, from.size(), to);
    }
  }
  // Beside the exported scene: the files it names (the scene-folder anchor too) are read
  // relative to it.
  const std::string taken = *dir_ / "export/taken.xml";
  std::ofstream(taken) << scene;
  char text[2048] = {0};
  mjSpec* world = mj_parseXML(taken.c_str(), nullptr, text, sizeof(text));
  ASSERT_NE(world, nullptr) << text;
  mjSpec* child = mj_parseXML(Scene().c_str(), nullptr, text, sizeof(text));
  mjsFrame* frame = mjs_addFrame(mjs_findBody(world, "world"), nullptr);
  ASSERT_NE(mjs_attach(frame->element, child->element, "b/", ""), nullptr);
  mjModel* m = mj_compile(world, nullptr);
  const std::string error = mjs_getError(world);
  EXPECT_EQ(m, nullptr);
  if (m) mj_deleteModel(m);
  mj_deleteSpec(world);
  mj_deleteSpec(child);
  EXPECT_NE(error.find("instance 'b/swarm'"), std::string::npos) << error;
  EXPECT_NE(error.find("referencing it but none of its vehicles: 'b/uav0_vehicle'"),
            std::string::npos)
      << error;
}

// The attitude tests' drone at the world's step, its body referencing the instance.
std::string AttachableDrone() {
  mjf::testing::DroneOptions o;
  o.timestep = "0.001";
  o.body_references_instance = true;
  return mjf::testing::DroneXml(o);
}

// mjformation.attitude, its instance referenced by the drone's body: two copies of a user's
// drone attached under two prefixes each find their body and rotors, and each flies the
// unattached drone's bits (the drones do not collide: contype 0).
TEST_F(NativeAttach, AttitudeInstanceFollowsItsBodyThroughTwoAttaches) {
  char text[2048] = {0};
  mjSpec* world = mj_parseXMLString(kWorld, nullptr, text, sizeof(text));
  const std::string drone = AttachableDrone();
  std::vector<mjSpec*> drones;
  for (const char* prefix : {"l/", "r/"}) {
    drones.push_back(mj_parseXMLString(drone.c_str(), nullptr, text, sizeof(text)));
    mjsFrame* frame = mjs_addFrame(mjs_findBody(world, "world"), nullptr);
    ASSERT_NE(mjs_attach(frame->element, drones.back()->element, prefix, ""), nullptr);
  }
  mjModel* m = mj_compile(world, nullptr);
  ASSERT_NE(m, nullptr) << mjs_getError(world);
  mjSpec* alone = mj_parseXMLString(drone.c_str(), nullptr, text, sizeof(text));
  mjModel* plain = mj_compile(alone, nullptr);
  ASSERT_NE(plain, nullptr) << mjs_getError(alone);
  EXPECT_EQ(m->nplugin, 2);
  mjData* d = mj_makeData(m);
  mjData* p = mj_makeData(plain);
  const int left = m->jnt_qposadr[mj_name2id(m, mjOBJ_JOINT, "l/root")];
  const int right = m->jnt_qposadr[mj_name2id(m, mjOBJ_JOINT, "r/root")];
  for (int k = 0; k < 1000; ++k) {
    mj_step(m, d);
    mj_step(plain, p);
  }
  EXPECT_EQ(std::memcmp(d->qpos + left, p->qpos, 7 * sizeof(mjtNum)), 0);
  EXPECT_EQ(std::memcmp(d->qpos + right, p->qpos, 7 * sizeof(mjtNum)), 0);
  EXPECT_NEAR(p->qpos[2], 1.0, 0.05) << "it climbed from 0.8 m to hold 1 m";
  mj_deleteData(p);
  mj_deleteData(d);
  mj_deleteModel(plain);
  mj_deleteModel(m);
  mj_deleteSpec(alone);
  mj_deleteSpec(world);
  for (mjSpec* drone : drones) mj_deleteSpec(drone);
}

}  // namespace
}  // namespace mjf::native
