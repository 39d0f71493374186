// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// runner/control/src/estimated_sensors.cc: the sensor models, the accelerometer synthesised from
// the truth and the kf_ins plugin (loaded from the build tree as the runner does), on a vehicle
// integrated here the way the simulator integrates it.
#include "mjformation/control/estimated_sensors.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <thread>

#include "error_of.hpp"
#include "mjformation/config/experiment.hpp"
#include "point_mass_util.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

using mjf::testing::Parse;
using mjf::testing::PointMassExperiment;
using ::testing::HasSubstr;

constexpr double kG = 9.81;

std::string ErrorOf(const std::function<void()>& f) {
  return mjf::testing::ErrorOf(f, "(no error)");
}

ExperimentConfig Config(const std::string& sensors) {
  return Parse(PointMassExperiment(
      2, 0, -2, 0, 1.0, "", "[sensors]\n" + sensors + "\n[estimator]\nplugin = \"kf_ins\"\n"));
}

struct Flight {
  std::vector<std::vector<mjfVehicleState>> truth, seen;
  std::vector<mjfEstimate> last;
};

// Truth of vehicle i: semi-implicit Euler (v+ = v + a dt, p+ = p + v+ dt) under a wandering
// acceleration, yawing and rolling at a constant body rate (the attitude stays exact).
mjfVehicleState Advance(const mjfVehicleState& s, int64_t n, double dt, int i) {
  mjfVehicleState out = s;
  const double t = n * dt;
  const double a[3] = {0.6 * std::sin(0.9 * t + i), 0.4 * std::cos(1.1 * t), 0.1 * std::sin(t)};
  for (int k = 0; k < 3; ++k) {
    out.vel[k] += a[k] * dt;
    out.pos[k] += out.vel[k] * dt;
  }
  const double angle = 0.3 * (n + 1) * dt;  // about (0, 0.6, 0.8)
  out.quat[0] = std::cos(angle / 2);
  out.quat[1] = 0.0;
  out.quat[2] = 0.6 * std::sin(angle / 2);
  out.quat[3] = 0.8 * std::sin(angle / 2);
  out.gyro[0] = 0.0;
  out.gyro[1] = 0.18;
  out.gyro[2] = 0.24;
  return out;
}

Flight Fly(const ExperimentConfig& c, int steps) {
  PluginRegistry registry({MJF_BINARY_DIR "/plugins"});
  const LoadedPlugin& kf = registry.Find(c.estimator.plugin, "test");
  const int n = c.followers + 1;
  std::vector<std::array<double, 3>> start(n);
  std::vector<mjfVehicleState> truth(n);
  for (int i = 0; i < n; ++i) {
    truth[i] = mjfVehicleState{{1.0 * i, -1.0, 2.0}, {0, 0, 0}, {1, 0, 0, 0}, {0, 0.18, 0.24}};
    start[i] = {truth[i].pos[0], truth[i].pos[1], truth[i].pos[2]};
  }
  EstimatedSensors stage(c, n, kG, [&](int i, const mjfSensorInfo& suite) {
    mjfCreateContext ctx{};
    ctx.timestep = c.timestep;
    ctx.vehicle = i;
    ctx.n_vehicles = n;
    ctx.initial_pos = start[i].data();
    ctx.sensors = &suite;
    return std::make_unique<PluginInstance>(kf, c.estimator, c.source_path, ctx);
  });
  Flight f;
  std::vector<mjfVehicleState> seen(n);
  for (int64_t step = 0; step <= steps; ++step) {
    if (step > 0) {
      for (int i = 0; i < n; ++i) truth[i] = Advance(truth[i], step - 1, c.timestep, i);
    }
    stage.Measure(step, step * c.timestep, truth, &seen);
    f.truth.push_back(truth);
    f.seen.push_back(seen);
  }
  f.last = stage.estimates();
  return f;
}

TEST(EstimatedSensors, NoiseFreeSensorsWithLatencyGiveTheTruthOnEveryChannel) {
  const ExperimentConfig c = Config(
      "position_latency = 0.11\nvelocity_latency = 0.11\nposition_rate = 10.0\n"
      "velocity_rate = 10.0\naccel_noise = 0.0");
  const Flight f = Fly(c, 3000);
  double worst = 0;
  for (size_t s = 0; s < f.truth.size(); ++s) {
    for (size_t i = 0; i < f.truth[s].size(); ++i) {
      const mjfVehicleState &t = f.truth[s][i], &e = f.seen[s][i];
      for (int k = 0; k < 3; ++k) {
        worst = std::max({worst, std::abs(t.pos[k] - e.pos[k]), std::abs(t.vel[k] - e.vel[k]),
                          std::abs(t.gyro[k] - e.gyro[k])});
      }
      for (int k = 0; k < 4; ++k) worst = std::max(worst, std::abs(t.quat[k] - e.quat[k]));
    }
  }
  EXPECT_LT(worst, 1e-6);
  EXPECT_GT(f.last[1].fused, 25);  // 3 s of 10 Hz samples, all fused
  EXPECT_EQ(f.last[1].rejected, 0);
}

