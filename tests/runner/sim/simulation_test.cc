// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Bad input found while a simulation is set up (plugins, MJCF, topology, parameters): every case
// gets one clear message naming the file (and line/key) and is refused before anything runs.
//
// Unit tests of the source:
// runner/sim/src/simulation.cc: Euler angles of known rotations, the step counter and clock, what a
// simulation exposes, and a non-finite state stopping it with a SimulationError naming the time.
#include "mjformation/sim/simulation.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "error_of.hpp"
#include "mjformation/config/config.hpp"
#include "mjformation/control/plugin_host.hpp"
#include "mjformation/scene/scene.hpp"
#include "point_mass_util.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

using mjf::testing::HoverExperiment;
using mjf::testing::Parse;
using ::testing::AllOf;
using ::testing::HasSubstr;

using mjf::testing::ErrorOf;

TEST(SetupErrorTest, UnknownPluginListsAvailable) {
  std::string text = HoverExperiment();
  text.replace(text.find("plugin = \"pd_cascade\""), 21, "plugin = \"pd_cascad\"");
  ExperimentConfig c = Parse(text, "p.toml");
  EXPECT_THAT(ErrorOf([&] { Simulation sim(c); }),
              AllOf(HasSubstr("p.toml:"), HasSubstr("[attitude]"), HasSubstr("'pd_cascad'"),
                    HasSubstr("available:"), HasSubstr("pd_cascade")));
}

TEST(SetupErrorTest, AbiMismatchIsNamed) {
  std::string text = HoverExperiment();
  text.replace(text.find("[leader]\nplugin = \"hover\""), 25, "[leader]\nplugin = \"future_abi\"");
  ExperimentConfig c = Parse(text);
  EXPECT_THAT(
      ErrorOf([&] { Simulation sim(c); }),
      AllOf(HasSubstr("future_abi"), HasSubstr("libmjf_test_badabi.so"), HasSubstr("ABI 99"),
            HasSubstr("speaks ABI " + std::to_string(MJF_ABI_VERSION))));
}

TEST(SetupErrorTest, MissingRequiredAttribute) {
  std::string text = HoverExperiment();
  text.replace(text.find("[leader]\nplugin = \"hover\""), 25,
               "[leader]\nplugin = \"test_required\"");
  ExperimentConfig c = Parse(text);
  EXPECT_THAT(ErrorOf([&] { Simulation sim(c); }),
              AllOf(HasSubstr("[leader] value"), HasSubstr("requires attribute 'value'")));
}

TEST(SetupErrorTest, UnknownAttributeListsDeclared) {
  std::string text = HoverExperiment();
  text += "";
  text.replace(text.find("plugin = \"pd_cascade\""), 21, "plugin = \"pd_cascade\"\nkp_attt = 3.0");
  ExperimentConfig c = Parse(text);
  EXPECT_THAT(ErrorOf([&] { Simulation sim(c); }),
              AllOf(HasSubstr("[attitude] kp_attt"), HasSubstr("no attribute 'kp_attt'"),
                    HasSubstr("its attributes:")));
}

// A gain the geometric attitude plugin refuses (att_bw above rate_bw / 2 breaks the cascade):
// FILE:LINE: [attitude], the key and the reason, before the first step.
TEST(SetupErrorTest, GeometricBadGainNamesFileSectionAndKey) {
  std::string text = HoverExperiment();
  text.replace(text.find("plugin = \"pd_cascade\""), 21, "plugin = \"geometric\"\natt_bw = 50.0");
  ExperimentConfig c = Parse(text, "p.toml");
  EXPECT_THAT(ErrorOf([&] { Simulation sim(c); }),
              AllOf(HasSubstr("p.toml:"), HasSubstr("[attitude]"), HasSubstr("'geometric'"),
                    HasSubstr("att_bw"), HasSubstr("cascade separation")));
}

TEST(SetupErrorTest, PluginOfWrongKind) {
  std::string text = HoverExperiment();
  text.replace(text.find("[leader]\nplugin = \"hover\""), 25, "[leader]\nplugin = \"pd_cascade\"");
  EXPECT_THAT(ErrorOf([&] { Simulation sim(Parse(text)); }),
              AllOf(HasSubstr("[leader]"), HasSubstr("needs a guidance plugin")));
}

