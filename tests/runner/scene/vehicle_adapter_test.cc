// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Bring your own quadrotor (docs/VEHICLES.md): a foreign MJCF model is adapted to the vehicle
// contract, bad mappings are refused naming the model file and the element, and the foreign
// test vehicle (examples/vehicles/bumblebee) flies Exp 2 to the formation.
#include "mjformation/scene/vehicle_adapter.hpp"

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <string>

#include "error_of.hpp"
#include "mjformation/config/config.hpp"
#include "mjformation/run/run.hpp"
#include "mjformation/scene/scene.hpp"
#include "mjformation/sim/simulation.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

using mjf::testing::ReadFile;
using mjf::testing::TempDir;
using mjf::testing::WriteFile;

const std::string kBumblebeeDir = std::string(MJF_SOURCE_DIR) + "/examples/vehicles/bumblebee";
const std::string kBumblebee = kBumblebeeDir + "/bumblebee.xml";

VehicleMapping BumblebeeMapping(const std::string& path = kBumblebee) {
  VehicleMapping m;
  m.model_path = path;
  m.body = "bumblebee";
  m.rotors = {"prop_a", "prop_b", "prop_c", "prop_d"};
  m.actuator_names = {"rotor0", "rotor1", "rotor2", "rotor3"};
  m.body_where = "exp.toml:7: [vehicles] body";
  m.rotors_where = "exp.toml:8: [vehicles] rotors";
  return m;
}

// The bumblebee model with one edit, in a temporary folder whose meshdir points back at the
// real assets.
std::string EditedModel(const std::string& from, const std::string& to) {
  std::string xml = ReadFile(kBumblebee);
  const auto at = xml.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) xml.replace(at, from.size(), to);
  for (const std::string dir : {"meshdir", "texturedir"}) {
    const std::string attr = dir + "=\"assets\"";
    xml.replace(xml.find(attr), attr.size(), dir + "=\"" + kBumblebeeDir + "/assets\"");
  }
  return WriteFile(TempDir("adapter") + "/model.xml", xml);
}

std::string ErrorOf(const VehicleMapping& m) {
  return mjf::testing::ErrorOf<SceneError>([&] { AdaptVehicle(m); }, "(no error)");
}

TEST(VehicleAdapterTest, BumblebeeBecomesAContractVehicle) {
  const AdaptedVehicle a = AdaptVehicle(BumblebeeMapping());
  std::unique_ptr<mjModel, ModelDeleter> m(CompileModel(a.xml, "adapted"));
  // One body (+ world), named vehicle, with the contract's site and sensors.
  EXPECT_EQ(m->nbody, 2);
  const int body = mj_name2id(m.get(), mjOBJ_BODY, "vehicle");
  ASSERT_EQ(body, 1);
  EXPECT_NEAR(m->body_mass[body], 0.9, 1e-12);
  const int imu = mj_name2id(m.get(), mjOBJ_SITE, "imu");
  ASSERT_GE(imu, 0);
  // At the centre of mass (1 cm below the body origin), not at the model's own imu site.
  EXPECT_NEAR(m->site_pos[3 * imu + 2], -0.01, 1e-12);
  EXPECT_GE(mj_name2id(m.get(), mjOBJ_SITE, "model_imu"), 0);
  for (const char* s : {"pos", "vel", "quat", "gyro"}) {
    const int id = mj_name2id(m.get(), mjOBJ_SENSOR, s);
    ASSERT_GE(id, 0) << s;
    EXPECT_EQ(m->sensor_objid[id], imu) << s;
  }
  EXPECT_GE(mj_name2id(m.get(), mjOBJ_SENSOR, "bb_acc"), 0);  // the model's own sensors stay
  // Rotors renamed in the given order; the gear signs show which is which.
  for (int k = 0; k < 4; ++k) {
    const int id = mj_name2id(m.get(), mjOBJ_ACTUATOR, ("rotor" + std::to_string(k)).c_str());
    ASSERT_GE(id, 0);
    EXPECT_NEAR(m->actuator_gear[6 * id + 5], k % 2 == 0 ? 0.011 : -0.011, 1e-12);
    EXPECT_NEAR(m->actuator_ctrlrange[2 * id + 1], 4.5, 1e-12);
  }
  EXPECT_EQ(m->nu, 4);
  // The mesh is kept (found through meshdir); the floor, light, sky and keyframe are not.
  EXPECT_EQ(m->nmesh, 1);
  EXPECT_EQ(m->ntex, 1);  // the PNG stripes, found through texturedir
  EXPECT_GE(mj_name2id(m.get(), mjOBJ_TEXTURE, "bb_stripes"), 0);
  EXPECT_EQ(m->nlight, 0);
  EXPECT_EQ(m->nkey, 0);
  EXPECT_EQ(mj_name2id(m.get(), mjOBJ_GEOM, "demo_floor"), -1);
  EXPECT_EQ(mj_name2id(m.get(), mjOBJ_TEXTURE, "demo_sky"), -1);
  std::string notes;
  for (const auto& n : a.notes) notes += n + "\n";
  for (const char* what :
       {"demo_light", "demo_floor", "keyframe", "demo_sky", "'prop_a' to 'rotor0'"}) {
    EXPECT_NE(notes.find(what), std::string::npos) << what << " not in notes:\n" << notes;
  }
}

