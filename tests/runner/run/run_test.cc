// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// End-to-end runs of the simulation core: hover and circle tracking on the quadrotor, run
// directories, partial results on a failure mid-run, determinism, and two simulations on two
// threads at once.
//
// Unit tests of the source:
// runner/run/src/run.cc: one run end to end: an interrupt ends it cleanly with summary.json saying
// so; no run directory means nothing written; the version string.
#include "mjformation/run/run.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <csignal>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <thread>

#include "mjformation/record/output.hpp"
#include "mjformation/run/interrupt.hpp"
#include "mjformation/sim/simulation.hpp"
#include "point_mass_util.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

using mjf::testing::ReadPng;

using mjf::testing::HoverExperiment;
using mjf::testing::Parse;
using mjf::testing::ReadFile;
using mjf::testing::TempDir;
using ::testing::HasSubstr;

// Followers under `hover` hold position within 0.1 m and altitude within 0.05 m.
TEST(FlightTest, HoverHoldsPositionAndAltitude) {
  Simulation sim(Parse(HoverExperiment(6, 20.0)));
  double worst_xy = 0, worst_z = 0;
  for (int64_t step = 0; step < sim.total_steps(); ++step) {
    sim.ComputeControls();
    if (sim.time() >= 3.0) {  // after the motors spin up from rest
      for (int i = 0; i < sim.n_vehicles(); ++i) {
        const auto& s = sim.states()[i];
        const auto& sp = sim.setpoints()[i];
        worst_xy = std::max(worst_xy, std::hypot(s.pos[0] - sp.pos[0], s.pos[1] - sp.pos[1]));
        worst_z = std::max(worst_z, std::abs(s.pos[2] - 2.0));
      }
    }
    sim.Integrate();
  }
  RecordProperty("worst_horizontal_error_m", std::to_string(worst_xy));
  RecordProperty("worst_altitude_error_m", std::to_string(worst_z));
  EXPECT_LT(worst_xy, 0.1);
  EXPECT_LT(worst_z, 0.05);
}

// The leader tracks its 20 m / 0.157 rad/s circle within 0.5 m after 10 s.
TEST(FlightTest, LeaderTracksCircle) {
  std::string text = HoverExperiment(2, 40.0);
  text.replace(text.find("leader_start = [0.0, 0.0]"), 25, "leader_start = [20.0, 0.0]");
  text.replace(text.find("[leader]\nplugin = \"hover\""), 25,
               "[leader]\nplugin = \"circle\"\nradius = 20.0\nomega = 0.157\naltitude = 2.0");
  Simulation sim(Parse(text));
  double worst = 0;
  for (int64_t step = 0; step < sim.total_steps(); ++step) {
    sim.ComputeControls();
    const double t = sim.time();
    if (t >= 10.0) {
      const auto& p = sim.states()[0].pos;
      const double rx = 20.0 * std::cos(0.157 * t), ry = 20.0 * std::sin(0.157 * t);
      worst = std::max(worst, std::hypot(p[0] - rx, p[1] - ry));
    }
    sim.Integrate();
  }
  RecordProperty("worst_leader_error_m", std::to_string(worst));
  EXPECT_LT(worst, 0.5);
}

std::string SnapshotExperiment(double duration) {
  return HoverExperiment(2, duration, "seed = 7\n") +
         "[render]\nsnapshots = [0.0, 1.0]\nwidth = 320\nheight = 240\ndistance = 12.0\n";
}

nlohmann::json Summary(const std::string& dir) {
  return nlohmann::json::parse(ReadFile(dir + "/summary.json"));
}