TEST(SetupErrorTest, MjcfThatFailsToLoad) {
  const std::string dir = mjf::testing::TempDir("mjcf");
  mjf::testing::WriteFile(dir + "/broken.xml",
                          "<mujoco><worldbody><body name=\"vehicle\"><geom type=\"sphere\" "
                          "size=\"-1\"/><freejoint/></body></worldbody></mujoco>");
  std::string text = HoverExperiment();
  text.replace(text.find("model = \"quadrotor\""), 19, "model = \"broken.xml\"");
  ExperimentConfig c = mjf::runner::LoadExperiment(mjf::testing::WriteFile(dir + "/e.toml", text));
  EXPECT_THAT(ErrorOf([&] { Simulation sim(c); }),
              AllOf(HasSubstr("broken.xml"), HasSubstr("MuJoCo cannot load")));
  mjf::testing::WriteFile(dir + "/notxml.xml", "<mujoco><worldbody>");
  text.replace(text.find("broken.xml"), 10, "notxml.xml");
  c = mjf::runner::LoadExperiment(mjf::testing::WriteFile(dir + "/e.toml", text));
  EXPECT_THAT(ErrorOf([&] { Simulation sim(c); }),
              AllOf(HasSubstr("notxml.xml:"), HasSubstr("cannot read the vehicle model")));
}

TEST(SetupErrorTest, VehicleWithoutSensors) {
  const std::string dir = mjf::testing::TempDir("nosensor");
  mjf::testing::WriteFile(
      dir + "/bare.xml",
      "<mujoco><worldbody><body name=\"vehicle\"><freejoint/><geom type=\"sphere\" size=\"0.1\"/>"
      "<site name=\"rotor0\"/><site name=\"rotor1\"/><site name=\"rotor2\"/><site name=\"rotor3\"/>"
      "</body></worldbody><actuator><general name=\"rotor0\" site=\"rotor0\" gear=\"0 0 1 0 0 0\"/>"
      "<general name=\"rotor1\" site=\"rotor1\" gear=\"0 0 1 0 0 0\"/><general name=\"rotor2\" "
      "site=\"rotor2\" gear=\"0 0 1 0 0 0\"/><general name=\"rotor3\" site=\"rotor3\" "
      "gear=\"0 0 1 0 0 0\"/></actuator></mujoco>");
  std::string text = HoverExperiment();
  text.replace(text.find("model = \"quadrotor\""), 19, "model = \"bare.xml\"");
  ExperimentConfig c = mjf::runner::LoadExperiment(mjf::testing::WriteFile(dir + "/e.toml", text));
  EXPECT_THAT(ErrorOf([&] { Simulation sim(c); }),
              AllOf(HasSubstr("bare.xml"), HasSubstr("needs a sensor named 'pos'")));
}

TEST(SetupErrorTest, VehicleWithoutThePluginsActuators) {
  std::string text = HoverExperiment();
  text.replace(text.find("model = \"quadrotor\""), 19, "model = \"pointmass\"");
  EXPECT_THAT(ErrorOf([&] { Simulation sim(Parse(text)); }),
              AllOf(HasSubstr("pointmass.xml"), HasSubstr("'pd_cascade'"), HasSubstr("'rotor0'"),
                    HasSubstr("no actuator named")));
}

TEST(SetupErrorTest, TopologyWithoutSpanningTree) {
  std::string text =
      "[vehicles]\nfollowers = 4\n[topology]\nleader_links = [1]\nedges = [[1, 2], [4, 3]]\n"
      "[leader]\nplugin = \"circle\"\n[formation]\nplugin = \"smc_discrete\"\n"
      "[formation.shape]\ntype = \"circle\"\n";
  EXPECT_THAT(ErrorOf([&] { Simulation sim(Parse(text, "tree.toml")); }),
              AllOf(HasSubstr("tree.toml"), HasSubstr("[topology]"), HasSubstr("spanning tree"),
                    HasSubstr("3, 4")));
}

TEST(SetupErrorTest, ParametersBreakingTheoremTwo) {
  std::string text =
      "[vehicles]\nfollowers = 2\n[topology]\nleader_links = [1]\nedges = [[1, 2]]\n"
      "[leader]\nplugin = \"circle\"\n[formation]\nplugin = \"smc_discrete\"\nperiod = 0.05\n"
      "q = 30.0\n[formation.shape]\ntype = \"circle\"\n";
  EXPECT_THAT(ErrorOf([&] { Simulation sim(Parse(text, "q.toml")); }),
              AllOf(HasSubstr("q.toml"), HasSubstr("[formation]"), HasSubstr("smc_discrete"),
                    HasSubstr("1 - q*T")));
}