TEST(VehicleAdapterTest, ComposedSceneHasTheAdaptedVehicles) {
  const AdaptedVehicle a = AdaptVehicle(BumblebeeMapping());
  SceneRequest r;
  r.scene_path = std::string(MJF_SOURCE_DIR) + "/mjcf/scene.xml";
  r.vehicle_path = kBumblebee;
  r.vehicle_xml = a.xml;
  r.vehicle_notes = a.notes;
  r.positions = {{0, 0, 1}, {2, 0, 1}, {4, 0, 1}};
  ComposedScene scene = ComposeScene(r, "composed");
  EXPECT_NE(scene.xml.find("renamed body 'bumblebee' to 'vehicle'"), std::string::npos);
  const auto& m = scene.model;
  EXPECT_EQ(m->nmesh, 1);
  EXPECT_EQ(m->nlight, 1);  // the scene's sun only
  for (int i = 0; i < 3; ++i) {
    EXPECT_GE(mj_name2id(m.get(), mjOBJ_ACTUATOR, (VehiclePrefix(i) + "rotor3").c_str()), 0);
    EXPECT_GE(mj_name2id(m.get(), mjOBJ_SENSOR, (VehiclePrefix(i) + "gyro").c_str()), 0);
  }
}

// A Menagerie-style scene.xml that <include>s the vehicle file and adds its own floor and light.
TEST(VehicleAdapterTest, SceneFileIncludingTheVehicleWorks) {
  const std::string vehicle = EditedModel("<keyframe>", "<keyframe>");
  const std::string dir = vehicle.substr(0, vehicle.find_last_of('/'));
  const std::string scene = WriteFile(dir + "/scene.xml", R"(<mujoco model="demo scene">
  <include file="model.xml"/>
  <worldbody>
    <light name="scene_light" pos="0 0 3"/>
    <geom name="scene_floor" type="plane" size="2 2 0.1"/>
  </worldbody>
</mujoco>)");
  const AdaptedVehicle a = AdaptVehicle(BumblebeeMapping(scene));
  std::unique_ptr<mjModel, ModelDeleter> m(CompileModel(a.xml, "adapted"));
  EXPECT_EQ(m->nbody, 2);
  EXPECT_EQ(m->nmesh, 1);
  EXPECT_EQ(m->nlight, 0);
  EXPECT_EQ(mj_name2id(m.get(), mjOBJ_GEOM, "scene_floor"), -1);
  EXPECT_GE(mj_name2id(m.get(), mjOBJ_ACTUATOR, "rotor0"), 0);
}

