// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Partitioned physics ([run] threads): the same bytes as the single whole-swarm model (Exp 2
// with 6 followers, a 200-follower ring, both with wind and sensors), a failure inside one
// partition ending the run by the failure contract, and the input it refuses.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <thread>

#include "mjformation/config/config.hpp"
#include "mjformation/run/run.hpp"
#include "mjformation/sim/mujoco_errors.hpp"
#include "mjformation/sim/simulation.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

using mjf::testing::HoverExperiment;
using mjf::testing::Parse;
using mjf::testing::ReadFile;
using mjf::testing::TempDir;
using mjf::testing::WriteFile;
using ::testing::HasSubstr;

nlohmann::json SummaryWithoutTiming(const std::string& dir) {
  nlohmann::json s = nlohmann::json::parse(ReadFile(dir + "/summary.json"));
  s.erase("timing");
  return s;
}

RunResult RunInto(ExperimentConfig config, int threads, const std::string& out) {
  config.threads = threads;
  RunOptions options;
  options.out_dir = out;
  options.overwrite = true;
  options.progress = false;
  return RunExperiment(config, options);
}

// Every file of the run at `threads` partitions equals the one-model run's, byte for byte
// (the runs are in root/t<threads>).
void ExpectSameAsOneModel(const ExperimentConfig& config, std::vector<int> threads,
                          std::vector<std::string> files,
                          const std::string& root = TempDir("part")) {
  const RunResult one = RunInto(config, 1, root + "/t1");
  ASSERT_TRUE(one.complete) << one.error;
  files.push_back("timeseries.csv");
  for (int t : threads) {
    const std::string dir = root + "/t" + std::to_string(t);
    const RunResult r = RunInto(config, t, dir);
    ASSERT_TRUE(r.complete) << r.error;
    for (const std::string& f : files) {
      const std::string a = ReadFile(root + "/t1/" + f), b = ReadFile(dir + "/" + f);
      EXPECT_FALSE(a.empty()) << f;
      EXPECT_TRUE(a == b) << f << " differs with " << t << " partitions";
    }
    EXPECT_EQ(SummaryWithoutTiming(root + "/t1").dump(), SummaryWithoutTiming(dir).dump());
    const auto timing = nlohmann::json::parse(ReadFile(dir + "/summary.json"))["timing"];
    EXPECT_EQ(timing["threads"], t);
  }
}

const std::vector<std::string> kRealism = {"sensors={preset=\"typical\"}",
                                           "wind={mean=[3.0, 1.0, 0.0], turbulence=\"moderate\"}"};

std::vector<std::string> With(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// Exp 2 as published (actuator rotor model, contacts on), wind and sensors on, with snapshots:
// rendering reads the whole-swarm state gathered from the partitions.
TEST(PartitionTest, Exp2WithWindAndSensorsGivesTheOneModelBytes) {
  ExperimentConfig c =
      LoadExperiment(std::string(MJF_SOURCE_DIR) + "/experiments/exp2.toml",
                     With({"run.duration=1.0", "run.metric_window=[0.5, 1.0]",
                           "render={snapshots=[0.0, 1.0], width=160, height=120, distance=45.0}"},
                          kRealism));
  ExpectSameAsOneModel(c, {2, 3}, {"snapshots/t000.00.png", "snapshots/t001.00.png"});
}

// A 200-follower ring with the wrench rotor model, no collision detection, wind and sensors.
TEST(PartitionTest, Ring200WithWindAndSensorsGivesTheOneModelBytes) {
  ExperimentConfig c = LoadExperiment(
      std::string(MJF_SOURCE_DIR) + "/experiments/exp2.toml",
      With({"run.duration=0.2", "run.metric_window=[0.1, 0.2]", "render.snapshots=[]",
            "vehicles={model=\"quadrotor\", followers=200, altitude=5.0, "
            "rotor_model=\"wrench\", contacts=false}",
            "topology={leader_links=[1], generate=\"ring\"}",
            "formation.shape={type=\"circle\", radius=48.0, omega=0.065}"},
           kRealism));
  ExpectSameAsOneModel(c, {2}, {});
}

// 1000 followers (the size docs/PERFORMANCE.md times), every step recorded, and a near-miss
// margin wider than the ring's spacing so that every neighbouring pair is an event: the rows
// formatted on the partitions' threads and the pair scans of their sorted places join into the
// one-model bytes and event order. A few steps only: composing the scenes is most of its time.
TEST(PartitionTest, Ring1000WithEveryPairANearMissGivesTheOneModelBytes) {
  ExperimentConfig c = LoadExperiment(
      std::string(MJF_SOURCE_DIR) + "/experiments/exp2.toml",
      {"run.duration=0.02", "run.metric_window=[0.01, 0.02]", "run.record_rate=1000.0",
       "render.snapshots=[]",
       "vehicles={model=\"quadrotor\", followers=1000, altitude=5.0, rotor_model=\"wrench\", "
       "contacts=false}",
       "topology={leader_links=[1], generate=\"ring\"}",
       "formation.shape={type=\"circle\", radius=239.0, omega=0.013}", "safety.near_miss_m=2.0"});
  const std::string root = TempDir("part");
  ExpectSameAsOneModel(c, {2}, {}, root);
  const nlohmann::json events =
      nlohmann::json::parse(ReadFile(root + "/t1/summary.json"))["events"];
  EXPECT_GE(events["by_kind"]["near_miss"].get<int>(), 1000) << events.dump();
}

// Per-agent execution over a lossy network: the channel and the agents stay on the caller's
// thread; the bytes are the one-model run's.
TEST(PartitionTest, PerAgentOverALossyNetworkGivesTheOneModelBytes) {
  ExperimentConfig c = LoadExperiment(
      std::string(MJF_SOURCE_DIR) + "/experiments/exp2.toml",
      {"run.duration=0.5", "run.metric_window=[0.25, 0.5]", "render.snapshots=[]",
       "execution={mode=\"per_agent\", coupling=\"jacobi\", jacobi_rounds=3}",
       "network={latency=0.002, jitter=0.001, loss=0.05, loss_model=\"gilbert_elliott\"}"});
  ExpectSameAsOneModel(c, {2}, {});
}

// A MuJoCo warning inside the worker thread's partition (the follower's absurd force command
// on the point mass; the leader, in partition 0, is fine) ends the run like the one-model run:
// same message, same rows kept, summary.json complete = false.
TEST(PartitionTest, WarningInAWorkerPartitionEndsTheRunByTheFailureContract) {
  std::string text = HoverExperiment(1, 2.0);
  text.replace(text.find("model = \"quadrotor\""), 19, "model = \"pointmass\"");
  text.replace(text.find("plugin = \"pd_cascade\""), 21, "plugin = \"pointmass_direct\"");
  text.replace(text.find("[formation]\nplugin = \"hover\""), 28,
               "[formation]\nplugin = \"test_huge\"\nafter = 0.5");
  const ExperimentConfig c = Parse(text);
  const std::string root = TempDir("partfail");
  const RunResult one = RunInto(c, 1, root + "/t1");
  const RunResult two = RunInto(c, 2, root + "/t2");
  EXPECT_FALSE(two.complete);
  EXPECT_THAT(two.error, HasSubstr("t = 0.501 s: MuJoCo warning: Nan, Inf or huge value in CTRL"));
  EXPECT_EQ(two.error, one.error);
  EXPECT_EQ(two.sim_time_s, one.sim_time_s);
  EXPECT_FALSE(SummaryWithoutTiming(root + "/t2")["complete"].get<bool>());
  EXPECT_EQ(ReadFile(root + "/t1/timeseries.csv"), ReadFile(root + "/t2/timeseries.csv"));
}

// An engine error (mju_error) raised on a worker thread, inside its partition's mj_step2,
// reaches the caller as the step's MujocoError once every partition has finished; the pool
// shuts down cleanly afterwards.
TEST(PartitionTest, EngineErrorOnAWorkerThreadReachesTheCaller) {
  ExperimentConfig c = Parse(HoverExperiment(3, 1.0));
  c.threads = 2;
  Simulation sim(c);
  ASSERT_EQ(sim.threads(), 2);
  for (int k = 0; k < 10; ++k) {
    sim.ComputeControls();
    sim.Integrate();
  }
  sim.ComputeControls();
  // No stack left: the partition's next mj_stackAlloc (in mj_step2) calls mju_error.
  mjData* d = sim.partitions()->partition_data(1);
  d->pstack = d->narena - d->parena;
  try {
    sim.Integrate();
    FAIL() << "no error";
  } catch (const MujocoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("MuJoCo error: mj_stackAlloc: out of memory, stack overflow"));
  }
  EXPECT_EQ(sim.step_index(), 10);  // the failed step is not counted, as with one model
}

