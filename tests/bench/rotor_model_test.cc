// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The two rotor models fly the same trajectories: rotor_model = "actuator" (MuJoCo's site
// actuators with filter dynamics, dense nu x nv transmission in MuJoCo 2.2.2) and
// rotor_model = "wrench" (the runner applies the same thrusts and yaw torques with its own motor
// lag, as a generalized force: linear in the swarm size). Not a timed test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "mjformation/config/config.hpp"
#include "mjformation/sim/simulation.hpp"

namespace mjf::runner {
namespace {

struct Deviation {
  double max_m = 0;  // largest follower position difference (3-D), m
  double at_s = 0;   // when it occurred
  double max_leader_m = 0;
};

// Steps the two models side by side, as RunExperiment does, and compares every vehicle's position
// on every step.
Deviation CompareRotorModels(const std::string& experiment, double duration) {
  const std::vector<std::string> extra;
  std::vector<std::string> actuator = extra, wrench = extra;
  actuator.push_back("vehicles.rotor_model=\"actuator\"");
  wrench.push_back("vehicles.rotor_model=\"wrench\"");
  actuator.push_back("run.duration=" + std::to_string(duration));
  wrench.push_back("run.duration=" + std::to_string(duration));
  const std::string file = std::string(MJF_SOURCE_DIR) + "/experiments/" + experiment;
  Simulation a(LoadExperiment(file, actuator));
  Simulation w(LoadExperiment(file, wrench));
  EXPECT_GT(a.model()->nu, 0);
  EXPECT_EQ(w.model()->nu, 0);
  Deviation dev;
  for (int64_t step = 0; step <= a.total_steps(); ++step) {
    a.ComputeControls();
    w.ComputeControls();
    for (int i = 0; i < a.n_vehicles(); ++i) {
      double d2 = 0;
      for (int k = 0; k < 3; ++k) {
        const double d = a.states()[i].pos[k] - w.states()[i].pos[k];
        d2 += d * d;
      }
      const double d = std::sqrt(d2);
      if (i == 0) {
        dev.max_leader_m = std::max(dev.max_leader_m, d);
      } else if (d > dev.max_m) {
        dev.max_m = d;
        dev.at_s = a.time();
      }
    }
    if (step < a.total_steps()) {
      a.Integrate();
      w.Integrate();
    }
  }
  std::printf("max follower deviation %.3g m at t = %.3f s; leader %.3g m\n", dev.max_m, dev.at_s,
              dev.max_leader_m);
  return dev;
}

// Measured (Release, MuJoCo 2.2.2): the two paths agree to 1e-13 m over the 40 s, round-off
// only (same forces, summed in another order). The bound leaves seven orders of magnitude for
// other compilers and libm while staying far below any physical effect (a millimetre).
constexpr double kTolerance = 1e-6;  // m

TEST(RotorModelTest, WrenchPathFliesExp2LikeActuatorPath) {
  // Experiment 2 (discrete SMC, 7 quadrotors) over its full 40 s.
  const Deviation dev = CompareRotorModels("exp2.toml", 40.0);
  EXPECT_LT(dev.max_m, kTolerance);
  EXPECT_LT(dev.max_leader_m, kTolerance);
}

TEST(RotorModelTest, WrenchPathFliesContinuousProtocolLikeActuatorPath) {
  // The continuous protocol (smc_continuous, switching + exponential reaching), 40 s.
  const Deviation dev = CompareRotorModels("exp1_exponential.toml", 40.0);
  EXPECT_LT(dev.max_m, kTolerance);
  EXPECT_LT(dev.max_leader_m, kTolerance);
}

}  // namespace
}  // namespace mjf::runner
