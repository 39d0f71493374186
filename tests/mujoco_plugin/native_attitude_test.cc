// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// mjformation.attitude on drones written as MuJoCo users write them: an inertia whose principal
// axes are not the body's (a rotated <inertial>, a full inertia), and an actuator that is not a
// rotor (a gimbal's orientation servo, 4 controls and 3 force outputs) declared before the
// rotors. Each drone starts tilted and yawed 0.4 m from (0, 0, 1) m, which it then holds: its
// rates and inertia matter. MuJoCo's C API alone flies it.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "drone_mjcf.hpp"

namespace mjf::native {
namespace {

namespace fs = std::filesystem;

using mjf::testing::Arms;
using mjf::testing::DroneXml;
using mjf::testing::kBodyAligned;

struct Flight {
  bool flew = false;   // the model compiled and its data (the plugin's init) was made
  double hold = 1e9;   // m, largest distance from (0, 0, 1) over the last second
  double final_z = 0;  // m
  std::string error;   // the compiler's, when it refused
};

// Flies the drone for `seconds` with mj_step, with d->ctrl of actuator `trimmed` (if given)
// set to `trim` throughout.
Flight Fly(const std::string& xml, double seconds, const char* trimmed = nullptr, double trim = 0) {
  static const bool loaded = [] {
    mj_loadPluginLibrary(MJF_NATIVE_PLUGIN_LIBRARY);
    return true;
  }();
  (void)loaded;
  // A name per flight: no two models are ever read from one path.
  static int flights = 0;
  const fs::path path = fs::temp_directory_path() / ("mjf_attitude_" + std::to_string(getpid()) +
                                                     "_" + std::to_string(++flights) + ".xml");
  std::ofstream(path) << xml;
  Flight f;
  char error[1024] = {0};
  mjModel* m = mj_loadXML(path.c_str(), nullptr, error, sizeof(error));
  fs::remove(path);
  f.error = error;
  if (!m) return f;
  mjData* d = mj_makeData(m);
  if (d) {
    f.flew = true;
    f.hold = 0;
    if (trimmed) d->ctrl[m->actuator_ctrladr[mj_name2id(m, mjOBJ_ACTUATOR, trimmed)]] = trim;
    const int body = mj_name2id(m, mjOBJ_BODY, "quad");
    const double target[3] = {0, 0, 1};
    // Counted steps, not d->time: MuJoCo resets a diverging simulation to time 0.
    const int steps = static_cast<int>(std::lround(seconds / m->opt.timestep));
    const int last_second = static_cast<int>(std::lround(1.0 / m->opt.timestep));
    for (int k = 0; k < steps; ++k) {
      mj_step(m, d);
      if (k >= steps - last_second) {
        f.hold = std::max(f.hold, mju_dist3(d->xpos + 3 * body, target));
      }
    }
    f.final_z = d->xpos[3 * body + 2];
    mj_deleteData(d);
  }
  mj_deleteModel(m);
  return f;
}

constexpr double kSeconds = 12.0;

// The same drone, its inertia given in principal axes turned 90 degrees about x: the body-frame
// tensor is the body-aligned one exactly, so the flight is the same to rounding.
TEST(NativeAttitude, RotatedInertialIsTheSameDrone) {
  const Flight aligned = Fly(DroneXml(kBodyAligned, false), kSeconds);
  const Flight rotated = Fly(DroneXml(R"(<inertial pos="0 0 0" quat="1 1 0 0" mass="1.2"
      diaginertia="0.012 0.022 0.012"/>)",
                                      false),
                             kSeconds);
  ASSERT_TRUE(aligned.flew) << aligned.error;
  EXPECT_LT(aligned.hold, 0.005) << "final z " << aligned.final_z;
  ASSERT_TRUE(rotated.flew) << rotated.error;
  EXPECT_LT(rotated.hold, 0.005) << "final z " << rotated.final_z;
  EXPECT_NEAR(rotated.final_z, aligned.final_z, 1e-6);
}

// A full inertia with products (principal axes 45 degrees off the body's): the controller
// takes the body-axis moments and still holds the point.
TEST(NativeAttitude, FullInertiaHolds) {
  const Flight f = Fly(DroneXml(R"(<inertial pos="0 0 0" mass="1.2"
      fullinertia="0.012 0.012 0.022 0.002 0 0"/>)",
                                false),
                       kSeconds);
  ASSERT_TRUE(f.flew) << f.error;
  EXPECT_LT(f.hold, 0.005) << "final z " << f.final_z;
}

// A gimbal servo (4 controls, 3 force outputs) before the rotors: the rotors' gear, ctrlrange
// and force are found at their own addresses, and the drone flies.
TEST(NativeAttitude, GimbalActuatorBeforeTheRotorsFlies) {
  const Flight f = Fly(DroneXml(kBodyAligned, true), kSeconds);
  ASSERT_TRUE(f.flew) << f.error;
  EXPECT_LT(f.hold, 0.005) << "final z " << f.final_z;
}

