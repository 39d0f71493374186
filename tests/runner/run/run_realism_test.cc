// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// [sensors] and [wind] in a run: the default bytes, and the stages acting in a flight.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

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

// An estimator other than passthrough adds the estimate and its 1-sigma beside the
// _meas columns and summary.json "estimation"; passthrough with the same suite adds neither.
TEST(RealismRun, AnEstimatorRecordsItsEstimateAndItsAccuracy) {
  const std::string suite = "[sensors]\npreset = \"consumer_gnss\"\n";
  const std::string root = TempDir("realism_est");
  RunOptions options;
  options.render = false;
  options.out_dir = root + "/kf";
  ASSERT_TRUE(
      RunExperiment(Parse(HoverExperiment(2, 1.0) + suite + "[estimator]\nplugin = \"kf_ins\"\n"),
                    options)
          .complete);
  const std::string csv = ReadFile(root + "/kf/timeseries.csv");
  const std::string header = csv.substr(0, csv.find('\n'));
  EXPECT_THAT(header, HasSubstr(",uav2_yaw_meas,uav0_px_est,uav0_py_est,uav0_pz_est,uav0_vx_est,"
                                "uav0_vy_est,uav0_vz_est,uav0_px_std,uav0_py_std,uav0_pz_std,"
                                "uav0_vx_std,uav0_vy_std,uav0_vz_std,uav0_nees,uav1_px_est"));
  EXPECT_EQ(header.substr(header.rfind(',')), ",uav2_nees");
  // Every row has as many cells as the header, and the standard deviations are filled in.
  const std::string row = csv.substr(csv.rfind('\n', csv.size() - 2) + 1);
  EXPECT_EQ(std::count(row.begin(), row.end(), ','), std::count(header.begin(), header.end(), ','));
  // (sigma_f is empty: this hover has no formation shape)
  const size_t first_est =
      std::count(header.begin(), header.begin() + header.find(",uav0_px_est"), ',');
  size_t cell = 0, empty_est = 0;
  for (size_t at = 0, next; at < row.size(); at = next + 1, ++cell) {
    next = std::min(row.find_first_of(",\n", at), row.size());
    if (cell > first_est && next == at) ++empty_est;
  }
  EXPECT_EQ(empty_est, 0u);
  const auto summary = nlohmann::json::parse(ReadFile(root + "/kf/summary.json"));
  ASSERT_TRUE(summary.contains("estimation"));
  const auto& e = summary["estimation"];
  EXPECT_EQ(e["plugin"], "kf_ins");
  EXPECT_EQ(e["state_dim"], 6);
  ASSERT_EQ(e["vehicles"].size(), 3u);
  for (const auto& v : e["vehicles"]) {
    EXPECT_GT(v["samples"].get<int>(), 10);
    EXPECT_GT(v["position_rms_m"].get<double>(), 0.0);
    EXPECT_LT(v["position_rms_m"].get<double>(), 10.0);  // the suite's 2.12 m wander per axis
    EXPECT_GT(v["nees_mean"].get<double>(), 0.0);
    EXPECT_GT(v["fused"].get<double>(), 5.0);  // 10 Hz GNSS for 1 s
    EXPECT_GE(v["gated"].get<double>(), 0.0);
    EXPECT_GE(v["too_old"].get<double>(), 0.0);
    EXPECT_LT(v["nees_band_95"][0].get<double>(), 6.0);
    EXPECT_GT(v["nees_band_95"][1].get<double>(), 6.0);
  }
  // The followers' figures are also metrics (so a sweep's tables carry them).
  EXPECT_EQ(summary["metrics"]["estimation_nees_mean"], e["followers"]["nees_mean"]);
  EXPECT_EQ(summary["metrics"]["estimation_position_rms_m"], e["followers"]["position_rms_m"]);
  options.out_dir = root + "/passthrough";
  ASSERT_TRUE(RunExperiment(Parse(HoverExperiment(2, 1.0) + suite), options).complete);
  const std::string plain = ReadFile(root + "/passthrough/timeseries.csv");
  EXPECT_EQ(plain.substr(0, plain.find('\n')).find("_est"), std::string::npos);
  const auto plain_summary = nlohmann::json::parse(ReadFile(root + "/passthrough/summary.json"));
  EXPECT_FALSE(plain_summary.contains("estimation"));
  EXPECT_FALSE(plain_summary["metrics"].contains("estimation_nees_mean"));
}

// The closed-loop goal, flown as experiments/exp2.toml (40 s, metric window [25, 40] s) on
// both vehicles: through kf_ins, position and velocity 110 ms late at 10 Hz and nothing else
// keep the ideal sensors' sigma_f within 10 %; the consumer-GNSS suite completes without a
// safety event. The references are flown here, not quoted.
double Exp2SigmaF(const std::vector<std::string>& sets, const std::string& dir,
                  nlohmann::json* summary = nullptr) {
  RunOptions options;
  options.render = false;
  options.out_dir = dir;
  const RunResult r = RunExperiment(
      LoadExperiment(std::string(MJF_SOURCE_DIR) + "/experiments/exp2.toml", sets), options);
  EXPECT_TRUE(r.complete) << dir << ": " << r.error;
  if (summary) *summary = r.summary;
  return r.summary["metrics"]["sigma_f_mean"].get<double>();
}

TEST(RealismRun, KfInsHoldsTheIdealSigmaFUnderLatencyAndConsumerGnssOnBothVehicles) {
  const std::string root = TempDir("realism_closed_loop");
  const std::vector<std::string> pointmass = {"vehicles.model=\"pointmass\"",
                                              "attitude={plugin=\"pointmass_direct\"}"};
  const std::string late =
      "sensors={position_latency=0.11, velocity_latency=0.11, position_rate=10.0, "
      "velocity_rate=10.0, accel_noise=0.0}";
  const std::string kf = "estimator={plugin=\"kf_ins\"}";
  for (const bool point_mass : {true, false}) {
    const std::vector<std::string> vehicle = point_mass ? pointmass : std::vector<std::string>{};
    const std::string name = point_mass ? "pointmass" : "quadrotor";
    const double ideal = Exp2SigmaF(vehicle, root + "/" + name + "_ideal");
    std::vector<std::string> sets = vehicle;
    sets.push_back(late);
    sets.push_back(kf);
    const double delayed = Exp2SigmaF(sets, root + "/" + name + "_late");
    std::printf("%s: ideal %.4f, 110 ms late through kf_ins %.4f\n", name.c_str(), ideal, delayed);
    EXPECT_LE(std::abs(delayed - ideal), 0.10 * ideal) << name;
    sets = vehicle;
    sets.push_back("sensors={preset=\"consumer_gnss\"}");
    sets.push_back(kf);
    nlohmann::json summary;
    const double gnss = Exp2SigmaF(sets, root + "/" + name + "_gnss", &summary);
    std::printf("%s: consumer GNSS through kf_ins %.4f\n", name.c_str(), gnss);
    EXPECT_TRUE(std::isfinite(gnss)) << name;
    EXPECT_FALSE(summary.contains("events")) << name << ": " << summary["events"].dump();
  }
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