using mjf::testing::Parse;
using mjf::testing::PointMassExperiment;
using ::testing::HasSubstr;

// w-x-y-z quaternion of a rotation by `angle` about the unit axis (x, y, z).
std::array<double, 4> AxisAngle(double x, double y, double z, double angle) {
  const double s = std::sin(angle / 2);
  return {std::cos(angle / 2), x * s, y * s, z * s};
}

TEST(SimulationTest, EulerAnglesOfSingleAxisRotations) {
  const auto roll = EulerZYX(AxisAngle(1, 0, 0, 0.3).data());
  EXPECT_NEAR(roll[0], 0.3, 1e-15);
  EXPECT_NEAR(roll[1], 0.0, 1e-15);
  EXPECT_NEAR(roll[2], 0.0, 1e-15);
  const auto pitch = EulerZYX(AxisAngle(0, 1, 0, -0.4).data());
  EXPECT_NEAR(pitch[1], -0.4, 1e-15);
  const auto yaw = EulerZYX(AxisAngle(0, 0, 1, M_PI / 2).data());
  EXPECT_NEAR(yaw[2], M_PI / 2, 1e-15);
  EXPECT_NEAR(yaw[0], 0.0, 1e-15);
  const double identity[4] = {1, 0, 0, 0};
  EXPECT_EQ(EulerZYX(identity), (std::array<double, 3>{0, 0, 0}));
}

// Yaw, then pitch, then roll (q = q_z q_y q_x): each angle comes back.
TEST(SimulationTest, EulerAnglesOfAComposedRotation) {
  const double r = 0.2, p = -0.35, y = 2.5;
  const auto qz = AxisAngle(0, 0, 1, y), qy = AxisAngle(0, 1, 0, p), qx = AxisAngle(1, 0, 0, r);
  auto mul = [](const std::array<double, 4>& a, const std::array<double, 4>& b) {
    return std::array<double, 4>{a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
                                 a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
                                 a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
                                 a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
  };
  const auto q = mul(mul(qz, qy), qx);
  const auto e = EulerZYX(q.data());
  EXPECT_NEAR(e[0], r, 1e-12);
  EXPECT_NEAR(e[1], p, 1e-12);
  EXPECT_NEAR(e[2], y, 1e-12);
}

TEST(SimulationTest, StepsClockAndWhatItExposes) {
  Simulation sim(Parse(PointMassExperiment(-2, 1, 2, 1, 0.03)));
  EXPECT_EQ(sim.total_steps(), 30);
  EXPECT_EQ(sim.n_vehicles(), 3);
  EXPECT_EQ(sim.n_followers(), 2);
  EXPECT_EQ(sim.actuators_per_vehicle(), 3);
  EXPECT_NE(sim.shape(), nullptr);
  EXPECT_EQ(sim.channel(), nullptr);  // central execution
  EXPECT_TRUE(sim.wind().empty());    // calm
  EXPECT_TRUE(sim.vehicle_notes().empty());
  // hover as the formation plugin is a guidance plugin flown per follower: no swarm-level one.
  EXPECT_EQ(sim.formation_plugin(), nullptr);
  EXPECT_STREQ(sim.leader_plugin().descriptor().name, "hover");
  EXPECT_STREQ(sim.attitude_plugin(2).descriptor().name, "pointmass_direct");
  EXPECT_THAT(sim.scene_xml(), HasSubstr("uav2_vehicle"));
  EXPECT_EQ(sim.model()->nu, 9);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(sim.step_index(), k);
    EXPECT_DOUBLE_EQ(sim.time(), k * 0.001);
    sim.ComputeControls();
    sim.Integrate();
  }
  EXPECT_EQ(sim.step_index(), 3);
  sim.ComputeControls();
  // Ideal sensors: what the controllers saw is the truth, bit for bit.
  ASSERT_EQ(sim.measured().size(), sim.states().size());
  for (size_t i = 0; i < sim.states().size(); ++i) {
    EXPECT_EQ(std::memcmp(&sim.measured()[i], &sim.states()[i], sizeof(mjfVehicleState)), 0);
  }
  EXPECT_EQ(sim.controls().size(), 9u);
  EXPECT_EQ(sim.setpoints().size(), 3u);
}