// ctrl of a driven rotor is a trim on the controller's command (docs/PLUGINS.md, "Actuation"):
// a constant trim on one rotor moves the drone, and a zero trim is the plain flight.
TEST(NativeAttitude, CtrlTrimsARotor) {
  const std::string xml = DroneXml(kBodyAligned, true);
  const Flight plain = Fly(xml, 2.0);
  const Flight zero = Fly(xml, 2.0, "m_front_right", 0.0);
  const Flight trimmed = Fly(xml, 2.0, "m_front_right", 0.5);
  ASSERT_TRUE(plain.flew) << plain.error;
  EXPECT_EQ(zero.final_z, plain.final_z);
  EXPECT_EQ(zero.hold, plain.hold);
  EXPECT_GT(std::fabs(trimmed.hold - plain.hold), 1e-4) << trimmed.hold << " vs " << plain.hold;
}

// Rotor sites on a fixed child body: the arms are carried through the child's frame, and the
// flight is the drone's with the sites on its body, to rounding.
TEST(NativeAttitude, RotorSitesOnAChildBodyAreTheSameDrone) {
  const Flight on_body = Fly(DroneXml(kBodyAligned, false), kSeconds);
  const Flight on_frame = Fly(DroneXml(kBodyAligned, false, Arms::kOnFrame), kSeconds);
  ASSERT_TRUE(on_frame.flew) << on_frame.error;
  EXPECT_LT(on_frame.hold, 0.005) << "final z " << on_frame.final_z;
  EXPECT_NEAR(on_frame.final_z, on_body.final_z, 1e-6);
}

// A rotor on a body that a joint moves has no fixed arm: refused, naming the site and the body.
TEST(NativeAttitude, RotorSiteOnAJointedBodyIsRefused) {
  const Flight f = Fly(DroneXml(kBodyAligned, false, Arms::kOnHingedFrame), 0.1);
  EXPECT_FALSE(f.flew);
  EXPECT_NE(f.error.find("site 's_front_right'"), std::string::npos) << f.error;
  EXPECT_NE(f.error.find("'frame'"), std::string::npos) << f.error;
}

// Configuration errors name the attribute the MJCF's author wrote, not a line of text the plugin
// built; a plugin_path may hold a quote.
TEST(NativeAttitude, ConfigErrorsNameTheAttribute) {
  std::string xml = DroneXml(kBodyAligned, false);
  const std::string tuned = "plugin = 'geometric', tilt_max = 0.5";
  xml.replace(xml.find(tuned), tuned.size(), "plugin = 'geometric', tilt_maxx = 0.5");
  const Flight unknown = Fly(xml, 0.1);
  EXPECT_FALSE(unknown.flew);
  EXPECT_NE(unknown.error.find("<config key=\"attitude\"> tilt_maxx"), std::string::npos)
      << unknown.error;
  EXPECT_EQ(unknown.error.find("autopilot':2"), std::string::npos) << unknown.error;

  xml = DroneXml(kBodyAligned, false);
  const std::string guidance = "plugin = 'hover', position = '0 0 1'";
  xml.replace(xml.find(guidance), guidance.size(), "plugin = 'hoover'");
  const Flight misnamed = Fly(xml, 0.1);
  EXPECT_FALSE(misnamed.flew);
  EXPECT_NE(misnamed.error.find("<config key=\"guidance\">"), std::string::npos) << misnamed.error;

  xml = DroneXml(kBodyAligned, false);
  xml.replace(xml.find("<config key=\"body\""), 0,
              "<config key=\"plugin_path\" value=\"/nowhere/a&quot;b\"/>\n        ");
  const Flight quoted = Fly(xml, 0.1);  // a folder that does not exist is searched, not refused
  EXPECT_TRUE(quoted.flew) << quoted.error;
}

// Two instances naming one actuator: refused while the model compiles, naming both.
TEST(NativeAttitude, AnActuatorDrivenTwiceIsRefused) {
  std::string xml = DroneXml(kBodyAligned, false);
  const std::string second = R"(<instance name="copilot">
        <config key="body" value="quad"/>
        <config key="actuators" value="m_back_right"/>
        <config key="attitude" value="plugin = 'geometric'"/>
      </instance>
    </plugin>)";
  xml.replace(xml.find("</plugin>"), 9, second);
  const Flight f = Fly(xml, 0.1);
  EXPECT_FALSE(f.flew);
  EXPECT_NE(f.error.find("'m_back_right' is driven by instance"), std::string::npos) << f.error;
  EXPECT_NE(f.error.find("autopilot"), std::string::npos) << f.error;
  EXPECT_NE(f.error.find("copilot"), std::string::npos) << f.error;
}

}  // namespace
}  // namespace mjf::native
