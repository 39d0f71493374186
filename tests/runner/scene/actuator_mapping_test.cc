// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Rotor actuators mapped onto the plugin's names: permutations, a non-rotor actuator that holds
// a contract name, a rotor acting on a site off the vehicle.
#include "adapt/actuator_mapping.hpp"

#include <gtest/gtest.h>

#include <string>

#include "error_of.hpp"
#include "mjformation/scene/scene.hpp"

namespace mjf::runner {
namespace {

const char* const kModel = R"(<mujoco>
  <worldbody>
    <site name="world_site"/>
    <body name="vehicle"><freejoint/><site name="s0"/><site name="s1"/></body>
  </worldbody>
  <actuator><motor name="rotor0" site="s1"/><motor name="rotor1" site="s0"/>
    <motor name="a" site="s0"/><motor name="b" site="world_site"/></actuator>
  <sensor><actuatorfrc name="f" actuator="rotor0"/></sensor>
</mujoco>)";

VehicleMapping Mapping(std::vector<std::string> rotors) {
  VehicleMapping m;
  m.model_path = "m.xml";
  m.body = "vehicle";
  m.rotors = std::move(rotors);
  m.actuator_names = {"rotor0", "rotor1"};
  m.rotors_where = "exp.toml:4: [vehicles] rotors";
  return m;
}

struct Fixture {
  Fixture() {
    EXPECT_EQ(doc.Parse(kModel), tinyxml2::XML_SUCCESS);
    root = doc.RootElement();
    body = root->FirstChildElement("worldbody")->FirstChildElement("body");
  }
  std::string Name(int k) const {
    const tinyxml2::XMLElement* a = root->FirstChildElement("actuator")->FirstChildElement();
    for (int i = 0; i < k; ++i) a = a->NextSiblingElement();
    return a->Attribute("name");
  }
  tinyxml2::XMLDocument doc;
  tinyxml2::XMLElement* root;
  tinyxml2::XMLElement* body;
  std::vector<std::string> notes;
};

TEST(ActuatorMappingTest, PermutationAndSteppingAsideWork) {
  Fixture f;
  // rotor0 of the plugin is the model's rotor1 and the other way round; "a" holds nothing.
  MapRotors(f.root, f.body, Mapping({"rotor1", "rotor0"}), &f.notes);
  EXPECT_EQ(f.Name(0), "rotor1");
  EXPECT_EQ(f.Name(1), "rotor0");
  // The sensor follows its actuator.
  EXPECT_STREQ(f.root->FirstChildElement("sensor")->FirstChildElement()->Attribute("actuator"),
               "rotor1");
  EXPECT_EQ(f.notes.size(), 2u);
  Fixture g;
  MapRotors(g.root, g.body, Mapping({"a", "rotor0"}), &g.notes);
  EXPECT_EQ(g.Name(0), "rotor1");        // the model's rotor0, now the plugin's rotor1
  EXPECT_EQ(g.Name(1), "model_rotor1");  // not a rotor, held a contract name
  EXPECT_EQ(g.Name(2), "rotor0");        // the model's "a"
}

std::string ErrorOf(const VehicleMapping& m) {
  Fixture f;
  return mjf::testing::ErrorOf<SceneError>([&] { MapRotors(f.root, f.body, m, &f.notes); },
                                           "(no error)");
}

TEST(ActuatorMappingTest, BadRotorsAreRefusedNamingTheKey) {
  EXPECT_NE(ErrorOf(Mapping({"a"})).find("lists 1 rotors of m.xml; the attitude plugin drives 2"),
            std::string::npos);
  EXPECT_NE(ErrorOf(Mapping({"a", "a"})).find("'a' is listed twice"), std::string::npos);
  EXPECT_NE(ErrorOf(Mapping({"a", "zz"}))
                .find("no actuator named 'zz' (its actuators: rotor0, "
                      "rotor1, a, b)"),
            std::string::npos);
  const std::string off = ErrorOf(Mapping({"a", "b"}));
  EXPECT_NE(off.find("exp.toml:4: [vehicles] rotors: m.xml:7: rotor 'b' acts on site "
                     "'world_site'"),
            std::string::npos)
      << off;
}

}  // namespace
}  // namespace mjf::runner
