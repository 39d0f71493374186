// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Renaming by kind: an element and every reference to it of the same kind, nothing of another
// kind that happens to share the name.
#include "adapt/vehicle_renaming.hpp"

#include <gtest/gtest.h>

#include <string>

#include "mjformation/scene/scene.hpp"

namespace mjf::runner {
namespace {

const char* const kModel = R"(<mujoco>
  <worldbody>
    <body name="drone"><freejoint/><geom name="drone" size="0.1"/><site name="imu"/>
      <camera name="c" mode="targetbody" target="drone"/></body>
  </worldbody>
  <actuator><motor name="m" site="imu"/></actuator>
  <sensor><framepos name="pos" objtype="xbody" objname="drone"/>
    <framepos name="g" objtype="geom" objname="drone"/><gyro name="gyro" site="imu"/></sensor>
</mujoco>)";

TEST(VehicleRenamingTest, BodyAndItsReferencesOnlyAreRenamed) {
  tinyxml2::XMLDocument doc;
  ASSERT_EQ(doc.Parse(kModel), tinyxml2::XML_SUCCESS);
  tinyxml2::XMLElement* root = doc.RootElement();
  tinyxml2::XMLElement* body = root->FirstChildElement("worldbody")->FirstChildElement("body");
  std::vector<std::string> notes;
  RenameVehicleBody(root, body, "drone", "m.xml", "exp.toml:2: [vehicles] body", &notes);
  EXPECT_STREQ(body->Attribute("name"), "vehicle");
  EXPECT_STREQ(body->FirstChildElement("geom")->Attribute("name"), "drone");  // a geom
  EXPECT_STREQ(body->FirstChildElement("camera")->Attribute("target"), "vehicle");
  const tinyxml2::XMLElement* sensor = root->FirstChildElement("sensor");
  EXPECT_STREQ(sensor->FirstChildElement()->Attribute("objname"), "vehicle");  // xbody
  EXPECT_STREQ(sensor->FirstChildElement()->NextSiblingElement()->Attribute("objname"), "drone");
  ASSERT_EQ(notes.size(), 1u);
}

TEST(VehicleRenamingTest, ContractNamesOfTheModelStepAside) {
  tinyxml2::XMLDocument doc;
  ASSERT_EQ(doc.Parse(kModel), tinyxml2::XML_SUCCESS);
  tinyxml2::XMLElement* root = doc.RootElement();
  std::vector<std::string> notes;
  MakeRoomForContractNames(root, &notes);
  const tinyxml2::XMLElement* body =
      root->FirstChildElement("worldbody")->FirstChildElement("body");
  EXPECT_STREQ(body->FirstChildElement("site")->Attribute("name"), "model_imu");
  EXPECT_STREQ(root->FirstChildElement("actuator")->FirstChildElement()->Attribute("site"),
               "model_imu");
  const tinyxml2::XMLElement* sensor = root->FirstChildElement("sensor");
  EXPECT_STREQ(sensor->FirstChildElement()->Attribute("name"), "model_pos");
  EXPECT_STREQ(sensor->LastChildElement()->Attribute("name"), "model_gyro");
  EXPECT_STREQ(sensor->LastChildElement()->Attribute("site"), "model_imu");
  EXPECT_EQ(notes.size(), 3u);  // the site, pos, gyro
}

TEST(VehicleRenamingTest, NestedBodyNamedVehicleIsRefused) {
  tinyxml2::XMLDocument doc;
  ASSERT_EQ(doc.Parse("<mujoco><worldbody><body name=\"d\"><freejoint/><body name=\"vehicle\"/>"
                      "</body></worldbody></mujoco>"),
            tinyxml2::XML_SUCCESS);
  tinyxml2::XMLElement* root = doc.RootElement();
  std::vector<std::string> notes;
  EXPECT_THROW(
      RenameVehicleBody(root, root->FirstChildElement("worldbody")->FirstChildElement("body"), "d",
                        "m.xml", "here", &notes),
      SceneError);
}

}  // namespace
}  // namespace mjf::runner