// The failure contract at the run level for an engine error is RunExperiment's (Guarded):
// the same path as a MujocoError from the single model (runner_test.cc).

TEST(PartitionTest, RefusesThreadsBelowOneWithFileAndLine) {
  try {
    Parse(HoverExperiment(2, 1.0, "threads = 0\n"));
    FAIL() << "accepted";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("exp.toml:4: [run] threads: must be in [1, 1024]"));
  }
}

// Vehicles whose geoms collide with each other's cannot be split: refused, naming the key,
// the geoms and the ways out; with contacts = false the same model is accepted.
TEST(PartitionTest, RefusesInterVehicleContacts) {
  std::string vehicle = ReadFile(std::string(MJF_SOURCE_DIR) + "/mjcf/pointmass.xml");
  const std::string from = "contype=\"2\" conaffinity=\"1\"";
  ASSERT_NE(vehicle.find(from), std::string::npos);
  vehicle.replace(vehicle.find(from), from.size(), "contype=\"1\" conaffinity=\"1\"");
  const std::string dir = TempDir("touch");
  const std::string path = WriteFile(dir + "/touching.xml", vehicle);
  std::string text = HoverExperiment(2, 0.1, "threads = 2\n");
  text.replace(text.find("model = \"quadrotor\""), 19, "model = \"" + path + "\"");
  text.replace(text.find("plugin = \"pd_cascade\""), 21, "plugin = \"pointmass_direct\"");
  try {
    Simulation sim(Parse(text));
    FAIL() << "accepted";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("exp.toml:4: [run] threads: = 2 needs vehicles that do not "
                                    "touch each other through MuJoCo, but geom"));
    EXPECT_THAT(e.what(), HasSubstr("[vehicles] contacts = false"));
  }
  text.replace(text.find("[vehicles]\n"), 11, "[vehicles]\ncontacts = false\n");
  EXPECT_EQ(Simulation(Parse(text)).threads(), 2);
}

TEST(PartitionTest, WarnsAboveTheMachinesCores) {
  const int cores = static_cast<int>(std::thread::hardware_concurrency());
  ExperimentConfig c = Parse(HoverExperiment(cores + 1, 0.1));
  c.threads = cores + 1;
  ::testing::internal::CaptureStderr();
  Simulation sim(c);
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_THAT(err, HasSubstr("warning: "));
  EXPECT_THAT(err, HasSubstr("[run] threads: " + std::to_string(cores + 1) +
                             " threads on a machine with " + std::to_string(cores) + " cores"));
  EXPECT_EQ(sim.threads(), cores + 1);
}

}  // namespace
}  // namespace mjf::runner
