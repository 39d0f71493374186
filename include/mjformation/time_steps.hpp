// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The one rule that turns a time in seconds into physics steps. Everything the simulation does
// happens at a step (a message is delivered, a law samples, a sensor reports), so a time the user
// gives must be a whole number of steps or it would be rounded without saying so. Header-only
// and plain C++, so the runner's stages and the plugins share the rule (and its tolerance).
#ifndef MJFORMATION_TIME_STEPS_HPP_
#define MJFORMATION_TIME_STEPS_HPP_

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace mjf {

// How far seconds / timestep may sit from a whole number and still count as that number,
// relative to the count (at least 1): far above the round-off of the division
// (0.02 / 0.001 = 20.000000000000004) and far below any time a user means.
inline constexpr double kWholeStepTolerance = 1e-9;

// seconds / timestep as a whole number of steps, or -1 when it is not one (within the
// tolerance), the timestep is not > 0 or either is not finite. 0 s is 0 steps.
inline int64_t WholeSteps(double seconds, double timestep) {
  if (!(timestep > 0.0) || !std::isfinite(timestep) || !std::isfinite(seconds)) return -1;
  const double steps = seconds / timestep;
  const double rounded = std::round(steps);
  if (!(std::abs(steps - rounded) <= kWholeStepTolerance * std::max(1.0, std::abs(steps)))) {
    return -1;
  }
  return static_cast<int64_t>(rounded);
}

// The first step at or after `seconds` (>= 0): seconds / timestep rounded up, except that a
// count within the tolerance of a whole number is that number (a delay of exactly 20 steps is
// not 21).
inline int64_t StepsAtOrAfter(double seconds, double timestep) {
  const double steps = seconds / timestep;
  return std::max<int64_t>(
      0, static_cast<int64_t>(std::ceil(steps - kWholeStepTolerance * std::max(1.0, steps))));
}

// The last step at or before `seconds`: seconds / timestep rounded down, except that a count
// within the tolerance below a whole number is that number (a clock that reads 0.3 s on a
// 0.1 s grid, 2.9999999999999996 periods, is on period 3, not 2). StepsAtOrAfter's mirror.
inline int64_t StepsAtOrBefore(double seconds, double timestep) {
  const double steps = seconds / timestep;
  return static_cast<int64_t>(
      std::floor(steps + kWholeStepTolerance * std::max(1.0, std::abs(steps))));
}

// The step nearest to `seconds`, for a time that lies on a step give or take round-off (a
// measurement's time stamp, a snapshot time, a run's duration checked whole by WholeSteps).
inline int64_t NearestStep(double seconds, double timestep) {
  return std::llround(seconds / timestep);
}

// The nearest whole number of steps (at least 1) of a period that need not be whole, such as an
// output's frame rate: it is sampled as closely as the physics steps allow. A period of more
// steps than int64_t holds (a rate of 1e-20 Hz) is the largest count, so it is sampled never
// again after step 0, rather than overflowing llround into a count of 1 (every step).
inline int64_t NearestSteps(double seconds, double timestep) {
  const double steps = seconds / timestep;
  constexpr double kBeyond = 9.2e18;  // below INT64_MAX (9.22e18), above any run's length
  if (!(steps < kBeyond)) return std::numeric_limits<int64_t>::max();
  return std::max<int64_t>(1, std::llround(steps));
}

}  // namespace mjf

#endif  // MJFORMATION_TIME_STEPS_HPP_
