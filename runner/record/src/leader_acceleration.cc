// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/record/leader_acceleration.hpp"

#include <cmath>
#include <cstdlib>
#include <limits>

#include "mjformation/sim/simulation.hpp"

namespace mjf::runner {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

LeaderAccelerationMonitor::LeaderAccelerationMonitor(const Simulation& sim)
    : dt_(sim.config().timestep),
      current_{kNaN, kNaN},
      min_{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()},
      max_{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()} {
  const auto& contracts = sim.contracts();
  if (contracts.law.HasInputBounds()) {
    u_min_ = contracts.law.u_min;
    u_max_ = contracts.law.u_max;
    have_bounds_ = true;
    bounds_source_ = "formation";
  } else if (contracts.leader.HasBounds()) {
    u_min_ = contracts.leader.a_min;
    u_max_ = contracts.leader.a_max;
    have_bounds_ = true;
    bounds_source_ = "leader";
  }
}

void LeaderAccelerationMonitor::Step(const Simulation& sim) {
  const double* vel = sim.states()[0].vel;
  if (have_previous_) {
    bool outside = false;
    for (int axis = 0; axis < 2; ++axis) {
      const double a = (vel[axis] - previous_vel_[axis]) / dt_;
      current_[axis] = a;
      min_[axis] = std::min(min_[axis], a);
      max_[axis] = std::max(max_[axis], a);
      if (have_bounds_) {
        const double excess = std::max(u_min_ - a, a - u_max_);  // > 0 outside
        max_excess_ = std::max(max_excess_, excess);
        outside |= excess > kTolerance;
      }
    }
    ++samples_;
    if (outside) {
      ++outside_;
      // The acceleration over [t - dt, t]: the violation starts at the step's beginning.
      if (first_violation_time_ < 0) first_violation_time_ = sim.time() - dt_;
    }
  }
  previous_vel_ = {vel[0], vel[1]};
  have_previous_ = true;
}

nlohmann::ordered_json LeaderAccelerationMonitor::Summary() const {
  using json = nlohmann::ordered_json;
  auto number = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  json s;
  s["source"] = "finite difference of the leader's velocity sensor per physics step";
  s["x_min"] = number(min_[0]);
  s["x_max"] = number(max_[0]);
  s["y_min"] = number(min_[1]);
  s["y_max"] = number(max_[1]);
  s["bounds"] = have_bounds_ ? json::array({u_min_, u_max_}) : json(nullptr);
  s["bounds_source"] = have_bounds_ ? json(bounds_source_) : json(nullptr);
  s["tolerance"] = kTolerance;
  s["samples"] = samples_;
  s["fraction_outside"] =
      have_bounds_ && samples_ > 0 ? json(static_cast<double>(outside_) / samples_) : json(nullptr);
  s["first_violation_time_s"] =
      first_violation_time_ >= 0 ? json(first_violation_time_) : json(nullptr);
  // How far outside at worst (m/s^2; <= 0: inside everywhere, by that margin).
  s["max_excess"] = have_bounds_ && samples_ > 0 ? json(max_excess_) : json(nullptr);
  s["assumption1_holds"] = have_bounds_ ? json(outside_ == 0) : json(nullptr);
  return s;
}

}  // namespace mjf::runner
