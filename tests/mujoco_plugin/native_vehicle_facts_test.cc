// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// One reader of a vehicle, two faces: the runner's vehicle binding (the vehicle file, as
// [vehicles] model names it) and the native plugin mjformation.attitude (the same drone with an
// instance in the MJCF) refuse the same drone for the same reason, word for word, and read a
// drone whose principal axes are not its body's the same.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "mjformation/config/experiment.hpp"
#include "mjformation/scene/vehicle_binding.hpp"

namespace mjf::native {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const char* const kRotors[] = {"m0", "m1", "m2", "m3"};

// The drone named 'vehicle' (the runner's contract), with `inside` in its body, `joint` its
// joint; `instance` true adds the attitude plugin's instance flying it.
std::string Drone(const std::string& inside, bool instance,
                  const std::string& joint = "<freejoint/>",
                  const std::string& inertial =
                      R"(<inertial pos="0 0 0" mass="1.2" diaginertia="0.012 0.012 0.022"/>)") {
  const std::string extension = instance ? R"(<extension><plugin plugin="mjformation.attitude">
      <instance name="autopilot"><config key="body" value="vehicle"/>
        <config key="actuators" value="m0 m1 m2 m3"/>
        <config key="attitude" value="plugin = 'geometric'"/></instance></plugin></extension>)"
                                         : "";
  return "<mujoco>" + extension + R"(<option timestep="0.002"/><worldbody>
    <site name="outside" pos="1 1 1"/>
    <body name="vehicle" pos="0 0 1">)" +
         joint + inertial + R"(<geom type="box" size="0.09 0.09 0.03" mass="0"/>)" + inside +
         R"(<site name="imu"/></body></worldbody><actuator>
      <general name="m0" site="s0" gear="0 0 1 0 0 -0.02" ctrlrange="0 9"/>
      <general name="m1" site="s1" gear="0 0 1 0 0 -0.02" ctrlrange="0 9"/>
      <general name="m2" site="s2" gear="0 0 1 0 0 0.02" ctrlrange="0 9"/>
      <general name="m3" site="s3" gear="0 0 1 0 0 0.02" ctrlrange="0 9"/>
    </actuator></mujoco>)";
}

constexpr char kSites[] = R"(<site name="s0" pos="0.16 -0.16 0.03"/>
  <site name="s1" pos="-0.16 0.16 0.03"/><site name="s2" pos="0.16 0.16 0.03"/>
  <site name="s3" pos="-0.16 -0.16 0.03"/>)";

fs::path Write(const std::string& xml) {
  static int files = 0;
  const fs::path path = fs::temp_directory_path() / ("mjf_facts_" + std::to_string(getpid()) + "_" +
                                                     std::to_string(++files) + ".xml");
  std::ofstream(path) << xml;
  return path;
}

// What the runner's binding reads of `xml` as the vehicle file, or its refusal in `error`.
struct RunnerRead {
  runner::VehicleBindings read;
  std::string error;
};

RunnerRead ReadByRunner(const std::string& xml) {
  const fs::path path = Write(xml);
  RunnerRead out;
  runner::ExperimentConfig config;
  config.model_path = path.string();
  mjfPlugin attitude{};
  attitude.name = "geometric";
  attitude.n_actuators = 4;
  attitude.actuators = kRotors;
  mjModel* m = mj_loadXML(path.c_str(), nullptr, nullptr, 0);  // for its gravity
  try {
    out.read = runner::DescribeVehicles(m, config, attitude);
  } catch (const std::exception& e) {
    out.error = e.what();
    // The reason alone: the runner puts the file (and the plugin naming the rotors) before it.
    for (const std::string& prefix :
         {path.string() + ": attitude plugin 'geometric': ", path.string() + ": "}) {
      if (out.error.rfind(prefix, 0) == 0) {
        out.error = out.error.substr(prefix.size());
        break;
      }
    }
  }
  if (m) mj_deleteModel(m);
  fs::remove(path);
  return out;
}

// The native plugin's refusal of `xml`, after "<config key=\"...\">: " ("" when it flies).
std::string NativeRefusal(const std::string& xml) {
  static const bool loaded = [] {
    mj_loadPluginLibrary(MJF_NATIVE_PLUGIN_LIBRARY);
    return true;
  }();
  (void)loaded;
  const fs::path path = Write(xml);
  char error[1024] = {0};
  mjModel* m = mj_loadXML(path.c_str(), nullptr, error, sizeof(error));
  fs::remove(path);
  if (m) {
    mj_deleteModel(m);
    return "";
  }
  // The last line names the instance and its key, then the reason.
  std::string reason = error;
  const size_t at = reason.rfind("\">: ");
  return at == std::string::npos ? reason : reason.substr(at + 4);
}

std::string WithoutM3(std::string xml) {
  const size_t at = xml.find(R"(<general name="m3")");
  xml.erase(at, xml.find("/>", at) + 2 - at);
  return xml;
}

// A rotor on a hinged arm, a body no joint moves, a deleted rotor: the same reason, word for
// word, from both faces.
TEST(VehicleFactsTwoFaces, TheSameRefusalsWordForWord) {
  const std::string hinged = R"(<body name="arm"><joint name="fold" type="hinge"/>
    <geom type="sphere" size="0.01" mass="0.01"/><site name="s0" pos="0.16 -0.16 0.03"/></body>
    <site name="s1" pos="-0.16 0.16 0.03"/><site name="s2" pos="0.16 0.16 0.03"/>
    <site name="s3" pos="-0.16 -0.16 0.03"/>)";
  struct Case {
    std::string runner_xml, native_xml, words;
  } cases[] = {
      {Drone(hinged, false), Drone(hinged, true), "site 's0' of body 'arm', which a joint moves"},
      {Drone(kSites, false, ""), Drone(kSites, true, ""),
       "body 'vehicle' has no joint, so it is welded to the world"},
      {WithoutM3(Drone(kSites, false)), WithoutM3(Drone(kSites, true)),
       "no actuator named 'm3' in this model (it has: m0, m1, m2)"},
  };
  for (const Case& c : cases) {
    const RunnerRead runner = ReadByRunner(c.runner_xml);
    EXPECT_THAT(runner.error, HasSubstr(c.words));
    EXPECT_EQ(NativeRefusal(c.native_xml), runner.error);
  }
}

// Principal axes turned 90 degrees about x (body_iquat not identity): the runner reads the
// body-axis moments, as the native plugin does (whose flight of such a drone
// native_attitude_test.cc holds), not the principal ones in the order MuJoCo lists them.
TEST(VehicleFactsTwoFaces, ARotatedInertialFrameIsReadInBodyAxes) {
  const std::string turned = R"(<inertial pos="0 0 0" quat="1 1 0 0" mass="1.2"
      diaginertia="0.012 0.022 0.012"/>)";
  const RunnerRead runner = ReadByRunner(Drone(kSites, false, "<freejoint/>", turned));
  ASSERT_EQ(runner.error, "");
  const mjfVehicleInfo& info = runner.read.vehicles[0].info;
  EXPECT_NEAR(info.inertia[0], 0.012, 1e-15);
  EXPECT_NEAR(info.inertia[1], 0.012, 1e-15);
  EXPECT_NEAR(info.inertia[2], 0.022, 1e-15);
  EXPECT_EQ(NativeRefusal(Drone(kSites, true, "<freejoint/>", turned)), "");
}

}  // namespace
}  // namespace mjf::native