TEST(EstimatedSensors, SameSeedSameBytesAndTwoThreadsDoNotInterfere) {
  const ExperimentConfig c = Config("preset = \"consumer_gnss\"");
  Flight a, b;
  std::thread ta([&] { a = Fly(c, 600); });
  std::thread tb([&] { b = Fly(c, 600); });
  ta.join();
  tb.join();
  const Flight alone = Fly(c, 600);
  for (size_t i = 0; i < alone.last.size(); ++i) {
    EXPECT_EQ(std::memcmp(&a.last[i], &alone.last[i], sizeof(mjfEstimate)), 0);
    EXPECT_EQ(std::memcmp(&b.last[i], &alone.last[i], sizeof(mjfEstimate)), 0);
  }
  EXPECT_NE(alone.last[1].state.pos[0], alone.truth.back()[1].pos[0]);  // the noise is there
}

// The estimator is told the steps at which aiding samples are taken: each channel's period from
// t = 0, so both channels' at the greatest common divisor (10 Hz and 4 Hz: every 50 ms); every
// step when either samples every step.
TEST(EstimatedSensors, TheSuiteSaysWhenAidingSamplesAreTaken) {
  realism::SensorParams p = realism::SensorParams::ConsumerGnss();
  EXPECT_DOUBLE_EQ(SuiteInfo(p, 0.001, kG).aiding_period, 0.1);
  p[realism::Channel::kVelocity].rate_hz = 4.0;
  EXPECT_DOUBLE_EQ(SuiteInfo(p, 0.001, kG).aiding_period, 0.05);
  p[realism::Channel::kPosition].rate_hz = 0.0;
  EXPECT_DOUBLE_EQ(SuiteInfo(p, 0.001, kG).aiding_period, 0.001);
}

TEST(EstimatedSensors, KfInsWithoutAnAccelerometerIsRefusedWithTheSection) {
  const ExperimentConfig c = Config("position_std = 0.1");
  EXPECT_THAT(ErrorOf([&] { Fly(c, 1); }),
              ::testing::AllOf(HasSubstr("exp.toml:"), HasSubstr("[estimator]"),
                               HasSubstr("accelerometer")));
}

// An estimator whose estimate of vehicle 1 turns NaN at step 3 (the others hand on the held
// samples): what a filter fed 1e300 m noise did before the sensor keys were bounded.
int g_nan_instance = 0, g_other_instance = 0;
void* CreateNanEstimator(const mjfCreateContext* ctx) {
  return ctx->vehicle == 1 ? &g_nan_instance : &g_other_instance;
}
int ComputeNanEstimate(void* instance, const mjfStepContext* ctx) {
  ctx->estimate->state = *ctx->estimator->held;
  if (instance == &g_nan_instance && ctx->step >= 3) ctx->estimate->state.vel[2] = std::nan("");
  return 0;
}
const mjfPlugin kNanEstimator = {MJF_ABI_VERSION,
                                 "nan_estimate_test",
                                 MJF_KIND_ESTIMATOR,
                                 "test",
                                 0,
                                 nullptr,
                                 0,
                                 nullptr,
                                 &CreateNanEstimator,
                                 &ComputeNanEstimate,
                                 nullptr,
                                 nullptr,
                                 nullptr,
                                 nullptr,
                                 nullptr,
                                 nullptr};

// A non-finite estimate stops the run where it appears, naming the estimator, the vehicle and
// the part, instead of reaching the controllers (the stop was reported later as a non-finite
// "vehicle states and setpoints", or not at all).
TEST(EstimatedSensors, ANonFiniteEstimateStopsNamingTheEstimatorAndTheVehicle) {
  RegisterInProcessPlugin(&kNanEstimator, "in-process (test)");
  const ExperimentConfig c = Parse(PointMassExperiment(
      2, 0, -2, 0, 1.0, "",
      "[sensors]\npreset = \"typical\"\n[estimator]\nplugin = \"nan_estimate_test\"\n"));
  EXPECT_EQ(ErrorOf([&] { Fly(c, 2); }), "(no error)");
  EXPECT_EQ(ErrorOf([&] { Fly(c, 10); }),
            "t = 0.003 s: estimator plugin 'nan_estimate_test' (vehicle 1) gave a non-finite "
            "velocity estimate");
}

}  // namespace
}  // namespace mjf::runner