// Top-level defaults of the model stay with the vehicle: the scene's floor keeps colliding, the
// vehicle's mesh gets the default scale.
TEST(VehicleAdapterTest, TopLevelDefaultsDoNotReachTheScene) {
  const std::string edited = EditedModel(
      "<default>\n", "<default>\n<geom contype=\"0\" conaffinity=\"0\"/><mesh scale=\"2 2 2\"/>\n");
  SceneRequest r;
  r.scene_path = std::string(MJF_SOURCE_DIR) + "/mjcf/scene.xml";
  r.positions = {{0, 0, 1}};
  auto compose = [&](const std::string& model) {
    const AdaptedVehicle a = AdaptVehicle(BumblebeeMapping(model));
    r.vehicle_path = model;
    r.vehicle_xml = a.xml;
    return ComposeScene(r, "composed").model;
  };
  const auto plain = compose(kBumblebee);
  const auto scoped = compose(edited);
  const int floor = mj_name2id(scoped.get(), mjOBJ_GEOM, "scene_floor");
  ASSERT_GE(floor, 0);
  EXPECT_EQ(scoped->geom_contype[floor], 1);
  EXPECT_EQ(scoped->geom_conaffinity[floor], 1);
  const int canopy = mj_name2id(scoped.get(), mjOBJ_GEOM, "uav0_bb_canopy");
  ASSERT_GE(canopy, 0);
  EXPECT_NEAR(scoped->geom_rbound[canopy], 2 * plain->geom_rbound[canopy], 1e-9);
}

TEST(VehicleAdapterTest, PermutedNamesOfTheOwnModelWork) {
  VehicleMapping m = BumblebeeMapping(std::string(MJF_SOURCE_DIR) + "/mjcf/quadrotor.xml");
  m.body = "vehicle";
  m.rotors = {"rotor1", "rotor0", "rotor3", "rotor2"};
  std::unique_ptr<mjModel, ModelDeleter> model(CompileModel(AdaptVehicle(m).xml, "adapted"));
  // The model's rotor1 (rear-left, gear -0.06, x = -0.13) is now called rotor0.
  const int r0 = mj_name2id(model.get(), mjOBJ_ACTUATOR, "rotor0");
  const int site = model->actuator_trnid[2 * r0];
  EXPECT_NEAR(model->site_pos[3 * site], -0.13, 1e-12);
}

TEST(VehicleAdapterTest, MissingBodyNamesFileAndBody) {
  VehicleMapping m = BumblebeeMapping();
  m.body = "wasp";
  const std::string e = ErrorOf(m);
  EXPECT_NE(e.find("exp.toml:7: [vehicles] body"), std::string::npos) << e;
  EXPECT_NE(e.find(kBumblebee), std::string::npos) << e;
  EXPECT_NE(e.find("'wasp'"), std::string::npos) << e;
  EXPECT_NE(e.find("'bumblebee'"), std::string::npos) << e;  // what it has
}

TEST(VehicleAdapterTest, BodyWithoutFreeJointIsRefused) {
  VehicleMapping m = BumblebeeMapping(EditedModel("<freejoint name=\"bb_free\"/>", ""));
  const std::string e = ErrorOf(m);
  EXPECT_NE(e.find("model.xml:"), std::string::npos) << e;
  EXPECT_NE(e.find("no free joint"), std::string::npos) << e;
}

TEST(VehicleAdapterTest, MissingRotorIsRefusedListingTheActuators) {
  VehicleMapping m = BumblebeeMapping();
  m.rotors[2] = "prop_x";
  const std::string e = ErrorOf(m);
  EXPECT_NE(e.find("exp.toml:8: [vehicles] rotors"), std::string::npos) << e;
  EXPECT_NE(e.find(kBumblebee), std::string::npos) << e;
  EXPECT_NE(e.find("no actuator named 'prop_x'"), std::string::npos) << e;
  EXPECT_NE(e.find("prop_a, prop_b, prop_c, prop_d"), std::string::npos) << e;
}

TEST(VehicleAdapterTest, RepeatedOrMiscountedRotorsAreRefused) {
  VehicleMapping m = BumblebeeMapping();
  m.rotors[3] = "prop_a";
  EXPECT_NE(ErrorOf(m).find("'prop_a' is listed twice"), std::string::npos) << ErrorOf(m);
  m.rotors.pop_back();
  EXPECT_NE(ErrorOf(m).find("lists 3 rotors"), std::string::npos) << ErrorOf(m);
}

TEST(VehicleAdapterTest, MissingMeshFileNamesTheMeshElement) {
  VehicleMapping m = BumblebeeMapping(EditedModel("file=\"canopy.obj\"", "file=\"nose.obj\""));
  const std::string e = ErrorOf(m);
  EXPECT_NE(e.find("model.xml:"), std::string::npos) << e;
  EXPECT_NE(e.find("<mesh name=\"bb_canopy\">"), std::string::npos) << e;
  EXPECT_NE(e.find("nose.obj"), std::string::npos) << e;
  EXPECT_NE(e.find("file not found"), std::string::npos) << e;
}

