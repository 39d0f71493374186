// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// [sensors] and [wind] in a run: the default bytes, and the stages acting in a flight.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "mjformation/config/config.hpp"
#include "mjformation/run/run.hpp"
#include "mjformation/sim/simulation.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

using mjf::testing::HoverExperiment;
using mjf::testing::Parse;
using mjf::testing::ReadFile;
using mjf::testing::TempDir;
using ::testing::AllOf;
using ::testing::HasSubstr;

// Writing the defaults out explicitly changes nothing in what is recorded.
TEST(RealismRun, IdealAndCalmSectionsKeepTheDefaultBytes) {
  const std::string root = TempDir("realism_default");
  RunOptions options;
  options.render = false;
  options.out_dir = root + "/plain";
  ASSERT_TRUE(RunExperiment(Parse(HoverExperiment(2, 1.0)), options).complete);
  options.out_dir = root + "/explicit";
  ASSERT_TRUE(RunExperiment(Parse(HoverExperiment(2, 1.0) +
                                  "[sensors]\npreset = \"ideal\"\n[wind]\nmean = [0, 0, 0]\n"),
                            options)
                  .complete);
  const std::string a = ReadFile(root + "/plain/timeseries.csv");
  EXPECT_GT(a.size(), 1000u);
  EXPECT_EQ(a, ReadFile(root + "/explicit/timeseries.csv"));
}

// Noise and wind are seeded: the same seed gives the same bytes, another seed other bytes.
TEST(RealismRun, SameSeedSameBytesWithNoiseAndWind) {
  const std::string root = TempDir("realism_seed");
  const std::string text = HoverExperiment(2, 1.0) +
                           "[sensors]\npreset = \"typical\"\n[wind]\nmean = [3.0, 0.0, 0.0]\n"
                           "turbulence = \"moderate\"\naltitude = 5.0\n";
  RunOptions options;
  options.render = false;
  for (const char* name : {"a", "b"}) {
    options.out_dir = root + "/" + name;
    ASSERT_TRUE(RunExperiment(Parse(text), options).complete);
  }
  options.out_dir = root + "/c";
  std::string other = text;
  other.insert(other.find("[vehicles]"), "seed = 2\n");
  ASSERT_TRUE(RunExperiment(Parse(other), options).complete);
  const std::string a = ReadFile(root + "/a/timeseries.csv");
  EXPECT_THAT(a.substr(0, a.find('\n')), HasSubstr("uav2_wind_z"));
  EXPECT_EQ(a, ReadFile(root + "/b/timeseries.csv"));
  EXPECT_NE(a, ReadFile(root + "/c/timeseries.csv"));
}

// The plugins get the measurement; the truth is what is recorded, the measurement beside it.
TEST(RealismRun, ControllersSeeTheMeasurementAndBothAreRecorded) {
  const std::string text = HoverExperiment(2, 1.0) + "[sensors]\npreset = \"typical\"\n";
  Simulation sim(Parse(text));
  double worst = 0;
  for (int64_t k = 0; k < 500; ++k) {
    sim.ComputeControls();
    for (int i = 0; i < sim.n_vehicles(); ++i) {
      worst = std::max(worst, std::abs(sim.measured_states()[i].pos[0] - sim.states()[i].pos[0]));
    }
    sim.Integrate();
  }
  EXPECT_GT(worst, 0.1);  // 0.5 m white noise on position
  const std::string dir = TempDir("realism_rec") + "/run";
  RunOptions options;
  options.render = false;
  options.out_dir = dir;
  ASSERT_TRUE(RunExperiment(Parse(text), options).complete);
  const std::string csv = ReadFile(dir + "/timeseries.csv");
  EXPECT_THAT(csv.substr(0, csv.find('\n')), HasSubstr(",uav2_yaw_meas"));
  EXPECT_THAT(ReadFile(dir + "/summary.json"), HasSubstr("\"preset\": \"typical\""));
}

// A hovering vehicle in a steady wind leans into it until its thrust's horizontal part balances
// the drag model's force at zero ground speed: tan(tilt) = |F_drag(-wind)| / (m g).
TEST(RealismRun, SteadyWindTiltMatchesTheDragModel) {
  Simulation sim(Parse(HoverExperiment(1, 20.0) + "[wind]\nmean = [4.0, 0.0, 0.0]\n"));
  const double still[3] = {0, 0, 0}, wind[3] = {4, 0, 0};
  const double drag = sim.config().wind.drag.Force(still, wind)[0];
  const double expected = std::atan(drag / (1.5 * 9.81));
  double sum = 0, speed = 0;
  int samples = 0;
  for (int64_t k = 0; k < sim.total_steps(); ++k) {
    sim.ComputeControls();
    if (sim.time() >= 15.0) {
      sum += EulerZYX(sim.states()[1].quat)[1];  // pitch: leaning into a wind along +x
      speed = std::max(speed, std::hypot(sim.states()[1].vel[0], sim.states()[1].vel[1]));
      ++samples;
    }
    sim.Integrate();
  }
  const double pitch = sum / samples;
  RecordProperty("pitch_deg", std::to_string(pitch * 180 / M_PI));
  EXPECT_GT(drag, 1.0);    // 0.256 * 4 + 0.0317 * 16 = 1.53 N
  EXPECT_LT(speed, 0.05);  // holding station
  EXPECT_NEAR(std::abs(pitch), expected, 0.05 * expected);
}

}  // namespace
}  // namespace mjf::runner
