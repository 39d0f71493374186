// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// plugins/estimator/plugin/: the family through dlopen(), as the runner loads it.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "plugin_loader.hpp"

namespace mjf::test {
namespace {

using ::testing::HasSubstr;

const double kStart[3] = {1.0, 2.0, 3.0};

mjfSensorInfo Suite() {
  mjfSensorInfo s{};
  s.has_accel = 1;
  s.accel_in_world = 1;
  s.accel_noise_density = 0.02;
  s.position_sources = MJF_MEASURES_POSITION | MJF_MEASURES_VELOCITY;
  s.max_latency = 0.11;
  return s;
}

TEST(EstimatorPlugins, BothAreEstimatorsOfTheCurrentAbi) {
  Library lib(MJF_ESTIMATOR_PLUGIN);
  for (const char* name : {"passthrough", "kf_ins"}) {
    const mjfPlugin* p = lib.Get(name);
    ASSERT_NE(p, nullptr) << name;
    EXPECT_EQ(p->kind, MJF_KIND_ESTIMATOR);
    EXPECT_EQ(p->abi_version, MJF_ABI_VERSION);
  }
}

TEST(EstimatorPlugins, KfInsRefusesASuiteWithoutAccelerometerOrPosition) {
  Library lib(MJF_ESTIMATOR_PLUGIN);
  const mjfPlugin& p = *lib.Get("kf_ins");
  for (int missing = 0; missing < 2; ++missing) {
    Context c(p, {}, nullptr, 1, kStart);
    mjfSensorInfo s = Suite();
    (missing == 0 ? s.has_accel : reinterpret_cast<int&>(s.position_sources)) = 0;
    c.ctx.sensors = &s;
    EXPECT_EQ(p.create(&c.ctx), nullptr);
    EXPECT_THAT(std::string(c.error), HasSubstr(missing == 0 ? "accelerometer" : "position"));
  }
}

// Standard deviations are squared into the filter's covariance: a negative one (which would
// pass as its absolute value) or one whose square overflows is refused naming the attribute,
// as are noise densities beyond the sensor suite's bounds and a gate that is not > 0.
TEST(EstimatorPlugins, KfInsRefusesNegativeOrUnboundedStandardDeviations) {
  Library lib(MJF_ESTIMATOR_PLUGIN);
  const mjfPlugin& p = *lib.Get("kf_ins");
  const std::pair<const char*, const char*> bad[] = {{"initial_position_std", "-1.0"},
                                                     {"initial_velocity_std", "-1.0"},
                                                     {"initial_bias_std", "-0.2"},
                                                     {"initial_position_std", "1e200"},
                                                     {"initial_velocity_std", "1e300"},
                                                     {"accel_noise", "1e300"},
                                                     {"accel_bias_walk", "-1"},
                                                     {"position_wander", "1e200"},
                                                     {"gate_sigma", "-5.0"}};
  for (const auto& [key, value] : bad) {
    Context c(p, {{key, value}}, nullptr, 1, kStart);
    const mjfSensorInfo s = Suite();
    c.ctx.sensors = &s;
    EXPECT_EQ(p.create(&c.ctx), nullptr) << key << " = " << value;
    EXPECT_THAT(std::string(c.error), HasSubstr(std::string("attribute '") + key + "'"))
        << key << " = " << value;
  }
  Context ok(p, {{"initial_position_std", "0"}, {"initial_velocity_std", "1e3"}}, nullptr, 1,
             kStart);
  const mjfSensorInfo s = Suite();
  ok.ctx.sensors = &s;
  void* filter = p.create(&ok.ctx);
  EXPECT_NE(filter, nullptr) << ok.error;
  if (filter) p.destroy(filter);
}

// The filter's declared state keeps the posteriors of the steps a sample can be taken at: with
// the suite's aiding period (10 Hz GNSS, 110 ms late) two of them, not every step's 113; a
// latency past the history it keeps is refused naming the sensor keys.
TEST(EstimatorPlugins, KfInsDeclaresTheHistoryOfTheAidingScheduleOnly) {
  Library lib(MJF_ESTIMATOR_PLUGIN);
  const mjfPlugin& p = *lib.Get("kf_ins");
  size_t sizes[2] = {0, 0};
  for (int scheduled = 0; scheduled < 2; ++scheduled) {
    Context c(p, {}, nullptr, 1, kStart);
    mjfSensorInfo s = Suite();
    s.aiding_period = scheduled ? 0.1 : 0.0;
    c.ctx.sensors = &s;
    void* filter = p.create(&c.ctx);
    ASSERT_NE(filter, nullptr) << c.error;
    sizes[scheduled] = p.state_size(filter);
    p.destroy(filter);
  }
  EXPECT_GT(sizes[0], 30000u);
  EXPECT_LT(sizes[1], 2000u);
  Context c(p, {}, nullptr, 1, kStart);
  mjfSensorInfo s = Suite();
  s.max_latency = 12.0;
  c.ctx.sensors = &s;
  EXPECT_EQ(p.create(&c.ctx), nullptr);
  EXPECT_THAT(std::string(c.error), HasSubstr("(12 s, [sensors] position_latency"));
}

// At rest, the accelerometer reads +g and a late exact position sample keeps it at the start.
TEST(EstimatorPlugins, KfInsHoldsAVehicleAtRestAndPassthroughHandsOnTheHeldSample) {
  Library lib(MJF_ESTIMATOR_PLUGIN);
  const mjfPlugin& kf = *lib.Get("kf_ins");
  const mjfPlugin& pass = *lib.Get("passthrough");
  Context c(kf, {}, nullptr, 1, kStart);
  const mjfSensorInfo s = Suite();
  c.ctx.sensors = &s;
  void* filter = kf.create(&c.ctx);
  ASSERT_NE(filter, nullptr) << c.error;
  Context cp(pass, {}, nullptr, 1, kStart);
  void* held = pass.create(&cp.ctx);
  mjfVehicleState sample{{9, 9, 9}, {0, 0, 0}, {1, 0, 0, 0}, {0, 0, 0}};
  mjfEstimatorInput in{};
  in.imu.has_accel = 1;
  in.imu.accel_in_world = 1;
  in.imu.accel[2] = 9.81;
  in.imu.quat[0] = 1;
  in.held = &sample;
  mjfMeasurement m{};
  m.fields = MJF_MEASURES_POSITION;
  for (int k = 0; k < 3; ++k) m.pos[k] = kStart[k];
  m.pos_std[0] = m.pos_std[1] = m.pos_std[2] = 0.01;
  mjfEstimate out{};
  char error[128] = {0};
  mjfStepContext step{};
  step.timestep = 0.001;
  step.estimator = &in;
  step.estimate = &out;
  step.error = error;
  step.error_size = sizeof(error);
  for (int64_t n = 0; n <= 500; ++n) {
    step.step = n;
    step.time = n * 0.001;
    in.n_measurements = 0;
    if (n >= 110 && n % 100 == 10) {
      m.time_taken = (n - 110) * 0.001;
      in.measurements = &m;
      in.n_measurements = 1;
    }
    ASSERT_EQ(kf.compute(filter, &step), 0) << error;
  }
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(out.state.pos[k], kStart[k], 1e-9);
  EXPECT_EQ(out.fused, 4);
  EXPECT_GT(out.covariance[0], 0.0);
  ASSERT_EQ(pass.compute(held, &step), 0);
  EXPECT_EQ(out.state.pos[0], 9.0);
  EXPECT_TRUE(std::isnan(out.covariance[0]));
  kf.destroy(filter);
  pass.destroy(held);
}

}  // namespace
}  // namespace mjf::test
