// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// runner/control/src/stage_factory.cc: which sensor and force stages an experiment gets, and what
// they do to plain arrays.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "mjformation/config/experiment.hpp"
#include "mjformation/control/errors.hpp"
#include "mjformation/control/stages.hpp"
#include "mjformation/realism/drag.hpp"
#include "point_mass_util.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

using mjf::testing::Parse;
using mjf::testing::PointMassExperiment;

std::vector<mjfVehicleState> Truth() {
  std::vector<mjfVehicleState> truth(3);
  for (int i = 0; i < 3; ++i) {
    truth[i] = mjfVehicleState{
        {1.0 * i, 2.0, 3.0}, {0.5, -0.25 * i, 0.0}, {1, 0, 0, 0}, {0.01, 0.02, 0.03}};
  }
  return truth;
}

bool Same(const mjfVehicleState& a, const mjfVehicleState& b) {
  return std::memcmp(&a, &b, sizeof(a)) == 0;
}

TEST(StageFactoryTest, DefaultsAreIdealSensorsAndNoForces) {
  const ExperimentConfig c = Parse(PointMassExperiment(-2, 0, 2, 0));
  auto sensors = MakeSensorStage(c);
  EXPECT_NE(dynamic_cast<IdealSensors*>(sensors.get()), nullptr);
  const auto truth = Truth();
  std::vector<mjfVehicleState> measured(3);
  sensors->Measure(0, 0.0, truth, &measured);
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(Same(truth[i], measured[i])) << i;  // bit for bit
  EXPECT_TRUE(MakeForceStages(c).empty());
}

TEST(StageFactoryTest, SensorsSectionGivesSeededNoisyMeasurements) {
  const std::string text =
      // 1 s: the typical preset's latencies (110 ms) must fit in the run.
      PointMassExperiment(-2, 0, 2, 0, 1.0, "", "[sensors]\npreset = \"typical\"\n");
  const ExperimentConfig c = Parse(text);
  auto a = MakeSensorStage(c), b = MakeSensorStage(c);
  EXPECT_EQ(dynamic_cast<IdealSensors*>(a.get()), nullptr);
  const auto truth = Truth();
  std::vector<mjfVehicleState> ma(3), mb(3);
  bool differs = false;
  for (int64_t step = 0; step < 20; ++step) {
    a->Measure(step, step * c.timestep, truth, &ma);
    b->Measure(step, step * c.timestep, truth, &mb);
    for (int i = 0; i < 3; ++i) {
      EXPECT_TRUE(Same(ma[i], mb[i])) << "same seed, same measurement: step " << step;
      differs = differs || !Same(ma[i], truth[i]);
    }
  }
  EXPECT_TRUE(differs);
  // Another seed, other noise.
  ExperimentConfig other = c;
  other.seed = 2;
  auto o = MakeSensorStage(other);
  std::vector<mjfVehicleState> mo(3);
  for (int64_t step = 0; step < 20; ++step) o->Measure(step, step * c.timestep, truth, &mo);
  bool seed_matters = false;
  for (int i = 0; i < 3; ++i) seed_matters = seed_matters || !Same(mo[i], ma[i]);
  EXPECT_TRUE(seed_matters);
}

TEST(StageFactoryTest, SteadyWindIsOneStageAddingTheDragForce) {
  const ExperimentConfig c =
      Parse(PointMassExperiment(-2, 0, 2, 0, 0.02, "", "[wind]\nmean = [3.0, -1.0, 0.0]\n"));
  auto stages = MakeForceStages(c);
  ASSERT_EQ(stages.size(), 1u);
  auto* wind = dynamic_cast<WindStage*>(stages[0].get());
  ASSERT_NE(wind, nullptr);
  EXPECT_TRUE(wind->wind().empty());  // nothing before the first step
  const auto truth = Truth();
  std::vector<double> force(9, 1.0);  // stages add to what is there
  wind->AddForces(0, 0.0, truth, &force);
  ASSERT_EQ(wind->wind().size(), 3u);
  const double mean[3] = {3.0, -1.0, 0.0};
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(wind->wind()[i], (std::array<double, 3>{3.0, -1.0, 0.0}));
    const auto f = c.wind.drag.Force(truth[i].vel, mean);
    for (int k = 0; k < 3; ++k) EXPECT_DOUBLE_EQ(force[3 * i + k], 1.0 + f[k]) << i << k;
  }
  // Air blowing +x past a vehicle moving slower in x pushes it +x.
  EXPECT_GT(force[0], 1.0);
}