// An actuator of the vehicle that the attitude plugin does not name (here a lift assist on the
// free joint) is never driven: the run says so among the vehicle notes, naming it; the stock
// quadrotor has no such note.
TEST(SimulationTest, AnActuatorThePluginDoesNotDriveIsNamedInTheVehicleNotes) {
  const std::string dir = mjf::testing::TempDir("undriven");
  std::string xml = mjf::testing::ReadFile(std::string(MJF_SOURCE_DIR) + "/mjcf/quadrotor.xml");
  const std::string end = "  </actuator>";
  ASSERT_NE(xml.find(end), std::string::npos);
  xml.replace(xml.find(end), end.size(),
              "    <motor name=\"lift_assist\" joint=\"root\" gear=\"0 0 1 0 0 0\"/>\n" + end);
  mjf::testing::WriteFile(dir + "/assisted.xml", xml);
  std::string text = HoverExperiment();
  text.replace(text.find("model = \"quadrotor\""), 19, "model = \"assisted.xml\"");
  ExperimentConfig c = mjf::runner::LoadExperiment(mjf::testing::WriteFile(dir + "/e.toml", text));
  c.plugin_path.push_back(MJF_TEST_PLUGIN_DIR);
  Simulation sim(c);
  EXPECT_THAT(sim.vehicle_notes(),
              ::testing::Contains(AllOf(HasSubstr("not driven"), HasSubstr("'pd_cascade'"),
                                        HasSubstr("'lift_assist'"))));
  Simulation stock(Parse(HoverExperiment()));
  EXPECT_TRUE(stock.vehicle_notes().empty());
}

// A contract-form vehicle (no adapter) whose sensor site is off the centre of mass: warned with
// the offset and the position that fixes it; its <option> changes are listed as vehicle notes.
// The same model with the site at the centre of mass gets neither.
TEST(SimulationTest, ContractFormModelWithImuOffTheCentreOfMassIsWarned) {
  const std::string dir = mjf::testing::TempDir("imuoffset");
  std::string xml = mjf::testing::ReadFile(std::string(MJF_SOURCE_DIR) + "/mjcf/pointmass.xml");
  ASSERT_NE(xml.find("<site name=\"imu\" pos=\"0 0 0\""), std::string::npos);
  const std::string at_com = xml;
  const std::string site = "<site name=\"imu\" pos=\"0 0 0\"";
  const std::string option = "<option timestep=\"0.001\"";
  xml.replace(xml.find(site), site.size(), "<site name=\"imu\" pos=\"0 0 0.034\"");
  xml.replace(xml.find(option), option.size(), "<option timestep=\"0.01\" density=\"1.225\"");
  mjf::testing::WriteFile(dir + "/offset.xml", xml);
  mjf::testing::WriteFile(dir + "/centred.xml", at_com);
  std::string text = mjf::testing::PointMassExperiment(-2, 1, 2, 1, 0.03);
  text.replace(text.find("model = \"pointmass\""), 19, "model = \"offset.xml\"");
  ExperimentConfig c = mjf::runner::LoadExperiment(mjf::testing::WriteFile(dir + "/e.toml", text));
  c.plugin_path.push_back(MJF_TEST_PLUGIN_DIR);
  Simulation sim(c);
  ASSERT_EQ(sim.warnings().size(), 1u);
  EXPECT_THAT(sim.warnings()[0],
              AllOf(HasSubstr("offset.xml"), HasSubstr("site 'imu'"), HasSubstr("0.034 m"),
                    HasSubstr("centre of mass"), HasSubstr("pos=\"0 0 0\"")));
  EXPECT_THAT(sim.vehicle_notes(),
              ::testing::ElementsAre(HasSubstr("<option timestep=\"0.01\"> is replaced"),
                                     HasSubstr("<option density=\"1.225\">")));

  text.replace(text.find("offset.xml"), 10, "centred.xml");
  ExperimentConfig centred =
      mjf::runner::LoadExperiment(mjf::testing::WriteFile(dir + "/e2.toml", text));
  centred.plugin_path.push_back(MJF_TEST_PLUGIN_DIR);
  Simulation plain(centred);
  EXPECT_TRUE(plain.warnings().empty());
  EXPECT_TRUE(plain.vehicle_notes().empty());
}