TEST(VehicleAdapterTest, MissingTextureFileNamesTheTextureElement) {
  VehicleMapping m = BumblebeeMapping(EditedModel("file=\"stripes.png\"", "file=\"spots.png\""));
  const std::string e = ErrorOf(m);
  EXPECT_NE(e.find("<texture name=\"bb_stripes\">"), std::string::npos) << e;
  EXPECT_NE(e.find("spots.png"), std::string::npos) << e;
  EXPECT_NE(e.find("texturedir"), std::string::npos) << e;
}

TEST(VehicleAdapterTest, ConfigRefusesRepeatedRotorWithItsLine) {
  const std::string dir = TempDir("adaptercfg");
  const std::string text = mjf::testing::HoverExperiment() +
                           "";  // [vehicles] is in the middle: rebuild it with the mapping
  std::string t = text;
  t.replace(t.find("model = \"quadrotor\""), 19,
            "model = \"" + kBumblebee + "\"\nbody = \"bumblebee\"\n" +
                "rotors = [\"prop_a\", \"prop_b\", \"prop_a\", \"prop_d\"]");
  try {
    LoadExperiment(WriteFile(dir + "/exp.toml", t));
    FAIL() << "accepted a repeated rotor";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("exp.toml:7: [vehicles] rotors: 'prop_a' is listed twice"),
              std::string::npos)
        << e.what();
  }
}

// Rotors whose yaw reactions all have one sign: yaw torque and thrust are dependent, and the
// attitude plugin's allocation refuses the vehicle before the run.
TEST(VehicleAdapterTest, SingularRotorLayoutIsRefusedBeforeTheRun) {
  const std::string model = EditedModel("site=\"prop_b\" gear=\"0 0 1 0 0 -0.011\"",
                                        "site=\"prop_b\" gear=\"0 0 1 0 0 0.011\"");
  std::string xml = mjf::testing::ReadFile(model);
  const std::string d_gear = "site=\"prop_d\" gear=\"0 0 1 0 0 -0.011\"";
  xml.replace(xml.find(d_gear), d_gear.size(), "site=\"prop_d\" gear=\"0 0 1 0 0 0.011\"");
  WriteFile(model, xml);
  const ExperimentConfig c =
      LoadExperiment(std::string(MJF_SOURCE_DIR) + "/experiments/exp2.toml",
                     {"vehicles.model=\"" + model + "\"", "vehicles.body=\"bumblebee\"",
                      "vehicles.rotors=[\"prop_a\",\"prop_b\",\"prop_c\",\"prop_d\"]"});
  try {
    Simulation sim(c);
    FAIL() << "a singular rotor layout was accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("singular"), std::string::npos) << e.what();
  }
}

// Exp 2 (experiments/exp2.toml) flown by the bumblebee with only the three mapping lines.
TEST(VehicleAdapterTest, BumblebeeFliesExp2ToTheFormation) {
  const std::string exp2 = std::string(MJF_SOURCE_DIR) + "/experiments/exp2.toml";
  ExperimentConfig c =
      LoadExperiment(exp2, {"vehicles.model=\"" + kBumblebee + "\"", "vehicles.body=\"bumblebee\"",
                            "vehicles.rotors=[\"prop_a\",\"prop_b\",\"prop_c\",\"prop_d\"]"});
  RunOptions o;
  o.out_dir = TempDir("bumblebee") + "/run";
  o.render = false;
  const RunResult r = RunExperiment(c, o);
  ASSERT_TRUE(r.complete) << r.error;
  const auto& m = r.summary["metrics"];
  // Measured: sigma_f mean 1.08 on [25, 40] s (the Iris: 1.28), final slot errors <= 0.07 m;
  // bounds leave room for other machines' floating point, not for a vehicle that does not fly.
  EXPECT_LT(m["sigma_f_mean"].get<double>(), 2.0);
  EXPECT_LT(m["max_final_slot_error_m"].get<double>(), 0.3);
  EXPECT_LT(m["sigma_f_final"].get<double>(), 0.1 * m["sigma_f_initial"].get<double>());
  const std::string scene = ReadFile(o.out_dir + "/scene.xml");
  EXPECT_NE(scene.find("adapted to the vehicle contract"), std::string::npos);
}

}  // namespace
}  // namespace mjf::runner
