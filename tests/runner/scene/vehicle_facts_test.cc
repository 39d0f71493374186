// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The one reader of a vehicle's facts (runner/scene/src/vehicle_facts.cc) on drones written as
// MuJoCo users write them: placed off the origin and turned, an inertia whose principal axes are
// not the body's, rotor sites on a fixed child body, a gimbal servo before the rotors.
#include "mjformation/scene/vehicle_facts.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace mjf::runner {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

const std::vector<std::string> kRotors = {"m0", "m1", "m2", "m3"};

// `inertial` the body's <inertial>, `inside` what else the body holds (sites, child bodies),
// `joint` its joint, `extra` actuators declared before the rotors.
std::string Drone(const std::string& inertial, const std::string& inside,
                  const std::string& joint = "<freejoint/>", const std::string& extra = "") {
  return R"(<mujoco><worldbody><site name="outside" pos="1 1 1"/>
    <body name="quad" pos="0.3 -0.2 45.1" euler="0.2 0.1 0.3">)" +
         joint + inertial + R"(<geom type="box" size="0.09 0.09 0.03" mass="0"/>)" + inside +
         R"(</body></worldbody><actuator>)" + extra + R"(
      <general name="m0" site="s0" gear="0 0 1 0 0 -0.02" ctrlrange="0 9" dyntype="filter"
               dynprm="0.03"/>
      <general name="m1" site="s1" gear="0 0 1 0 0 -0.02" ctrlrange="0 9"/>
      <general name="m2" site="s2" gear="0 0 1 0 0 0.02" ctrlrange="0 8"/>
      <general name="m3" site="s3" gear="0 0 1 0 0 0.02" ctrlrange="0 9"/>
    </actuator></mujoco>)";
}

constexpr char kAligned[] =
    R"(<inertial pos="0.01 -0.02 0.005" mass="1.2" diaginertia="0.012 0.014 0.022"/>)";
constexpr char kSitesOnBody[] = R"(<site name="s0" pos="0.16 -0.16 0.03"/>
  <site name="s1" pos="-0.16 0.16 0.03"/><site name="s2" pos="0.16 0.16 0.03"/>
  <site name="s3" pos="-0.16 -0.16 0.03"/>)";

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
using Model = std::unique_ptr<mjModel, ModelDeleter>;

Model Compile(const std::string& xml) {
  char error[512] = {0};
  mjSpec* spec = mj_parseXMLString(xml.c_str(), nullptr, error, sizeof(error));
  EXPECT_NE(spec, nullptr) << error;
  mjModel* m = spec ? mj_compile(spec, nullptr) : nullptr;
  EXPECT_NE(m, nullptr) << (spec ? mjs_getError(spec) : "");
  if (spec) mj_deleteSpec(spec);
  return Model(m);
}

// The refusal of ReadVehicleFacts on `xml`, with its key ("" when it reads).
std::pair<std::string, std::string> Refusal(const std::string& xml,
                                            const std::vector<std::string>& rotors = kRotors) {
  Model m = Compile(xml);
  if (!m) return {"", "no model"};
  try {
    ReadVehicleFacts(m.get(), "quad", rotors);
  } catch (const VehicleFactError& e) {
    return {e.key(), e.what()};
  }
  return {"", ""};
}

// The arms are R^T (site_xpos - xipos) of mj_forward to the bit, for a drone off the origin and
// turned, its sites on the body or on a fixed child body turned about z: the runner's arithmetic.
TEST(VehicleFacts, ArmsAreThoseOfForwardKinematicsToTheBit) {
  const std::string on_frame = R"(<body name="frame" pos="0.01 0.02 -0.01" euler="0 0 90">
    <site name="s0" pos="-0.16 -0.16 0.03"/><site name="s1" pos="0.16 0.16 0.03"/>
    <site name="s2" pos="0.16 -0.16 0.03"/><site name="s3" pos="-0.16 0.16 0.03"/></body>)";
  const std::string layouts[] = {kSitesOnBody, on_frame};
  // Rotor 0's arm along body x: 0.16 - 0.01 on the body; 0.16 + 0.01 - 0.01 through the frame.
  const double arm0_x[] = {0.15, 0.16};
  for (int layout = 0; layout < 2; ++layout) {
    Model m = Compile(Drone(kAligned, layouts[layout]));
    ASSERT_TRUE(m);
    const VehicleFacts f = ReadVehicleFacts(m.get(), "quad", kRotors);
    mjData* d = mj_makeData(m.get());
    mj_forward(m.get(), d);
    for (int k = 0; k < 4; ++k) {
      double rel[3], arm[3];
      mju_sub3(rel, d->site_xpos + 3 * f.sites[k], d->xipos + 3 * f.body);
      mju_mulMatTVec(arm, d->xmat + 9 * f.body, rel, 3, 3);
      for (int i = 0; i < 3; ++i) EXPECT_EQ(f.info[k].site_pos[i], arm[i]) << k << " " << i;
    }
    mj_deleteData(d);
    EXPECT_NEAR(f.info[0].site_pos[0], arm0_x[layout], 1e-12);
  }
}