TEST(RunTest, WritesACompleteRunDirectory) {
  const std::string out = TempDir("run") + "/r";
  RunOptions options;
  options.out_dir = out;
  const RunResult r = RunExperiment(Parse(SnapshotExperiment(1.0)), options);
  ASSERT_TRUE(r.complete) << r.error;
  const nlohmann::json s = Summary(out);
  EXPECT_TRUE(s["complete"].get<bool>());
  EXPECT_EQ(s["seed"], 7);
  EXPECT_EQ(s["config_sha256"].get<std::string>().size(), 64u);
  EXPECT_GT(s["timing"]["real_time_factor"].get<double>(), 0.0);
  // The engine that ran: its version and the SHA-256 of its library file (64 hex digits; the
  // Python tests check it against the file itself).
  EXPECT_EQ(s["versions"]["mujoco"].get<std::string>(), std::string(mj_versionString()));
  EXPECT_THAT(s["versions"]["mujoco_library_sha256"].get<std::string>(),
              ::testing::MatchesRegex("[0-9a-f]{64}"));
  // timeseries: header + one row per 10 ms over 1 s, inclusive.
  const std::string csv = ReadFile(out + "/timeseries.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 101);
  EXPECT_THAT(csv.substr(0, 40), HasSubstr("t,sigma_f,uav0_px,uav0_py"));
  // The composed scene loads in MuJoCo alone.
  char error[1000] = "";
  mjModel* m = mj_loadXML((out + "/scene.xml").c_str(), nullptr, error, sizeof(error));
  ASSERT_NE(m, nullptr) << error;
  EXPECT_GE(mj_name2id(m, mjOBJ_BODY, "uav2_vehicle"), 0);
  mj_deleteModel(m);
  // Snapshots are real renders: right size, not a flat image.
  ASSERT_EQ(s["snapshots"].size(), 2u);
  int w = 0, h = 0;
  const auto px = ReadPng(out + "/" + s["snapshots"][1].get<std::string>(), &w, &h);
  ASSERT_EQ(w, 320);
  ASSERT_EQ(h, 240);
  double mean = 0, var = 0;
  for (unsigned char v : px) mean += v;
  mean /= px.size();
  for (unsigned char v : px) var += (v - mean) * (v - mean);
  EXPECT_GT(std::sqrt(var / px.size()), 10.0);
}

TEST(RunTest, RefusesToOverwriteAnExistingRun) {
  const std::string out = TempDir("ovw") + "/r";
  RunOptions options;
  options.out_dir = out;
  options.render = false;
  ASSERT_TRUE(RunExperiment(Parse(HoverExperiment(1, 0.2)), options).complete);
  const std::string before = ReadFile(out + "/timeseries.csv");
  EXPECT_THROW(RunExperiment(Parse(HoverExperiment(1, 0.3)), options), OutputError);
  EXPECT_EQ(ReadFile(out + "/timeseries.csv"), before);
  options.overwrite = true;
  EXPECT_TRUE(RunExperiment(Parse(HoverExperiment(1, 0.3)), options).complete);
}

// A run that goes non-finite stops with a clear error and keeps what it recorded, marked.
TEST(RunTest, NonFiniteRunKeepsPartialResultsMarkedIncomplete) {
  std::string text = HoverExperiment(1, 3.0);
  text.replace(text.find("[leader]\nplugin = \"hover\""), 25,
               "[leader]\nplugin = \"test_nan\"\nafter = 1.0");
  const std::string out = TempDir("nan") + "/r";
  RunOptions options;
  options.out_dir = out;
  const RunResult r = RunExperiment(Parse(text), options);
  EXPECT_FALSE(r.complete);
  EXPECT_THAT(r.error, HasSubstr("non-finite"));
  const nlohmann::json s = Summary(out);
  EXPECT_FALSE(s["complete"].get<bool>());
  EXPECT_THAT(s["error"].get<std::string>(), HasSubstr("t = 1.000 s"));
  const std::string csv = ReadFile(out + "/timeseries.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 100);  // rows for t in [0, 1) s
}

// A MuJoCo warning (here bad ctrl: an absurd force command on the point mass) stops the run the
// same way.
TEST(RunTest, MujocoWarningStopsTheRunAndKeepsWhatWasRecorded) {
  std::string text = HoverExperiment(1, 3.0);
  text.replace(text.find("model = \"quadrotor\""), 19, "model = \"pointmass\"");
  text.replace(text.find("plugin = \"pd_cascade\""), 21, "plugin = \"pointmass_direct\"");
  text.replace(text.find("[leader]\nplugin = \"hover\""), 25,
               "[leader]\nplugin = \"test_huge\"\nafter = 0.5");
  const std::string out = TempDir("qacc") + "/r";
  RunOptions options;
  options.out_dir = out;
  const RunResult r = RunExperiment(Parse(text), options);
  EXPECT_FALSE(r.complete);
  EXPECT_THAT(r.error, HasSubstr("t = 0.501 s: MuJoCo warning: Nan, Inf or huge value in CTRL"));
  const nlohmann::json s = Summary(out);
  EXPECT_FALSE(s["complete"].get<bool>());
  const std::string csv = ReadFile(out + "/timeseries.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 51);  // rows for t in [0, 0.5] s
}

// Same config and seed: the same bytes in every file (summary.json's "timing" aside).
void ExpectSameRunFiles(const std::string& a, const std::string& b) {
  for (const char* f : {"config.toml", "scene.xml", "timeseries.csv", "snapshots/t000.00.png",
                        "snapshots/t001.00.png"}) {
    const std::string fa = ReadFile(a + "/" + f), fb = ReadFile(b + "/" + f);
    EXPECT_FALSE(fa.empty()) << f;
    EXPECT_TRUE(fa == fb) << f << " differs between " << a << " and " << b;
  }
  nlohmann::json sa = Summary(a), sb = Summary(b);
  sa.erase("timing");
  sb.erase("timing");
  EXPECT_EQ(sa.dump(), sb.dump());
}

TEST(RunTest, SameConfigAndSeedGiveIdenticalFiles) {
  const std::string root = TempDir("det");
  RunOptions options;
  options.out_dir = root + "/a";
  ASSERT_TRUE(RunExperiment(Parse(SnapshotExperiment(1.0)), options).complete);
  options.out_dir = root + "/b";
  ASSERT_TRUE(RunExperiment(Parse(SnapshotExperiment(1.0)), options).complete);
  ExpectSameRunFiles(root + "/a", root + "/b");
}

// Two simulations on two threads of one process do not interfere: each gives the files it gives
// when run alone.
TEST(RunTest, ConcurrentRunsMatchSoloRuns) {
  const std::string root = TempDir("conc");
  const std::string text_a = SnapshotExperiment(1.0);
  std::string text_b = SnapshotExperiment(1.0);
  text_b.replace(text_b.find("leader_start = [0.0, 0.0]"), 25, "leader_start = [1.0, -1.0]");
  auto run = [&](const std::string& text, const std::string& out) {
    RunOptions options;
    options.out_dir = out;
    EXPECT_TRUE(RunExperiment(Parse(text), options).complete);
  };
  run(text_a, root + "/solo_a");
  run(text_b, root + "/solo_b");
  std::thread ta([&] { run(text_a, root + "/conc_a"); });
  std::thread tb([&] { run(text_b, root + "/conc_b"); });
  ta.join();
  tb.join();
  ExpectSameRunFiles(root + "/solo_a", root + "/conc_a");
  ExpectSameRunFiles(root + "/solo_b", root + "/conc_b");
  EXPECT_NE(ReadFile(root + "/solo_a/timeseries.csv"), ReadFile(root + "/solo_b/timeseries.csv"));
}

// A MuJoCo engine error ends the simulation on the thread that raised it, and only that one:
// the run beside it on another thread completes with the bytes of its solo run.
TEST(RunTest, EngineErrorOnOneThreadLeavesTheOtherRunIntact) {
  const std::string root = TempDir("engine");
  std::string faulty = SnapshotExperiment(1.0);
  faulty.replace(faulty.find("[leader]\nplugin = \"hover\""), 25,
                 "[leader]\nplugin = \"test_engine_error\"\nafter = 0.3");
  const std::string healthy = SnapshotExperiment(1.0);
  auto run = [&](const std::string& text, const std::string& out) {
    RunOptions options;
    options.out_dir = out;
    return RunExperiment(Parse(text), options);
  };
  ASSERT_TRUE(run(healthy, root + "/solo").complete);
  RunResult bad, good;
  std::thread ta([&] { bad = run(faulty, root + "/faulty"); });
  std::thread tb([&] { good = run(healthy, root + "/healthy"); });
  ta.join();
  tb.join();
  EXPECT_FALSE(bad.complete);
  EXPECT_THAT(bad.error, HasSubstr("MuJoCo error: test_engine_error"));
  EXPECT_NEAR(bad.sim_time_s, 0.3, 1e-9);
  EXPECT_FALSE(Summary(root + "/faulty")["complete"].get<bool>());
  EXPECT_TRUE(good.complete) << good.error;
  ExpectSameRunFiles(root + "/solo", root + "/healthy");
}

using mjf::testing::Parse;
using mjf::testing::PointMassExperiment;
using mjf::testing::ReadFile;
using mjf::testing::TempDir;
using ::testing::HasSubstr;

RunOptions Quiet(const std::string& dir) {
  RunOptions o;
  o.out_dir = dir;
  o.render = false;
  return o;
}

TEST(RunExperimentTest, AnInterruptBeforeTheFirstStepEndsTheRunCleanly) {
  const std::string dir = TempDir("run_int") + "/run";
  RequestInterrupt(SIGTERM);
  const RunResult r = RunExperiment(Parse(PointMassExperiment(-2, 1, 2, 1, 0.05)), Quiet(dir));
  ClearInterrupt();
  EXPECT_FALSE(r.complete);
  EXPECT_EQ(r.signal, SIGTERM);
  EXPECT_EQ(r.error, "interrupted by SIGTERM");
  EXPECT_EQ(r.steps, 0);
  EXPECT_EQ(r.sim_time_s, 0.0);
  const auto s = nlohmann::json::parse(ReadFile(dir + "/summary.json"));
  EXPECT_EQ(s["complete"], false);
  EXPECT_EQ(s["interrupted_by_signal"], SIGTERM);
  EXPECT_EQ(s["error"], "interrupted by SIGTERM");
  // Everything before the loop is there: the config echo, the scene, the CSV header.
  EXPECT_TRUE(std::filesystem::exists(dir + "/config.toml"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/scene.xml"));
  const std::string csv = ReadFile(dir + "/timeseries.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1);
}

TEST(RunExperimentTest, SigintIsNamedToo) {
  RequestInterrupt(SIGINT);
  const RunResult r = RunExperiment(Parse(PointMassExperiment(-2, 1, 2, 1, 0.05)), RunOptions{});
  ClearInterrupt();
  EXPECT_EQ(r.error, "interrupted by SIGINT");
  EXPECT_EQ(r.summary["interrupted_by_signal"], SIGINT);
}

TEST(RunExperimentTest, SighupIsNamedToo) {
  RequestInterrupt(SIGHUP);
  const RunResult r = RunExperiment(Parse(PointMassExperiment(-2, 1, 2, 1, 0.05)), RunOptions{});
  ClearInterrupt();
  EXPECT_EQ(r.error, "interrupted by SIGHUP");
  EXPECT_EQ(r.summary["interrupted_by_signal"], SIGHUP);
}

TEST(RunExperimentTest, WithoutARunDirectoryNothingIsWrittenAndTheSummaryIsReturned) {
  const std::string cwd = TempDir("run_nodir");
  const auto before = std::distance(std::filesystem::directory_iterator(cwd),
                                    std::filesystem::directory_iterator());
  const RunResult r = RunExperiment(Parse(PointMassExperiment(-2, 1, 2, 1, 0.02)), RunOptions{});
  EXPECT_TRUE(r.complete) << r.error;
  EXPECT_EQ(r.steps, 20);
  EXPECT_DOUBLE_EQ(r.sim_time_s, 0.02);
  EXPECT_EQ(r.summary["complete"], true);
  EXPECT_EQ(r.summary["steps"], 20);
  // Metrics are still computed (sigma_f of the start, 1 record tick every 10 steps + the last).
  EXPECT_EQ(r.summary["metrics"]["sigma_f_samples"], 3);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(cwd),
                          std::filesystem::directory_iterator()),
            before);
}

TEST(RunExperimentTest, TheSummaryOnDiskIsTheReturnedOne) {
  const std::string dir = TempDir("run_same") + "/run";
  const RunResult r = RunExperiment(Parse(PointMassExperiment(-2, 1, 2, 1, 0.02)), Quiet(dir));
  ASSERT_TRUE(r.complete) << r.error;
  EXPECT_EQ(ReadFile(dir + "/summary.json"), r.summary.dump(2) + "\n");
  EXPECT_GT(r.wall_time_s, 0.0);
  EXPECT_EQ(r.summary_error, "");
}

TEST(RunExperimentTest, VersionString) {
  EXPECT_THAT(VersionString(),
              ::testing::MatchesRegex("mjformation [0-9]+\\.[0-9]+\\.[0-9]+ \\(MuJoCo .*, plugin "
                                      "ABI [0-9]+\\)"));
  EXPECT_THAT(VersionString(), HasSubstr(std::string("MuJoCo ") + mj_versionString()));
  EXPECT_THAT(VersionString(), HasSubstr("plugin ABI " + std::to_string(MJF_ABI_VERSION)));
}

}  // namespace
}  // namespace mjf::runner
