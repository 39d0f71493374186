// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// An MJCF file read as MuJoCo reads it: includes inlined (nested too), repeated sections merged,
// a missing include refused with its line.
#include "adapt/mjcf_document.hpp"

#include <gtest/gtest.h>

#include <string>

#include "mjformation/scene/scene.hpp"
#include "test_util.hpp"

namespace mjf::runner::mjcf {
namespace {

using mjf::testing::TempDir;
using mjf::testing::WriteFile;

TEST(MjcfDocumentTest, IncludesAreInlinedAndSectionsMerged) {
  const std::string dir = TempDir("mjcf_document");
  WriteFile(dir + "/inner.xml", "<mujoco><option timestep=\"0.004\"/></mujoco>");
  WriteFile(dir + "/outer.xml",
            "<mujoco><include file=\"inner.xml\"/><actuator><motor name=\"b\"/></actuator>"
            "</mujoco>");
  const std::string path = WriteFile(
      dir + "/model.xml",
      "<mujoco>\n<option timestep=\"0.002\" integrator=\"RK4\"/>\n<actuator><motor name=\"a\"/>"
      "</actuator>\n<include file=\"outer.xml\"/>\n</mujoco>");
  tinyxml2::XMLDocument doc;
  tinyxml2::XMLElement* root = ReadModelDocument(path, dir, "exp.toml:3: [vehicles] body", &doc);
  // One <option>: the later timestep wins, the earlier integrator stays.
  ASSERT_NE(root->FirstChildElement("option"), nullptr);
  EXPECT_EQ(root->FirstChildElement("option")->NextSiblingElement("option"), nullptr);
  EXPECT_STREQ(root->FirstChildElement("option")->Attribute("timestep"), "0.004");
  EXPECT_STREQ(root->FirstChildElement("option")->Attribute("integrator"), "RK4");
  // One <actuator> with both motors, in file order.
  const tinyxml2::XMLElement* act = root->FirstChildElement("actuator");
  ASSERT_NE(act, nullptr);
  EXPECT_EQ(act->NextSiblingElement("actuator"), nullptr);
  EXPECT_STREQ(act->FirstChildElement()->Attribute("name"), "a");
  EXPECT_STREQ(act->LastChildElement()->Attribute("name"), "b");
  EXPECT_EQ(root->FirstChildElement("include"), nullptr);
}

TEST(MjcfDocumentTest, MissingIncludeIsRefusedWithItsLine) {
  const std::string dir = TempDir("mjcf_document_missing");
  const std::string path =
      WriteFile(dir + "/model.xml", "<mujoco>\n\n<include file=\"gone.xml\"/>\n</mujoco>");
  tinyxml2::XMLDocument doc;
  try {
    ReadModelDocument(path, dir, "exp.toml:3: [vehicles] body", &doc);
    FAIL() << "a missing include was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find(path + ":3: <include file=\"gone.xml\">"),
              std::string::npos)
        << e.what();
  }
}

TEST(MjcfDocumentTest, NotMjcfIsRefused) {
  const std::string dir = TempDir("mjcf_document_root");
  const std::string path = WriteFile(dir + "/model.xml", "<robot/>");
  tinyxml2::XMLDocument doc;
  EXPECT_THROW(ReadModelDocument(path, dir, "here", &doc), SceneError);
}

}  // namespace
}  // namespace mjf::runner::mjcf