// Inertia given in principal axes turned 90 degrees about x (iquat not identity): read in body
// axes, the same moments as the body-aligned <inertial>.
TEST(VehicleFacts, InertiaIsReadInBodyAxes) {
  Model aligned = Compile(Drone(kAligned, kSitesOnBody));
  Model turned = Compile(Drone(R"(<inertial pos="0.01 -0.02 0.005" quat="1 1 0 0" mass="1.2"
      diaginertia="0.012 0.022 0.014"/>)",
                               kSitesOnBody));
  ASSERT_TRUE(aligned && turned);
  const int body = mj_name2id(turned.get(), mjOBJ_BODY, "quad");
  ASSERT_GT(std::abs(turned->body_iquat[4 * body + 1]), 0.5);  // principal axes not the body's
  const VehicleFacts a = ReadVehicleFacts(aligned.get(), "quad", kRotors);
  const VehicleFacts t = ReadVehicleFacts(turned.get(), "quad", kRotors);
  EXPECT_DOUBLE_EQ(t.mass, 1.2);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(t.inertia[i], a.inertia[i], 1e-15) << i;
  EXPECT_NEAR(t.inertia[1], 0.014, 1e-15);
}

// A gimbal servo (4 controls, 3 force outputs) before the rotors: each rotor's gear, control
// range and lag are found at its own addresses; the gimbal is left alone and listed.
TEST(VehicleFacts, AGimbalBeforeTheRotorsIsIgnoredAndListed) {
  const std::string gimbal = R"(<body name="gimbal" pos="0 0 -0.05"><joint name="g" type="ball"/>
    <geom type="sphere" size="0.02" mass="0.02"/></body>)";
  Model m = Compile(Drone(kAligned, std::string(kSitesOnBody) + gimbal, "<freejoint/>",
                          R"(<orientation name="gimbal" joint="g" kp="0.01" input="quat"/>)"));
  ASSERT_TRUE(m);
  const VehicleFacts f = ReadVehicleFacts(m.get(), "quad", kRotors);
  EXPECT_THAT(f.ignored, ElementsAre("gimbal"));
  EXPECT_EQ(f.info[2].ctrl_max, 8);
  EXPECT_EQ(f.info[2].gear[5], 0.02);
  EXPECT_EQ(f.info[2].gear[2], 1);
  EXPECT_EQ(f.info[0].time_constant, 0.03);
  EXPECT_EQ(f.info[1].time_constant, 0);
  EXPECT_NEAR(f.mass, 1.22, 1e-12);  // the subtree's
}

TEST(VehicleFacts, RefusalsNameWhatIsWrong) {
  const std::string hinged = R"(<body name="arm"><joint name="fold" type="hinge"/>
    <geom type="sphere" size="0.01" mass="0.01"/><site name="s0" pos="0.16 -0.16 0.03"/></body>
    <site name="s1" pos="-0.16 0.16 0.03"/><site name="s2" pos="0.16 0.16 0.03"/>
    <site name="s3" pos="-0.16 -0.16 0.03"/>)";
  auto r = Refusal(Drone(kAligned, hinged));
  EXPECT_EQ(r.first, "actuators");
  EXPECT_THAT(r.second, HasSubstr("site 's0' of body 'arm', which a joint moves"));

  std::string outside = Drone(kAligned, kSitesOnBody);
  outside.replace(outside.find(R"(site="s3")"), 9, R"(site="outside")");
  r = Refusal(outside);
  EXPECT_THAT(r.second, HasSubstr("site 'outside', which is not on the vehicle's body"));

  r = Refusal(Drone(kAligned, kSitesOnBody), {"m0", "m1", "m9", "m3"});
  EXPECT_EQ(r.first, "actuators");
  EXPECT_EQ(r.second, "no actuator named 'm9' in this model (it has: m0, m1, m2, m3)");

  r = Refusal(Drone(kAligned, kSitesOnBody, ""));
  EXPECT_EQ(r.first, "body");
  EXPECT_THAT(r.second, HasSubstr("body 'quad' has no joint, so it is welded to the world"));

  const std::string gimbal = R"(<body name="gimbal"><joint name="g" type="ball"/>
    <geom type="sphere" size="0.02" mass="0.02"/></body>)";
  r = Refusal(Drone(kAligned, std::string(kSitesOnBody) + gimbal, "<freejoint/>",
                    R"(<orientation name="gimbal" joint="g" kp="0.01" input="quat"/>)"),
              {"m0", "m1", "gimbal", "m3"});
  EXPECT_THAT(r.second, HasSubstr("actuator 'gimbal' takes 4 controls and has 3 force outputs"));
}

}  // namespace
}  // namespace mjf::runner
