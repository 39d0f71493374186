// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The contract's imu site sits at the centre of mass of the vehicle and its child bodies, in the
// body's axes, with the four contract sensors on it.
#include "adapt/vehicle_sensors.hpp"

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <string>
#include <vector>

#include "mjformation/scene/scene.hpp"

namespace mjf::runner {
namespace {

TEST(VehicleSensorsTest, ImuAtTheCentreOfMassInBodyAxes) {
  // 1 kg at the origin and 1 kg 0.2 m along the body's x axis; the body yawed 90 degrees.
  std::vector<std::string> notes;
  const std::string xml = AddImuAndSensors(R"(<mujoco><worldbody>
      <body name="vehicle" pos="1 2 3" euler="0 0 90"><freejoint/><geom size="0.05" mass="1"/>
        <body pos="0.2 0 0"><geom size="0.05" mass="1"/></body></body>
      </worldbody></mujoco>)",
                                           "test", &notes);
  mjModel* m = CompileModel(xml, "test");
  const int site = mj_name2id(m, mjOBJ_SITE, "imu");
  ASSERT_GE(site, 0);
  EXPECT_EQ(m->site_bodyid[site], mj_name2id(m, mjOBJ_BODY, "vehicle"));
  EXPECT_NEAR(m->site_pos[3 * site], 0.1, 1e-12);
  EXPECT_NEAR(m->site_pos[3 * site + 1], 0.0, 1e-12);
  EXPECT_NEAR(m->site_pos[3 * site + 2], 0.0, 1e-12);
  EXPECT_EQ(m->site_group[site], 5);
  for (const char* s : {"pos", "vel", "quat", "gyro"}) {
    const int id = mj_name2id(m, mjOBJ_SENSOR, s);
    ASSERT_GE(id, 0) << s;
    EXPECT_EQ(m->sensor_objtype[id], mjOBJ_SITE) << s;
    EXPECT_EQ(m->sensor_objid[id], site) << s;
  }
  EXPECT_EQ(m->sensor_type[mj_name2id(m, mjOBJ_SENSOR, "gyro")], mjSENS_GYRO);
  mj_deleteModel(m);
  EXPECT_EQ(notes.size(), 2u);
}

}  // namespace
}  // namespace mjf::runner
