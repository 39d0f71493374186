// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The contract's imu site sits at the centre of mass of the vehicle and its child bodies, in the
// body's axes, with the four contract sensors on it.
#include "vehicle_sensors.hpp"

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cstdio>
#include <string>

#include "mjformation/scene/scene.hpp"

namespace mjf::runner {
namespace {

TEST(VehicleSensorsTest, ImuAtTheCentreOfMassInBodyAxes) {
  // 1 kg at the origin and 1 kg 0.2 m along the body's x axis; the body yawed 90 degrees.
  tinyxml2::XMLDocument doc;
  ASSERT_EQ(doc.Parse(R"(<mujoco><worldbody>
      <body name="vehicle" pos="1 2 3" euler="0 0 90"><freejoint/><geom size="0.05" mass="1"/>
        <body pos="0.2 0 0"><geom size="0.05" mass="1"/></body></body>
      </worldbody></mujoco>)"),
            tinyxml2::XML_SUCCESS);
  tinyxml2::XMLElement* root = doc.RootElement();
  tinyxml2::XMLElement* body = root->FirstChildElement("worldbody")->FirstChildElement("body");
  std::vector<std::string> notes;
  AddImuAndSensors(&doc, root, body, "test", &notes);
  const tinyxml2::XMLElement* site = body->LastChildElement("site");
  ASSERT_NE(site, nullptr);
  double x = 0, y = 0, z = 0;
  ASSERT_EQ(std::sscanf(site->Attribute("pos"), "%lf %lf %lf", &x, &y, &z), 3);
  EXPECT_NEAR(x, 0.1, 1e-12);
  EXPECT_NEAR(y, 0.0, 1e-12);
  EXPECT_NEAR(z, 0.0, 1e-12);
  tinyxml2::XMLPrinter printer;
  doc.Print(&printer);
  mjModel* m = CompileModel(printer.CStr(), "test");
  for (const char* s : {"pos", "vel", "quat", "gyro"}) {
    EXPECT_GE(mj_name2id(m, mjOBJ_SENSOR, s), 0) << s;
  }
  mj_deleteModel(m);
  EXPECT_EQ(notes.size(), 2u);
}

}  // namespace
}  // namespace mjf::runner
