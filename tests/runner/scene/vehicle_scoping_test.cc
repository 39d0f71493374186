// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// What one vehicle must not bring into the shared scene is dropped or scoped, with a note each.
#include "adapt/vehicle_scoping.hpp"

#include <gtest/gtest.h>

#include <string>

namespace mjf::runner {
namespace {

const char* const kModel = R"(<mujoco>
  <size njmax="50" nkey="2"/>
  <default><geom rgba="1 0 0 1"/></default>
  <visual/>
  <worldbody>
    <light name="sun"/>
    <geom name="floor" type="plane" size="1 1 1"/>
    <body name="drone"><freejoint/><geom name="hull" size="0.1"/><light name="lamp"/>
      <site name="s"/></body>
  </worldbody>
  <actuator><motor name="m" site="s"/></actuator>
  <sensor><touch name="floor_touch" site="s"/><framepos name="p" objtype="geom" objname="floor"/>
    <framepos name="q" objtype="geom" objname="hull"/></sensor>
  <contact><pair geom1="floor" geom2="hull"/></contact>
</mujoco>)";

struct Fixture {
  Fixture() {
    EXPECT_EQ(doc.Parse(kModel), tinyxml2::XML_SUCCESS);
    root = doc.RootElement();
    body = root->FirstChildElement("worldbody")->FirstChildElement("body");
  }
  tinyxml2::XMLDocument doc;
  tinyxml2::XMLElement* root;
  tinyxml2::XMLElement* body;
  Notes notes;
};

TEST(VehicleScopingTest, WorldExtrasAndForeignSectionsAreDropped) {
  Fixture f;
  DropWorldExtras(f.body, &f.notes);
  DropSections(f.root, &f.notes);
  const tinyxml2::XMLElement* world = f.root->FirstChildElement("worldbody");
  EXPECT_EQ(world->FirstChildElement(), f.body);
  EXPECT_EQ(world->FirstChildElement()->NextSiblingElement(), nullptr);
  EXPECT_EQ(f.body->FirstChildElement("light"), nullptr);
  EXPECT_EQ(f.root->FirstChildElement("visual"), nullptr);
  // Floor, sun, lamp, <visual>: one note each.
  ASSERT_EQ(f.notes.size(), 4u);
  EXPECT_NE(f.notes[0].find("<light name=\"sun\">"), std::string::npos) << f.notes[0];
  EXPECT_NE(f.notes[3].find("<visual>"), std::string::npos) << f.notes[3];
}

TEST(VehicleScopingTest, ReferencesToDroppedElementsGo) {
  Fixture f;
  DropWorldExtras(f.body, &f.notes);
  f.notes.clear();
  DropDanglingReferences(f.root, f.body, &f.notes);
  const tinyxml2::XMLElement* sensor = f.root->FirstChildElement("sensor");
  // The touch sensor's site and the hull's framepos stay; the floor's framepos and pair go.
  ASSERT_NE(sensor->FirstChildElement("touch"), nullptr);
  EXPECT_STREQ(sensor->LastChildElement()->Attribute("name"), "q");
  EXPECT_EQ(f.root->FirstChildElement("contact")->FirstChildElement(), nullptr);
  EXPECT_EQ(f.notes.size(), 2u);
}

TEST(VehicleScopingTest, DefaultsAndSizesAreScopedToTheVehicle) {
  Fixture f;
  ScopeDefaults(&f.doc, f.root, f.body, &f.notes);
  ScopeSizes(f.root, &f.notes);
  const tinyxml2::XMLElement* def = f.root->FirstChildElement("default");
  EXPECT_EQ(def->FirstChildElement("geom"), nullptr);
  ASSERT_NE(def->FirstChildElement("default"), nullptr);
  EXPECT_STREQ(def->FirstChildElement("default")->Attribute("class"), "mjf_vehicle_defaults");
  EXPECT_STREQ(f.body->Attribute("childclass"), "mjf_vehicle_defaults");
  EXPECT_STREQ(f.root->FirstChildElement("actuator")->FirstChildElement()->Attribute("class"),
               "mjf_vehicle_defaults");
  // njmax goes (sized for one vehicle), nkey is not a memory size.
  EXPECT_EQ(f.root->FirstChildElement("size")->Attribute("njmax"), nullptr);
  EXPECT_STREQ(f.root->FirstChildElement("size")->Attribute("nkey"), "2");
  EXPECT_EQ(f.notes.size(), 2u);
}

TEST(VehicleScopingTest, ModelOptionsAreListed) {
  tinyxml2::XMLDocument doc;
  ASSERT_EQ(doc.Parse("<mujoco><option integrator=\"RK4\" density=\"1.225\" "
                      "viscosity=\"1.8e-5\"><flag energy=\"enable\"/></option></mujoco>"),
            tinyxml2::XML_SUCCESS);
  Notes notes;
  NoteModelOptions(doc.RootElement(), &notes);
  ASSERT_EQ(notes.size(), 4u);
  EXPECT_NE(notes[0].find("<option integrator=\"RK4\"> is replaced"), std::string::npos);
  EXPECT_NE(notes[1].find("density=\"1.225\"> for the whole scene: MuJoCo's fluid forces"),
            std::string::npos);
  EXPECT_NE(notes[3].find("<flag energy=\"enable\">"), std::string::npos);
}

}  // namespace
}  // namespace mjf::runner
