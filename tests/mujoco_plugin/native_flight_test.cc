// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The exported scene, loaded with libmujoco and libmjformation_mujoco.so alone, flies the
// runner's trajectory: the native side below uses only MuJoCo's C API (mj_loadPluginLibrary,
// mj_loadXML, mj_step); the reference is the runner's own Simulation in the same process.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "mjformation/config/config.hpp"
#include "mjformation/export/export.hpp"
#include "mjformation/sim/simulation.hpp"
#include "native_fixture.hpp"

namespace mjf::runner {
namespace {

namespace fs = std::filesystem;
using mjf::testing::LoadNativePluginsOnce;
using mjf::testing::NativeExperimentText;
using mjf::testing::ReadFile;
using mjf::testing::Scratch;

// The experiment file, with [vehicles] model and [attitude] plugin changed when asked and
// [render] removed (the runner would render; the export notes it).
std::string Variant(const std::string& experiment, const std::string& model,
                    const std::string& attitude, const Scratch& dir) {
  std::string text = NativeExperimentText(experiment, model);
  if (!attitude.empty()) {
    text = std::regex_replace(text, std::regex("\\[attitude\\][^\\[]*"),
                              "[attitude]\nplugin = \"" + attitude + "\"\n\n");
  }
  const std::string path = dir / "experiment.toml";
  std::ofstream(path) << text;
  return path;
}

mjModel* LoadNative(const std::string& scene, std::string* error_text = nullptr) {
  LoadNativePluginsOnce();
  char error[2048] = {0};
  mjModel* m = mj_loadXML(scene.c_str(), nullptr, error, sizeof(error));
  if (error_text) *error_text = error;
  return m;
}

struct Comparison {
  double max_diff = 0;  // m, largest |qpos difference| over every step
  bool bitwise = true;  // every qpos, qvel and act identical at every step
  int64_t steps = 0;
  double moved = 0;              // m, largest change of a qpos entry over the flight (it did fly)
  std::vector<mjtNum> end;       // the exported scene's qpos after the last step
  size_t topology_switches = 0;  // the runner's range topology events (per-agent execution)
};

// Steps the runner's Simulation and the exported scene side by side for `seconds`.
Comparison FlyBoth(const std::string& experiment, double seconds, int pause_every = 0) {
  ExperimentConfig config = LoadExperiment(experiment, {}, ExperimentChecks::Rendering(false));
  Simulation runner(config);
  Scratch out("scene");
  ExportExperiment(experiment, out / "export");
  mjModel* m = LoadNative(out / "export/scene.xml");
  EXPECT_NE(m, nullptr);
  Comparison c;
  if (!m) return c;
  mjData* d = mj_makeData(m);
  const mjData* r = runner.data();
  EXPECT_EQ(m->nq, runner.model()->nq);
  const int64_t steps = std::llround(seconds / config.timestep);
  const std::vector<mjtNum> start(d->qpos, d->qpos + m->nq);
  for (int64_t k = 0; k < steps; ++k) {
    runner.ComputeControls();
    runner.Integrate();
    if (pause_every > 0 && k % pause_every == 7) {
      // A paused viewer: mj_forward again and again without stepping.
      for (int i = 0; i < 3; ++i) mj_forward(m, d);
    }
    mj_step(m, d);
    for (int i = 0; i < m->nq; ++i) {
      c.max_diff = std::max(c.max_diff, std::fabs(d->qpos[i] - r->qpos[i]));
    }
    c.bitwise = c.bitwise && !std::memcmp(d->qpos, r->qpos, sizeof(mjtNum) * m->nq) &&
                !std::memcmp(d->qvel, r->qvel, sizeof(mjtNum) * m->nv) &&
                !std::memcmp(d->act, r->act, sizeof(mjtNum) * m->na);
    ++c.steps;
  }
  for (int i = 0; i < m->nq; ++i) c.moved = std::max(c.moved, std::fabs(d->qpos[i] - start[i]));
  if (const AgentChannel* channel = runner.channel()) {
    c.topology_switches = channel->network().events().size();
  }
  c.end.assign(d->qpos, d->qpos + m->nq);
  mj_deleteData(d);
  mj_deleteModel(m);
  return c;
}

// FlyBoth, expecting `steps` steps flown bit for bit with the runner and a vehicle moved by more
// than `least_moved` m (so that a scene that never flew cannot pass).
Comparison ExpectTheRunnersFlight(const std::string& experiment, double seconds, int64_t steps,
                                  double least_moved, int pause_every = 0) {
  const Comparison c = FlyBoth(experiment, seconds, pause_every);
  EXPECT_EQ(c.steps, steps);
  EXPECT_TRUE(c.bitwise) << "largest qpos difference " << c.max_diff << " m";
  EXPECT_GT(c.moved, least_moved);
  return c;
}

void ExpectSameFlight(const std::string& experiment, const std::string& model,
                      const std::string& attitude) {
  Scratch dir("flight");
  const Comparison c = FlyBoth(Variant(experiment, model, attitude, dir), 40.0);
  EXPECT_EQ(c.steps, 40000);
  EXPECT_TRUE(c.bitwise) << "largest qpos difference " << c.max_diff << " m";
  EXPECT_LE(c.max_diff, 1e-9);
  EXPECT_GT(c.moved, 10.0);  // the leader flies a 20 m circle: the comparison is not of rest
}

TEST(NativeFlight, Exp2QuadrotorIsTheRunnersTrajectory) { ExpectSameFlight("exp2.toml", "", ""); }
TEST(NativeFlight, Exp2PointMassIsTheRunnersTrajectory) {
  ExpectSameFlight("exp2.toml", "pointmass", "pointmass_direct");
}
TEST(NativeFlight, Exp3QuadrotorIsTheRunnersTrajectory) { ExpectSameFlight("exp3.toml", "", ""); }
TEST(NativeFlight, Exp3PointMassIsTheRunnersTrajectory) {
  ExpectSameFlight("exp3.toml", "pointmass", "pointmass_direct");
}

// The GNSS-grade sensors and the Kalman filter of the benchmark's b05 ([sensors] noise, bias,
// wander, rates and latency; [estimator] kf_ins), shortened to 2 s: the exported scene flown by
// plain mj_step is the runner's flight, bit for bit (every random draw, every delayed sample and
// every filter update happens in both, from the tick's state in plugin_state).
TEST(NativeFlight, GnssAndKalmanFilterAreTheRunnersTrajectory) {
  Scratch dir("gnss_kf");
  std::string text = NativeExperimentText("benchmark/b05_gnss_kf.toml");
  ASSERT_NE(text.find("\n[sensors]"), std::string::npos);
  ASSERT_NE(text.find("\n[estimator]"), std::string::npos);
  text = std::regex_replace(text, std::regex("\nduration = [0-9.]+"), "\nduration = 2.0");
  text = std::regex_replace(text, std::regex("\nmetric_window = [^\n]*"),
                            "\nmetric_window = [1.0, 2.0]");
  std::ofstream(dir / "experiment.toml") << text;
  ExpectTheRunnersFlight(dir / "experiment.toml", 2.0, 2000, 0.5);
}

// `experiment` of experiments/ shortened to `seconds` (its metric window the last half).
std::string Shortened(const std::string& experiment, double seconds) {
  std::string text = NativeExperimentText(experiment);
  text = std::regex_replace(text, std::regex("\nduration = [0-9.]+"),
                            "\nduration = " + std::to_string(seconds));
  return std::regex_replace(
      text, std::regex("\nmetric_window = [^\n]*"),
      "\nmetric_window = [" + std::to_string(seconds / 2) + ", " + std::to_string(seconds) + "]");
}

// The benchmark's b13, per-agent execution over a lossy network (100 Hz broadcasts, 20 ms
// latency, 10 % loss), shortened to 2 s: every link's loss draws, its messages in flight and
// held, and each follower's instance are in plugin_state, so plain mj_step flies the runner's
// flight, bit for bit.
TEST(NativeFlight, PerAgentOverALossyNetworkIsTheRunnersTrajectory) {
  Scratch dir("lossy_network");
  const std::string text = Shortened("benchmark/b13_lossy_network.toml", 2.0);
  ASSERT_NE(text.find("\nmode = \"per_agent\""), std::string::npos);
  std::ofstream(dir / "experiment.toml") << text;
  ExpectTheRunnersFlight(dir / "experiment.toml", 2.0, 2000, 0.5);
}

// b13 with a range-limited link between followers 1 and 2 (5 m): up while they start 1.5 m
// apart, down once the formation has spread them 10 m apart. The links' up state is in
// plugin_state, so the flight is the runner's, bit for bit, across the change.
TEST(NativeFlight, RangeLimitedLinkIsTheRunnersTrajectory) {
  Scratch dir("range_link");
  std::string text = Shortened("benchmark/b13_lossy_network.toml", 4.0);
  text += "\n[[network.link]]\nfrom = 1\nto = 2\nrange = 5.0\n";
  std::ofstream(dir / "experiment.toml") << text;
  const Comparison c = ExpectTheRunnersFlight(dir / "experiment.toml", 4.0, 4000, 0.5);
  EXPECT_GE(c.topology_switches, 1u) << "the link never went down: the range was not tested";
}

// The benchmark's b08 ([[vehicles.fault]]: rotor 0 of follower 3 keeps 70 % of its clamped
// command from `at` on), the fault moved to 1 s and the flight cut to 2 s: the exported scene
// faults the held control where the runner faults d->ctrl, so plain mj_step flies the runner's
// flight, bit for bit; and the fault acted (the flight without it ends elsewhere).
TEST(NativeFlight, RotorFaultIsTheRunnersTrajectory) {
  Scratch dir("rotor_fault");
  std::string text = Shortened("benchmark/b08_rotor_fault.toml", 2.0);
  ASSERT_NE(text.find("\nat = 15.0"), std::string::npos);
  text = std::regex_replace(text, std::regex("\nat = 15.0"), "\nat = 1.0");
  std::ofstream(dir / "experiment.toml") << text;
  const Comparison c = ExpectTheRunnersFlight(dir / "experiment.toml", 2.0, 2000, 0.5);
  // The same flight without the fault: the faulted follower's position differs by more than
  // rounding (its qpos entries are not the faulted flight's).
  const size_t fault = text.find("\n[[vehicles.fault]]");
  ASSERT_NE(fault, std::string::npos);
  std::ofstream(dir / "unfaulted.toml") << text.substr(0, fault);
  Simulation unfaulted(
      LoadExperiment(dir / "unfaulted.toml", {}, ExperimentChecks::Rendering(false)));
  for (int k = 0; k < 2000; ++k) {
    unfaulted.ComputeControls();
    unfaulted.Integrate();
  }
  ASSERT_EQ(c.end.size(), static_cast<size_t>(unfaulted.model()->nq));
  double apart = 0;
  for (size_t i = 0; i < c.end.size(); ++i) {
    apart = std::max(apart, std::fabs(c.end[i] - unfaulted.data()->qpos[i]));
  }
  EXPECT_GT(apart, 1e-3);
}

// examples/vehicles/midge/exp2_midge.toml: a foreign model mapped onto the vehicle contract
// ([vehicles] body, thrust and moments: a thrust-and-moment vehicle), cut to 2 s. Export bundles
// the model file and the plugin adapts it as the runner does and reads the vehicle's facts from
// that text, so plain mj_step flies the runner's flight, bit for bit.
TEST(NativeFlight, ForeignVehicleMappingIsTheRunnersTrajectory) {
  Scratch dir("midge");
  std::string text = mjf::testing::MidgeExperimentText();
  ASSERT_NE(text.find("\nbody = \"midge\""), std::string::npos);
  ASSERT_NE(text.find("\nthrust = \"lift\""), std::string::npos);
  ASSERT_EQ(text.find("\n[safety]"), std::string::npos);
  text = std::regex_replace(text, std::regex("\nduration = [0-9.]+"), "\nduration = 2.0");
  text = std::regex_replace(text, std::regex("\nmetric_window = [^\n]*"),
                            "\nmetric_window = [1.0, 2.0]");
  std::ofstream(dir / "experiment.toml") << text;
  ExpectTheRunnersFlight(dir / "experiment.toml", 2.0, 2000, 0.1);  // the leader flies a 2 m circle
}

// examples/vehicles/bumblebee: a foreign rotor vehicle (its own body and rotor names, its own
// sensors, a mesh and a texture below its meshdir, 20 ms motor lag) mapped by [vehicles] body and
// rotors into Exp 2, cut to 2 s. Export bundles the model with its asset files; the plugin adapts
// the copy, so plain mj_step flies the runner's flight, bit for bit.
TEST(NativeFlight, ForeignRotorVehicleWithAssetsIsTheRunnersTrajectory) {
  Scratch dir("bumblebee");
  const std::string model =
      std::string(MJF_SOURCE_DIR) + "/examples/vehicles/bumblebee/bumblebee.xml";
  std::string text = NativeExperimentText("exp2.toml", model);
  const std::string line = "\nmodel = \"" + model + "\"";
  ASSERT_NE(text.find(line), std::string::npos);
  text.insert(text.find(line) + line.size(),
              "\nbody = \"bumblebee\"\nrotors = [\"prop_a\", \"prop_b\", \"prop_c\", "
              "\"prop_d\"]");
  text = std::regex_replace(text, std::regex("\nduration = [0-9.]+"), "\nduration = 2.0");
  text = std::regex_replace(text, std::regex("\nmetric_window = [^\n]*"),
                            "\nmetric_window = [1.0, 2.0]");
  std::ofstream(dir / "experiment.toml") << text;
  ExpectTheRunnersFlight(dir / "experiment.toml", 2.0, 2000, 0.5);
}

// b13 shortened to 1 s, with `execution` added to its [execution] table and `network` in place
// of its `loss = 0.1` line.
std::string B13Variant(const std::string& execution, const std::string& network) {
  std::string text = Shortened("benchmark/b13_lossy_network.toml", 1.0);
  EXPECT_NE(text.find("\nloss = 0.1 "), std::string::npos) << "b13's [network] loss moved";
  text = std::regex_replace(text, std::regex("\n\\[execution\\]"), "\n[execution]\n" + execution);
  return std::regex_replace(text, std::regex("\nloss = 0.1 "), "\n" + network + " ");
}

// The channel's other parts (Jacobi rounds, input prediction, clock offsets and drift, jitter,
// Gilbert-Elliott bursts, a link of its own) on b13, 1 s: the runner's flight, bit for bit.
TEST(NativeFlight, JacobiRoundsClocksAndBurstsAreTheRunnersTrajectory) {
  Scratch dir("jacobi_network");
  std::string text = B13Variant(
      "coupling = \"jacobi\"\njacobi_rounds = 2\npredict = \"input\"\nclock_offset = 0.004\n"
      "clock_drift_ppm = 50.0",
      "jitter = 0.005\nloss_model = \"gilbert_elliott\"\nburst_enter = 0.1\nburst_exit = 0.5\n"
      "loss = 0.05");
  text += "\n[[network.link]]\nfrom = 0\nto = 1\nlatency = 0.004\nloss = 0.0\n";
  std::ofstream(dir / "experiment.toml") << text;
  ExpectTheRunnersFlight(dir / "experiment.toml", 1.0, 1000, 0.1);
}

// Jacobi's exchange rounds carried over b13's lossy, late links, with a round timeout, 1 s: the
// letters in flight, the exchanges waiting for them and their counts are in plugin_state, and
// plain mj_step flies the runner's flight, bit for bit.
TEST(NativeFlight, JacobiRoundsOverTheLinksAreTheRunnersTrajectory) {
  Scratch dir("rounds_over_links");
  std::ofstream(dir / "experiment.toml")
      << B13Variant("coupling = \"jacobi\"\njacobi_rounds = 3\npredict = \"input\"",
                    "rounds = \"over_links\"\nround_timeout = 0.02\nloss = 0.1");
  ExpectTheRunnersFlight(dir / "experiment.toml", 1.0, 1000, 0.1);
}

// The central solve over the links (each R_i up to the solver, each W_i back down its own link)
// with the followers' clocks out of phase, on the point mass, 2 s: the runner's flight.
TEST(NativeFlight, CentralSolveOverTheLinksIsTheRunnersTrajectory) {
  Scratch dir("solve_over_links");
  std::string text = Shortened("exp2.toml", 2.0);
  text = std::regex_replace(text, std::regex("\nmodel = \"quadrotor\""), "\nmodel = \"pointmass\"");
  text = std::regex_replace(text, std::regex("\\[attitude\\][^\\[]*"),
                            "[attitude]\nplugin = \"pointmass_direct\"\n\n");
  text +=
      "\n[execution]\nmode = \"per_agent\"\ncoupling = \"central_solve\"\n"
      "predict = \"input\"\nclock_offset = 0.02\n"
      "[network]\nlatency = 0.004\nrounds = \"over_links\"\n";
  std::ofstream(dir / "experiment.toml") << text;
  ExpectTheRunnersFlight(dir / "experiment.toml", 2.0, 2000, 0.5);
}

// The benchmark's b06, a 3 m/s wind with moderate Dryden turbulence, shortened to 3 s: the wind
// field (its Dryden filters, held samples and random streams) is in plugin_state, its drag is
// added into qfrc_passive as the runner adds it, and plain mj_step flies the runner's flight,
// bit for bit; so it does with a paused viewer's mj_forward calls in between (qfrc_passive is
// recomputed by each, and the drag added once to each).
TEST(NativeFlight, GustyWindIsTheRunnersTrajectory) {
  Scratch dir("gusty_wind");
  const std::string text = Shortened("benchmark/b06_gusty_wind.toml", 3.0);
  ASSERT_NE(text.find("\nturbulence = \"moderate\""), std::string::npos);
  std::ofstream(dir / "experiment.toml") << text;
  for (const int pause_every : {0, 100}) {
    ExpectTheRunnersFlight(dir / "experiment.toml", 3.0, 3000, 0.5, pause_every);
  }
}

// The benchmark's b10, its three 1-cosine gusts moved to 0.2, 1.0 and 1.8 s (from 26, 31 and
// 35 s) of a 6 s flight: the runner's flight, bit for bit, through the gusts.
TEST(NativeFlight, GustsAreTheRunnersTrajectory) {
  Scratch dir("gusts");
  std::string text = Shortened("benchmark/b10_gusts.toml", 6.0);
  for (const auto& [from, to] :
       {std::pair<std::string, std::string>{"26.0", "0.2"}, {"31.0", "1.0"}, {"35.0", "1.8"}}) {
    const size_t at = text.find("start = " + from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, 8 + from.size(), "start = " + to);
  }
  std::ofstream(dir / "experiment.toml") << text;
  ExpectTheRunnersFlight(dir / "experiment.toml", 6.0, 6000, 0.5);
}

// A rotor fault with the wrench rotor model: the faulted controls are held in plugin_state and
// drive the rotors' motor lags there, as the runner's faulted actuation drives its wrench model.
TEST(NativeFlight, RotorFaultOnTheWrenchRotorModelIsTheRunnersTrajectory) {
  Scratch dir("wrench_fault");
  std::string text = Shortened("benchmark/b08_rotor_fault.toml", 2.0);
  ASSERT_NE(text.find("\nat = 15.0"), std::string::npos);
  text = std::regex_replace(text, std::regex("\nat = 15.0"), "\nat = 1.0");
  const size_t at = text.find("followers = 6");
  ASSERT_NE(at, std::string::npos);
  text.insert(at + 13, "\nrotor_model = \"wrench\"");
  std::ofstream(dir / "experiment.toml") << text;
  ExpectTheRunnersFlight(dir / "experiment.toml", 2.0, 2000, 0.5);
}

// Exp 2 with [vehicles] rotor_model = "wrench": the runner's rotor wrenches (thrust and yaw
// torque per rotor, the motor lags in plugin_state) added into qfrc_passive, with the exported
// scene's one zero-gear actuator only there so that MuJoCo calls the plugin. 10 s, bit for bit.
TEST(NativeFlight, WrenchRotorModelIsTheRunnersTrajectory) {
  Scratch dir("wrench");
  std::string text = Shortened("exp2.toml", 10.0);
  const size_t at = text.find("followers = 6");
  ASSERT_NE(at, std::string::npos);
  text.insert(at + 13, "\nrotor_model = \"wrench\"");
  std::ofstream(dir / "experiment.toml") << text;
  ExpectTheRunnersFlight(dir / "experiment.toml", 10.0, 10000, 3.0, 300);
}

// Repeated mj_forward between steps (a paused viewer) leaves the held commands as they were:
// the flight that follows is still the runner's, bit for bit.
TEST(NativeFlight, PausedViewerLeavesHeldCommands) {
  Scratch dir("paused");
  const std::string experiment = Variant("exp2.toml", "", "", dir);
  Scratch out("paused_scene");
  ExportExperiment(experiment, out / "export");
  mjModel* m = LoadNative(out / "export/scene.xml");
  ASSERT_NE(m, nullptr);
  mjData* d = mj_makeData(m);
  for (int k = 0; k < 1234; ++k) mj_step(m, d);
  mj_forward(m, d);
  const std::vector<mjtNum> state(d->plugin_state, d->plugin_state + m->npluginstate);
  const std::vector<mjtNum> force(d->actuator_force, d->actuator_force + m->nu);
  const std::vector<mjtNum> act_dot(d->act_dot, d->act_dot + m->na);
  for (int i = 0; i < 20; ++i) mj_forward(m, d);
  // Bytes: the state holds NaNs (a setpoint's sliding diagnostic, undriven actuators).
  EXPECT_EQ(std::memcmp(state.data(), d->plugin_state, sizeof(mjtNum) * state.size()), 0);
  EXPECT_EQ(force, std::vector<mjtNum>(d->actuator_force, d->actuator_force + m->nu));
  EXPECT_EQ(act_dot, std::vector<mjtNum>(d->act_dot, d->act_dot + m->na));
  mj_deleteData(d);
  mj_deleteModel(m);
  const Comparison c = FlyBoth(experiment, 5.0, 50);
  EXPECT_TRUE(c.bitwise) << "largest qpos difference " << c.max_diff << " m";
}

// A bad key or value is refused when the model compiles, naming plugin, instance and key.
std::string CompileWith(const std::string& key, const std::string& from, const std::string& to) {
  Scratch dir("refusal");
  const std::string experiment = Variant("exp2.toml", "", "", dir);
  std::vector<std::string> notes;
  std::string xml = ExportedSceneXml(experiment, {}, &notes);
  const std::string anchor = "<config key=\"" + key + "\" value=\"";
  const size_t at = xml.find(anchor);
  EXPECT_NE(at, std::string::npos) << key;
  const size_t value = at + anchor.size();
  const size_t found = xml.find(from, at);
  EXPECT_LT(found, xml.find('"', value)) << from;
  xml.replace(found, from.size(), to);
  const std::string path = dir / "scene.xml";
  std::ofstream(path) << xml;
  std::string error;
  mjModel* m = LoadNative(path, &error);
  EXPECT_EQ(m, nullptr);
  if (m) mj_deleteModel(m);
  return error;
}

TEST(NativeConfig, BadValueIsRefusedAtCompile) {
  const std::string error = CompileWith("formation", "q = 4.5", "q = -4.5");
  EXPECT_NE(error.find("mjformation.swarm"), std::string::npos) << error;
  EXPECT_NE(error.find("instance 'swarm'"), std::string::npos) << error;
  EXPECT_NE(error.find("[formation] q:"), std::string::npos) << error;
}

TEST(NativeConfig, UnknownKeyIsRefusedAtCompile) {
  const std::string error = CompileWith("leader", "radius = 20.0", "radius = 20.0, radios = 3.0");
  EXPECT_NE(error.find("mjformation.swarm"), std::string::npos) << error;
  EXPECT_NE(error.find("instance 'swarm'"), std::string::npos) << error;
  EXPECT_NE(error.find("radios"), std::string::npos) << error;
}

// A value is one table's keys: one that closes its table and opens a section of its own (a
// newline written as &#10;) is refused, not read as more of the experiment.
TEST(NativeConfig, ValueThatOpensASectionIsRefused) {
  const std::string error = CompileWith("leader", "radius = 20.0",
                                        "radius = 20.0 }&#10;[wind]&#10;mean = [5.0, 0.0, 0.0]"
                                        "&#10;gust = { a = 1");
  EXPECT_NE(error.find("<config key=\"leader\">"), std::string::npos) << error;
  EXPECT_NE(error.find("closes the table"), std::string::npos) << error;
}

// A scene edited past the bound of messages in flight (per-agent execution over a link of 1 s
// delay at a broadcast every step) is refused when MuJoCo compiles it, naming the keys and the
// numbers, as export refuses it.
TEST(NativeConfig, MessagesInFlightPastTheBoundAreRefusedAtCompile) {
  Scratch dir("in_flight");
  std::vector<std::string> notes;
  std::string xml = ExportedSceneXml(Variant("exp2.toml", "", "", dir), {}, &notes);
  for (const auto& [key, value] :
       {std::pair<std::string, std::string>{"execution", "mode = &quot;per_agent&quot;"},
        {"network", "latency = 1.0"}}) {
    const std::string empty = "<config key=\"" + key + "\" value=\"\"";
    ASSERT_NE(xml.find(empty), std::string::npos) << key;
    xml.replace(xml.find(empty), empty.size(),
                "<config key=\"" + key + "\" value=\"" + value + "\"");
  }
  std::ofstream(dir / "scene.xml") << xml;
  std::string error;
  mjModel* m = LoadNative(dir / "scene.xml", &error);
  EXPECT_EQ(m, nullptr);
  if (m) mj_deleteModel(m);
  EXPECT_NE(error.find("[network] latency = 1 s"), std::string::npos) << error;
  EXPECT_NE(error.find("up to 1001 messages in flight"), std::string::npos) << error;
}

// One swarm flies every vehicle of a scene: a second instance is refused, naming both.
TEST(NativeConfig, ASecondSwarmIsRefused) {
  Scratch dir("second_swarm");
  std::vector<std::string> notes;
  std::string xml = ExportedSceneXml(Variant("exp2.toml", "", "", dir), {}, &notes);
  const std::string open = "<instance name=\"swarm\">";
  xml.replace(xml.find(open), open.size(), "<instance name=\"second\"/>\n      " + open);
  std::ofstream(dir / "scene.xml") << xml;
  std::string error;
  mjModel* m = LoadNative(dir / "scene.xml", &error);
  EXPECT_EQ(m, nullptr);
  if (m) mj_deleteModel(m);
  EXPECT_NE(error.find("a second swarm instance"), std::string::npos) << error;
  EXPECT_NE(error.find("'second'"), std::string::npos) << error;
  EXPECT_NE(error.find("'swarm'"), std::string::npos) << error;
}

TEST(NativeConfig, UnknownConfigKeyIsRefusedByMuJoCo) {
  const std::string error =
      CompileWith("leader", "<config key=\"leader\"", "<config key=\"leeder\"");
  EXPECT_NE(error.find("leeder"), std::string::npos) << error;
}

// Export refuses, naming file, section and key, what the native path cannot carry; the message
// is the user's only notice, so each is checked.
std::string ExportRefusal(const std::string& append, const std::string& after = "") {
  Scratch dir("export_refusal");
  std::string text = ReadFile(Variant("exp2.toml", "", "", dir));
  if (after.empty()) {
    text += append;
  } else {
    text.insert(text.find(after) + after.size(), append);
  }
  std::ofstream(dir / "experiment.toml") << text;
  try {
    ExportExperiment(dir / "experiment.toml", dir / "out");
  } catch (const std::runtime_error& e) {  // ExportError, or the parser's ConfigError
    EXPECT_FALSE(fs::exists(dir / "out")) << "nothing is written on a refusal";
    return e.what();
  }
  ADD_FAILURE() << "exported: " << append;
  return "";
}

// Exchange rounds over the links whose letters in flight pass what plugin_state holds: 60
// Jacobi rounds a sample every 50 steps over links 1 ms late keep 60 x (1 / 49 + 2) = 120 letters
// on a link, refused naming the keys and the numbers.
TEST(NativeExport, RefusesRoundLettersInFlightPastTheNativeBound) {
  const std::string e = ExportRefusal(
      "\n[execution]\nmode = \"per_agent\"\ncoupling = \"jacobi\"\njacobi_rounds = 60\n"
      "[network]\nlatency = 0.001\nrounds = \"over_links\"\n");
  EXPECT_NE(e.find("experiment.toml:"), std::string::npos) << e;
  EXPECT_NE(e.find("[network] latency = 0.001 s and jitter = 0 s with 60 exchange rounds a "
                   "sample every 0.05 s keep up to 120 round letters in flight on a link"),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("at most 100"), std::string::npos) << e;
}

// A link whose messages in flight pass what plugin_state holds: refused naming the keys and the
// numbers (1 s of delay at a broadcast every step: 1001 messages).
TEST(NativeExport, RefusesMessagesInFlightPastTheNativeBound) {
  const std::string e = ExportRefusal(
      "\n[execution]\nmode = \"per_agent\"\n[network]\nlatency = 0.01\n"
      "[[network.link]]\nfrom = 0\nto = 1\nlatency = 1.0\n");
  EXPECT_NE(e.find("experiment.toml:"), std::string::npos) << e;
  EXPECT_NE(e.find("[[network.link]] from = 0, to = 1: latency = 1 s"), std::string::npos) << e;
  EXPECT_NE(e.find("up to 1001 messages in flight"), std::string::npos) << e;
  EXPECT_NE(e.find("at most 100 "), std::string::npos) << e;
}

// Every section the runner reads is carried or noted: a section export refuses is one the
// runner refuses too, worded as `run` words it (the known sections listed).
TEST(NativeExport, RefusesAnUnknownSectionAsTheRunnerDoes) {
  const std::string e = ExportRefusal("\n[wnd]\nmean = [3.0, 0.0, 0.0]\n");
  EXPECT_NE(e.find("experiment.toml:"), std::string::npos) << e;
  EXPECT_NE(e.find("[wnd]: unknown section (known: "), std::string::npos) << e;
  EXPECT_NE(e.find("wind"), std::string::npos) << e;
  EXPECT_EQ(e.find("no wind or disturbance"), std::string::npos) << "the stale reason: " << e;
}

// [safety] only records (stop_on, which ends a run, is refused on its own): the scene is
// written, and a note says that the events are the runner's alone.
TEST(NativeExport, SafetyIsANoteNotARefusal) {
  Scratch dir("export_safety");
  std::string text = ReadFile(Variant("exp2.toml", "", "", dir));
  text += "\n[safety]\nflip_tilt_deg = 80.0\nnear_miss_m = 0.5\n";
  std::ofstream(dir / "experiment.toml") << text;
  const ExportResult result = ExportExperiment(dir / "experiment.toml", dir / "out");
  EXPECT_TRUE(fs::exists(result.scene_path));
  std::string safety_note;
  for (const std::string& note : result.notes) {
    if (note.rfind("[safety]", 0) == 0) safety_note = note;
  }
  EXPECT_NE(safety_note.find("[safety] is not carried: "), std::string::npos) << safety_note;
  EXPECT_NE(safety_note.find("recorded by the runner only"), std::string::npos) << safety_note;
  EXPECT_EQ(ReadFile(result.scene_path).find("flip_tilt_deg"), std::string::npos);
  mjModel* m = LoadNative(result.scene_path);
  EXPECT_NE(m, nullptr);
  if (m) mj_deleteModel(m);
}

// A latency buffer past what plugin_state holds: refused naming the key and both numbers.
TEST(NativeExport, RefusesALatencyPastTheNativeBound) {
  const std::string e = ExportRefusal("\n[sensors]\nposition_latency = 1.5\n");
  EXPECT_NE(e.find("experiment.toml:"), std::string::npos) << e;
  EXPECT_NE(e.find("[sensors] position_latency = 1.5 s is 1500 physics steps"), std::string::npos)
      << e;
  EXPECT_NE(e.find("at most 1000"), std::string::npos) << e;
}

TEST(NativeExport, NeverWritesIntoAUsersDirectory) {
  Scratch dir("export_owned");
  const std::string experiment = Variant("exp2.toml", "", "", dir);
  fs::create_directories(dir / "out");
  std::ofstream(dir / "out/mine.txt") << "mine";
  try {
    ExportExperiment(experiment, dir / "out");
    ADD_FAILURE() << "wrote into a non-empty directory";
  } catch (const ExportError& e) {
    EXPECT_NE(std::string(e.what()).find("exists and is not empty; pass --overwrite"),
              std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(fs::exists(dir / "out/scene.xml"));
  ExportExperiment(experiment, dir / "out", {{}, {}, /*overwrite=*/true});
  EXPECT_TRUE(fs::exists(dir / "out/scene.xml"));
  EXPECT_EQ(ReadFile(dir / "out/mine.txt"), "mine");
}

}  // namespace
}  // namespace mjf::runner
