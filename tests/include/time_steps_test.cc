// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The one seconds-to-steps rule: what counts as a whole number of steps, and how the three
// roundings treat a count that is whole only up to the division's round-off.
#include "mjformation/time_steps.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace mjf {
namespace {

TEST(TimeStepsTest, WholeStepsCountsAWholeNumberOfSteps) {
  EXPECT_EQ(WholeSteps(0.02, 0.001), 20);  // 20.000000000000004 after the division
  EXPECT_EQ(WholeSteps(0.0, 0.001), 0);
  EXPECT_EQ(WholeSteps(1.0 / 50.0, 0.0005), 40);
  EXPECT_EQ(WholeSteps(0.1, 0.01), 10);
}

TEST(TimeStepsTest, WholeStepsRefusesWhatIsNotWhole) {
  EXPECT_EQ(WholeSteps(0.0005, 0.001), -1);  // half a step
  EXPECT_EQ(WholeSteps(0.0215, 0.001), -1);
  EXPECT_EQ(WholeSteps(1.0 / 333.3333, 0.001), -1);  // 3.0000003 steps: beyond the tolerance
  EXPECT_EQ(WholeSteps(0.01, 0.0), -1);
  EXPECT_EQ(WholeSteps(0.01, -0.001), -1);
  EXPECT_EQ(WholeSteps(std::numeric_limits<double>::infinity(), 0.001), -1);
  EXPECT_EQ(WholeSteps(std::numeric_limits<double>::quiet_NaN(), 0.001), -1);
}

TEST(TimeStepsTest, WholeStepsToleranceIsRelativeToTheCount) {
  const double timestep = 0.001;
  const double within = 0.5 * kWholeStepTolerance;
  const double beyond = 2.0 * kWholeStepTolerance;
  EXPECT_EQ(WholeSteps(1000.0 * (1.0 + within) * timestep, timestep), 1000);
  EXPECT_EQ(WholeSteps(1000.0 * (1.0 + beyond) * timestep, timestep), -1);
  EXPECT_EQ(WholeSteps(within * timestep, timestep), 0);  // below one step: absolute
  EXPECT_EQ(WholeSteps(beyond * timestep, timestep), -1);
}

TEST(TimeStepsTest, StepsAtOrAfterRoundsUpButNotAWholeCount) {
  EXPECT_EQ(StepsAtOrAfter(0.02, 0.001), 20);  // not 21 for the round-off
  EXPECT_EQ(StepsAtOrAfter(0.0201, 0.001), 21);
  EXPECT_EQ(StepsAtOrAfter(0.0005, 0.001), 1);
  EXPECT_EQ(StepsAtOrAfter(0.0, 0.001), 0);
}

TEST(TimeStepsTest, StepsAtOrBeforeRoundsDownButNotAWholeCount) {
  EXPECT_EQ(StepsAtOrBefore(0.3, 0.1), 3);  // 2.9999999999999996: not 2 for the round-off
  EXPECT_EQ(StepsAtOrBefore(0.0199, 0.001), 19);
  EXPECT_EQ(StepsAtOrBefore(0.0005, 0.001), 0);
  EXPECT_EQ(StepsAtOrBefore(0.0, 0.001), 0);
  EXPECT_EQ(StepsAtOrBefore(-0.0015, 0.001), -2);  // a clock running behind the start
}

TEST(TimeStepsTest, NearestStepRoundsAndMayBeZero) {
  EXPECT_EQ(NearestStep(0.0, 0.001), 0);  // a snapshot at t = 0 is step 0 (NearestSteps: 1)
  EXPECT_EQ(NearestStep(40.0, 0.001), 40000);
  EXPECT_EQ(NearestStep(0.0014, 0.001), 1);
  EXPECT_EQ(NearestStep(0.0016, 0.001), 2);
}

TEST(TimeStepsTest, NearestStepsRoundsAndNeverGivesZero) {
  EXPECT_EQ(NearestSteps(0.01, 0.001), 10);  // 100 Hz at 1 kHz
  EXPECT_EQ(NearestSteps(0.1, 0.001), 100);  // rounded, not truncated
  EXPECT_EQ(NearestSteps(1.0 / 30, 0.001), 33);
  EXPECT_EQ(NearestSteps(0.0001, 0.001), 1);  // faster than the physics: every step
  EXPECT_EQ(NearestSteps(0.375, 0.25), 2);    // exactly 1.5: rounds away from zero
  EXPECT_EQ(NearestSteps(0.25, 0.375), 1);    // 0.67
}

TEST(TimeStepsTest, NearestStepsOfAnAstronomicalPeriodIsNeverAgainNotEveryStep) {
  // 1 / 1e-20 Hz at 1 kHz is 1e23 steps: past int64_t, where llround overflowed to a count the
  // clamp made 1, so timeseries.csv recorded every step.
  constexpr int64_t kNever = std::numeric_limits<int64_t>::max();
  EXPECT_EQ(NearestSteps(1.0 / 1e-20, 0.001), kNever);
  EXPECT_EQ(NearestSteps(1.0 / 1e-17, 0.001), kNever);
  EXPECT_EQ(NearestSteps(std::numeric_limits<double>::infinity(), 0.001), kNever);
  EXPECT_EQ(NearestSteps(1e15, 0.001), 1000000000000000000);  // 1e18: still a count
}

}  // namespace
}  // namespace mjf