// The sensor stage's state as a fixed number of doubles (the control tick's state, the native
// MuJoCo plugin's plugin_state): loaded into another stage of the same configuration, it
// measures the same bits from then on; every stored number is finite (engines as 32-bit words).
TEST(StageFactoryTest, SensorStateRoundTripsThroughFixedDoubles) {
  const ExperimentConfig c = Parse(PointMassExperiment(
      -2, 0, 2, 0, 1.0, "", "[sensors]\npreset = \"consumer_gnss\"\nposition_rate = 50.0\n"));
  auto a = MakeSensorStage(c), b = MakeSensorStage(c);
  FixedStateArchive sizing = FixedStateArchive::Sizing();
  a->VisitState(sizing);
  const size_t n = sizing.size();
  auto truth = Truth();
  std::vector<mjfVehicleState> ma(3), mb(3);
  for (int64_t step = 0; step < 137; ++step) {
    truth[1].pos[0] += 0.01;
    a->Measure(step, step * c.timestep, truth, &ma);
  }
  std::vector<double> state(n + 1, 7.0);
  FixedStateArchive saving = FixedStateArchive::Saving(state.data());
  a->VisitState(saving);
  EXPECT_EQ(saving.size(), n);  // the length is the configuration's, whatever the steps
  EXPECT_EQ(state[n], 7.0);     // nothing written past it
  for (size_t k = 0; k < n; ++k) ASSERT_TRUE(std::isfinite(state[k])) << k;
  FixedStateArchive loading = FixedStateArchive::Loading(state.data());
  b->VisitState(loading);
  EXPECT_EQ(loading.size(), n);
  for (int64_t step = 137; step < 400; ++step) {
    truth[1].pos[0] += 0.01;
    a->Measure(step, step * c.timestep, truth, &ma);
    b->Measure(step, step * c.timestep, truth, &mb);
    for (int i = 0; i < 3; ++i) ASSERT_TRUE(Same(ma[i], mb[i])) << "step " << step << " " << i;
  }
  // A state not written by this configuration (a fraction, a NaN where an integer is stored)
  // is refused, never converted (that would be undefined).
  for (const double foreign : {0.5, std::nan(""), -1.0}) {
    std::fill(state.begin(), state.end(), foreign);
    FixedStateArchive garbage = FixedStateArchive::Loading(state.data());
    EXPECT_THROW(b->VisitState(garbage), StateArchiveError) << foreign;
  }
}

// A latency buffer past what the native MuJoCo plugin holds is named with its key and steps.
TEST(StageFactoryTest, NativeSensorRefusalNamesTheKeyAndTheSteps) {
  const ExperimentConfig fits =
      Parse(PointMassExperiment(-2, 0, 2, 0, 2.0, "", "[sensors]\npreset = \"consumer_gnss\"\n"));
  EXPECT_EQ(NativeSensorRefusal(fits), "");
  const ExperimentConfig past = Parse(PointMassExperiment(
      -2, 0, 2, 0, 2.0, "", "[sensors]\npreset = \"consumer_gnss\"\nvelocity_latency = 1.2\n"));
  const std::string why = NativeSensorRefusal(past);
  EXPECT_NE(why.find("[sensors] velocity_latency = 1.2 s is 1200 physics steps"), std::string::npos)
      << why;
  EXPECT_NE(why.find("at most 1000"), std::string::npos) << why;
  EXPECT_THROW(MakeSensorStage(past)->RequireNativeState(), SimulationError);
  EXPECT_NO_THROW(MakeSensorStage(fits)->RequireNativeState());
}

}  // namespace
}  // namespace mjf::runner
