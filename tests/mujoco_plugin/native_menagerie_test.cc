// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Menagerie's drones as published (examples/vehicles/menagerie: the Crazyflie 2, thrust and
// moments at one site; the Skydio X2 with the yaw gears of Menagerie PR 220 and its inertia
// from its geoms, principal axes not the body's) under mjformation.attitude, with nothing added
// but the instance: each holds a point. Their meshes fly along when they are beside the models
// and are left out otherwise (visual, massless or out of contact: README.md there).
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "mjformation/config/config.hpp"
#include "mjformation/export/export.hpp"
#include "mjformation/sim/simulation.hpp"
#include "native_fixture.hpp"

namespace mjf::native {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const fs::path kMenagerie = fs::path(MJF_SOURCE_DIR) / "examples/vehicles/menagerie";

// `file` of the Menagerie folder, its asset folder `assets` read from where it is, or, when it
// is absent, without the elements that name its files (meshes, textures, the geoms and the
// material that use them).
std::string Published(const std::string& file, const std::string& assets) {
  const fs::path path = kMenagerie / file;
  std::string text = mjf::testing::ReadFile(path.string());
  const fs::path folder = path.parent_path() / assets;
  const std::string relative = "dir=\"" + assets + "\"";
  if (fs::is_directory(folder)) {
    text.replace(text.find(relative), relative.size(), "dir=\"" + folder.string() + "\"");
    return text;
  }
  std::istringstream in(text);
  std::string kept;
  for (std::string line; std::getline(in, line);) {
    const bool names_a_file =
        line.find("<mesh ") != std::string::npos || line.find("<texture ") != std::string::npos ||
        line.find(" mesh=\"") != std::string::npos || line.find(" texture=\"") != std::string::npos;
    if (!names_a_file) kept += line + "\n";
  }
  return kept;
}

// `xml` with an mjformation.attitude instance flying `body` on `actuators` to (0, 0, 1) m.
std::string WithAutopilot(std::string xml, const std::string& body, const std::string& actuators,
                          const std::string& attitude, const std::string& more = "") {
  const std::string instance = R"(
  <extension><plugin plugin="mjformation.attitude"><instance name="autopilot">
    <config key="body" value=")" +
                               body + R"("/>
    <config key="actuators" value=")" +
                               actuators +
                               R"("/>
    <config key="attitude" value=")" +
                               attitude +
                               R"("/>
    <config key="guidance" value="plugin = 'hover', position = '0 0 1'"/>)" +
                               more + R"(
  </instance></plugin></extension>)";
  const size_t open = xml.find("<mujoco");
  xml.insert(xml.find('>', open) + 1, instance);
  return xml;
}

struct Flight {
  bool flew = false;
  double hold = 1e9;  // m, largest distance from (0, 0, 1) over the last second
  std::string error;
};

Flight Fly(const std::string& xml, const std::string& body_name, double seconds) {
  mjf::testing::LoadNativePluginsOnce();
  mjf::testing::Scratch dir("menagerie");
  std::ofstream(dir / "drone.xml") << xml;
  Flight f;
  char error[1024] = {0};
  mjModel* m = mj_loadXML((dir / "drone.xml").c_str(), nullptr, error, sizeof(error));
  f.error = error;
  if (!m) return f;
  mjData* d = mj_makeData(m);
  if (d) {
    f.flew = true;
    f.hold = 0;
    const int body = mj_name2id(m, mjOBJ_BODY, body_name.c_str());
    const double target[3] = {0, 0, 1};
    const int steps = static_cast<int>(std::lround(seconds / m->opt.timestep));
    const int last_second = static_cast<int>(std::lround(1.0 / m->opt.timestep));
    for (int k = 0; k < steps; ++k) {
      mj_step(m, d);
      if (k >= steps - last_second) {
        f.hold = std::max(f.hold, mju_dist3(d->xpos + 3 * body, target));
      }
    }
    mj_deleteData(d);
  }
  mj_deleteModel(m);
  return f;
}

constexpr char kX2Rotors[] = "thrust1 thrust2 thrust3 thrust4";

// The X2, its inertia's principal axes not its body's: pd_cascade at the published 10 ms step,
// geometric at 2 ms (at 10 ms geometric's height still swings by 0.12 m after 12 s; x and y
// hold).
TEST(NativeMenagerie, SkydioX2HoldsAPoint) {
  const std::string x2 = Published("skydio_x2/x2.xml", "assets");
  ASSERT_THAT(x2, ::testing::Not(HasSubstr("<inertial ")));
  const Flight cascade =
      Fly(WithAutopilot(x2, "x2", kX2Rotors, "plugin = 'pd_cascade'"), "x2", 12.0);
  ASSERT_TRUE(cascade.flew) << cascade.error;
  EXPECT_LT(cascade.hold, 0.05);
  std::string fine = x2;
  const std::string step = "timestep=\"0.01\"";
  fine.replace(fine.find(step), step.size(), "timestep=\"0.002\"");
  const Flight geometric =
      Fly(WithAutopilot(fine, "x2", kX2Rotors, "plugin = 'geometric'"), "x2", 12.0);
  ASSERT_TRUE(geometric.flew) << geometric.error;
  EXPECT_LT(geometric.hold, 0.05);
}

