// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/control/agent_clock.hpp"

#include <cmath>

#include "mjformation/network/link.hpp"
#include "mjformation/time_steps.hpp"

namespace mjf::runner {
namespace {

// Far above any link index: the clocks' stream never coincides with a link's.
constexpr uint64_t kClockStream = 0x636c6f636bULL;  // "clock"

}  // namespace

AgentClocks::AgentClocks(int n_followers, double offset_max, double drift_ppm_max, double timestep,
                         uint64_t seed, bool synchronised)
    : timestep_(timestep),
      active_(offset_max > 0.0 || drift_ppm_max > 0.0),
      synchronised_(synchronised),
      offset_(n_followers, 0.0),
      drift_(n_followers, 0.0) {
  if (!active_) return;
  network::Random random(network::LinkSeed(seed, kClockStream));
  for (int i = 0; i < n_followers; ++i) {
    offset_[i] = offset_max * random.Uniform();
    drift_[i] = drift_ppm_max * 1e-6 * (2.0 * random.Uniform() - 1.0);
  }
}

double AgentClocks::Local(int vehicle, double time) const {
  if (vehicle == 0 || !active_) return time;
  return (1.0 + drift_[vehicle - 1]) * time + offset_[vehicle - 1];
}

int64_t AgentClocks::LocalStep(int follower, double time) const {
  // A clock reading that is a whole step (in intent) stays on that step.
  return StepsAtOrBefore(Local(follower + 1, time), timestep_);
}

}  // namespace mjf::runner