// A rotor layout the attitude plugin refuses (the two +y rotors share a yaw gear sign, as in
// Menagerie's Skydio X2) is pointed at [vehicles] rotors, names the model's own rotors and the
// documented fix, and gives a readable condition number.
TEST(SetupErrorTest, ASingularRotorLayoutNamesTheModelsRotors) {
  const std::string dir = mjf::testing::TempDir("x2like");
  std::string xml =
      "<mujoco><worldbody><body name=\"quad\"><freejoint/>"
      "<geom type=\"sphere\" size=\"0.1\" mass=\"1\"/>";
  const char* sites[] = {"0.1 0.1 0", "-0.1 0.1 0", "-0.1 -0.1 0", "0.1 -0.1 0"};
  for (int k = 0; k < 4; ++k) {
    xml += "<site name=\"s" + std::to_string(k) + "\" pos=\"" + sites[k] + "\"/>";
  }
  xml += "</body></worldbody><actuator>";
  const char* yaw[] = {"0.01", "0.01", "-0.01", "-0.01"};
  for (int k = 0; k < 4; ++k) {
    xml += "<general name=\"prop" + std::to_string(k + 1) + "\" site=\"s" + std::to_string(k) +
           "\" gear=\"0 0 1 0 0 " + yaw[k] + "\" ctrlrange=\"0 10\" ctrllimited=\"true\"/>";
  }
  xml += "</actuator></mujoco>";
  mjf::testing::WriteFile(dir + "/x2like.xml", xml);
  std::string text = HoverExperiment();
  text.replace(text.find("model = \"quadrotor\""), 19,
               "model = \"x2like.xml\"\nbody = \"quad\"\n"
               "rotors = [\"prop1\", \"prop2\", \"prop3\", \"prop4\"]");
  ExperimentConfig c = mjf::runner::LoadExperiment(mjf::testing::WriteFile(dir + "/e.toml", text));
  c.plugin_path.push_back(MJF_TEST_PLUGIN_DIR);
  const std::string error = ErrorOf([&] { Simulation sim(c); });
  EXPECT_THAT(error, AllOf(HasSubstr("e.toml:"),
                           HasSubstr("[vehicles] rotors: the attitude "
                                     "plugin 'pd_cascade' cannot fly"),
                           HasSubstr("'prop1' (rotor0, "), HasSubstr("'prop4' (rotor3, "),
                           HasSubstr("docs/VEHICLES.md")));
  EXPECT_THAT(error, ::testing::Not(HasSubstr("[attitude]")));
  EXPECT_THAT(error, ::testing::ContainsRegex("condition number [0-9.]+e\\+[0-9]+\\)"));
}

TEST(SimulationTest, ANonFiniteSetpointStopsBeforeTheStep) {
  // test_nan commands NaN from t = 0.005 s on: the step that would use it is never taken.
  std::string text = PointMassExperiment(-2, 1, 2, 1, 0.05);
  text.replace(text.find("[leader]\nplugin = \"hover\""), 25,
               "[leader]\nplugin = \"test_nan\"\nafter = 0.005");
  Simulation sim(Parse(text));
  try {
    for (int k = 0; k < 50; ++k) {
      sim.ComputeControls();
      sim.Integrate();
    }
    ADD_FAILURE() << "a NaN command did not stop the simulation";
  } catch (const SimulationError& e) {
    EXPECT_STREQ(e.what(),
                 "t = 0.005 s: plugin 'test_nan' wrote a non-finite setpoint for vehicle 0");
  }
  EXPECT_EQ(sim.step_index(), 5);
}

TEST(SimulationTest, ANonFiniteStateAfterAStepIsAnError) {
  Simulation sim(Parse(PointMassExperiment(-2, 1, 2, 1, 0.05)));
  for (int k = 0; k < 3; ++k) {
    sim.ComputeControls();
    sim.Integrate();
  }
  sim.ComputeControls();
  sim.data()->qvel[0] = std::numeric_limits<double>::quiet_NaN();
  try {
    sim.Integrate();
    ADD_FAILURE() << "a NaN velocity went unnoticed";
  } catch (const SimulationError& e) {
    EXPECT_THAT(e.what(), HasSubstr("t = 0.00"));
    EXPECT_THAT(e.what(), ::testing::AnyOf(HasSubstr("non-finite"), HasSubstr("MuJoCo warning")));
  }
}

}  // namespace
}  // namespace mjf::runner