// The X2 as Menagerie publishes it (thrust1 and thrust4, both on the -y side, share a yaw gear):
// yaw cannot be told from roll, and the plugin says so instead of flying it.
TEST(NativeMenagerie, SkydioX2WithThePublishedYawGearsIsRefused) {
  std::string x2 = Published("skydio_x2/x2.xml", "assets");
  for (const char* rotor :
       {"\"thrust3\" gear=\"0 0 1 0 0 -.0201\"", "\"thrust4\" gear=\"0 0 1 0 0  .0201\""}) {
    std::string gear = rotor;
    const size_t at = x2.find(gear);
    ASSERT_NE(at, std::string::npos) << gear;
    const bool minus = gear.find("-.0201") != std::string::npos;
    gear.replace(gear.find(minus ? "-.0201" : " .0201"), 6, minus ? " .0201" : "-.0201");
    x2.replace(at, gear.size(), gear);
  }
  const Flight f = Fly(WithAutopilot(x2, "x2", kX2Rotors, "plugin = 'geometric'"), "x2", 0.1);
  EXPECT_FALSE(f.flew);
  EXPECT_THAT(f.error, HasSubstr("yaw"));
}

// The Crazyflie 2: one site, a thrust and three moments (gears of either sign), RK4 as published.
// Its moments reach +-1e-5 N m (0.42 rad/s^2): a low tilt limit, as in
// examples/vehicles/midge/exp2_low_authority.toml (geometric gets there too, in 20 s).
TEST(NativeMenagerie, Crazyflie2HoldsAPoint) {
  const std::string cf2 = Published("bitcraze_crazyflie_2/cf2.xml", "cf2");
  const Flight f = Fly(WithAutopilot(cf2, "cf2", "body_thrust x_moment y_moment z_moment",
                                     "plugin = 'pd_cascade', tilt_max = 0.05",
                                     R"(<config key="actuation" value="thrust_moments"/>)"),
                       "cf2", 12.0);
  ASSERT_TRUE(f.flew) << f.error;
  EXPECT_LT(f.hold, 0.05);
}

// Its moments named in the wrong order: refused naming the actuator, its role and its gear.
TEST(NativeMenagerie, Crazyflie2MomentsOutOfOrderAreRefused) {
  const std::string cf2 = Published("bitcraze_crazyflie_2/cf2.xml", "cf2");
  const Flight f = Fly(
      WithAutopilot(cf2, "cf2", "body_thrust y_moment x_moment z_moment", "plugin = 'geometric'",
                    R"(<config key="actuation" value="thrust_moments"/>)"),
      "cf2", 0.1);
  EXPECT_FALSE(f.flew);
  EXPECT_THAT(f.error, HasSubstr("actuator 'y_moment' is mapped as the moment about body x but "
                                 "its gear is \"0 0 0 0 -1 0\""));
}

// Exp 2 (`experiment`, a file of the source tree, cut to `seconds`) with Menagerie's `file`
// (`assets` as in Published) mapped by `mapping` in place of its [vehicles] model lines, flown
// by the runner's Simulation and by the exported scene under plain mj_step, side by side.
struct BothFaces {
  bool bitwise = true;         // every qpos, qvel and act the same at every step
  double max_diff = 0;         // m
  double lowest = 1e9;         // m, the lowest vehicle at the end
  double moved = 0;            // m, the largest change of a qpos entry (it did fly)
  std::string export_refusal;  // export's message when it cannot carry the experiment
  int64_t compared = 0;        // steps of the exported scene compared with the runner's
};

