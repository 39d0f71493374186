// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// A physics step allocates nothing, on any thread: this binary replaces malloc/calloc/realloc
// (count_allocations.hpp, as formation_no_allocation_test.cc does for the laws) and counts the
// calls made while Simulation::ComputeControls and Integrate run, with one model and with
// partitioned physics (whose worker threads' allocations count too), for both rotor models with
// wind and sensors on.
#include <gtest/gtest.h>

#include <atomic>
#include <cstddef>
#include <string>
#include <vector>

#include "count_allocations.hpp"
#include "mjformation/config/config.hpp"
#include "mjformation/sim/simulation.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

long AllocationsPerSteps(const std::string& rotor_model, int threads) {
  ExperimentConfig c = LoadExperiment(
      std::string(MJF_SOURCE_DIR) + "/experiments/exp2.toml",
      {"run.duration=1.0", "run.metric_window=[0.5, 1.0]", "render.snapshots=[]",
       "vehicles.rotor_model=\"" + rotor_model + "\"", "sensors={preset=\"typical\"}",
       "wind={mean=[3.0, 1.0, 0.0], turbulence=\"moderate\"}"});
  c.threads = threads;
  Simulation sim(c);
  for (int k = 0; k < 20; ++k) {  // warm-up: first-touch paths may allocate once
    sim.ComputeControls();
    sim.Integrate();
  }
  allocations = 0;
  counting = true;
  for (int k = 0; k < 200; ++k) {
    sim.ComputeControls();
    sim.Integrate();
  }
  counting = false;
  return allocations.load();
}

TEST(StepNoAllocationTest, OneModelAndPartitionsAllocateNothingPerStep) {
  for (const char* rotor : {"actuator", "wrench"}) {
    for (int threads : {1, 2}) {
      EXPECT_EQ(AllocationsPerSteps(rotor, threads), 0)
          << rotor << " rotor model, " << threads << " thread(s)";
    }
  }
}

}  // namespace
}  // namespace mjf::runner