BothFaces FlyBothFaces(const std::string& experiment, const std::string& file,
                       const std::string& assets, const std::string& mapping, double seconds) {
  mjf::testing::Scratch dir("menagerie_exp2");
  std::ofstream(dir / "drone.xml") << Published(file, assets);
  std::string text = mjf::testing::ReadFile(std::string(MJF_SOURCE_DIR) + "/" + experiment);
  // The model lines (a file and its mapping, or the stock quadrotor) become `mapping`.
  text = std::regex_replace(text, std::regex("\nmodel = [^\n]*(\n(body|thrust|moments) = [^\n]*)*"),
                            "\nmodel = \"drone.xml\"\n" + mapping);
  text = std::regex_replace(text, std::regex("\nduration = [^\n]*"),
                            "\nduration = " + std::to_string(seconds));
  text = std::regex_replace(text, std::regex("\nmetric_window = [^\n]*"),
                            "\nmetric_window = [0.0, " + std::to_string(seconds) + "]");
  // [render] and [safety] watch the flight without touching it; the native face carries neither.
  for (const char* section : {"\n[render]", "\n[safety]"}) {
    const size_t at = text.find(section);
    if (at != std::string::npos) text.erase(at, text.find("\n[", at + 1) - at);
  }
  std::ofstream(dir / "exp2.toml") << text;

  using runner::ExperimentChecks;
  const runner::ExperimentConfig config =
      runner::LoadExperiment(dir / "exp2.toml", {}, ExperimentChecks::Rendering(false));
  runner::Simulation sim(config);
  BothFaces c;
  try {
    runner::ExportExperiment(dir / "exp2.toml", dir / "export");
  } catch (const std::exception& e) {
    c.export_refusal = e.what();
  }
  mjModel* m = nullptr;
  if (c.export_refusal.empty()) {
    mjf::testing::LoadNativePluginsOnce();
    char error[2048] = {0};
    m = mj_loadXML((dir / "export/scene.xml").c_str(), nullptr, error, sizeof(error));
    EXPECT_NE(m, nullptr) << error;
  }
  mjData* d = m ? mj_makeData(m) : nullptr;
  const mjModel* rm = sim.model();
  const mjData* r = sim.data();
  const std::vector<mjtNum> start(r->qpos, r->qpos + rm->nq);
  const int64_t steps = std::llround(seconds / config.timestep);
  for (int64_t k = 0; k < steps; ++k) {
    sim.ComputeControls();
    sim.Integrate();
    if (!d) continue;
    mj_step(m, d);
    ++c.compared;
    for (int i = 0; i < m->nq; ++i) {
      c.max_diff = std::max(c.max_diff, std::fabs(d->qpos[i] - r->qpos[i]));
    }
    c.bitwise = c.bitwise && !std::memcmp(d->qpos, r->qpos, sizeof(mjtNum) * m->nq) &&
                !std::memcmp(d->qvel, r->qvel, sizeof(mjtNum) * m->nv) &&
                !std::memcmp(d->act, r->act, sizeof(mjtNum) * m->na);
  }
  for (int i = 0; i < rm->nq; ++i) c.moved = std::max(c.moved, std::fabs(r->qpos[i] - start[i]));
  for (int j = 0; j < rm->njnt; ++j) {
    if (rm->jnt_type[j] == mjJNT_FREE) {
      c.lowest = std::min(c.lowest, r->qpos[rm->jnt_qposadr[j] + 2]);
    }
  }
  if (d) mj_deleteData(d);
  if (m) mj_deleteModel(m);
  return c;
}

// The exported face: `mjformation export` carries the mapping ([vehicles] body, rotors, thrust,
// moments; the model file bundled beside the scene), and the plugin adapts the model as the
// runner does, so plain mj_step flies the runner's flight, bit for bit.
void ExpectTheExportedFaceAlike(const BothFaces& c) {
  EXPECT_EQ(c.export_refusal, "");
  EXPECT_TRUE(c.bitwise) << "largest qpos difference " << c.max_diff << " m";
  EXPECT_GT(c.compared, 0);
}

// The X2 flies the first 4 s of the full-size Exp 2 (its 0.5 m span does not fit the scaled
// one's 0.15 m start ring) with pd_cascade, the runner and the exported scene alike.
TEST(NativeMenagerie, SkydioX2FliesExp2ThroughBothFaces) {
  const BothFaces c = FlyBothFaces(
      "experiments/exp2.toml", "skydio_x2/x2.xml", "assets",
      "body = \"x2\"\nrotors = [\"thrust1\", \"thrust2\", \"thrust3\", \"thrust4\"]", 4.0);
  EXPECT_GT(c.lowest, 4.5);  // every vehicle near the 5 m altitude
  EXPECT_GT(c.moved, 1.0);
  ExpectTheExportedFaceAlike(c);
}

// The cf2 flies the first 4 s of the scaled Exp 2 for little torque authority
// (examples/vehicles/midge/exp2_low_authority.toml, mapped as its header says).
TEST(NativeMenagerie, Crazyflie2FliesTheScaledExp2ThroughBothFaces) {
  const BothFaces c = FlyBothFaces("examples/vehicles/midge/exp2_low_authority.toml",
                                   "bitcraze_crazyflie_2/cf2.xml", "cf2",
                                   "body = \"cf2\"\nthrust = \"body_thrust\"\n"
                                   "moments = [\"x_moment\", \"y_moment\", \"z_moment\"]",
                                   4.0);
  EXPECT_GT(c.lowest, 0.4);  // every vehicle near the 0.5 m altitude
  EXPECT_GT(c.moved, 0.1);
  ExpectTheExportedFaceAlike(c);
}

}  // namespace
}  // namespace mjf::native
