// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The followers' clocks ([execution] clock_offset / clock_drift_ppm): follower i's
// clock reads c_i(t) = (1 + d_i) t + o_i, with o_i uniform in [0, clock_offset] and d_i uniform
// in [-clock_drift_ppm, clock_drift_ppm] 1e-6, drawn once from the run's seed. The leader's clock
// is the reference (c_0(t) = t). A follower's instance is handed its own clock's time and the
// physics step its clock reads (floor(c_i / dt)), so it samples when its clock says so, not in
// phase with the others. With synchronised clocks (GNSS time, PTP: [execution] clock_sync) o_i
// and d_i still set when a follower's loop samples, but what its clock reads, for its time stamps,
// its formation reference and its prediction, is the common time. Pure: no MuJoCo.
#ifndef MJFORMATION_CONTROL_AGENT_CLOCK_HPP_
#define MJFORMATION_CONTROL_AGENT_CLOCK_HPP_

#include <cstdint>
#include <vector>

namespace mjf::runner {

class AgentClocks {
 public:
  AgentClocks(int n_followers, double offset_max, double drift_ppm_max, double timestep,
              uint64_t seed, bool synchronised = false);

  // False when every clock is the reference: the host then hands the true time unchanged.
  bool active() const { return active_; }
  double offset(int follower) const { return offset_[follower]; }  // o_i, s
  double drift(int follower) const { return drift_[follower]; }    // d_i (1e-6 = 1 ppm)
  // c_i(t); vehicle 0 (the leader) is the reference. vehicle: 0..N.
  double Local(int vehicle, double time) const;
  // What vehicle's clock reports at true time t (its stamps, its formation time, its
  // prediction): c_i(t), or t itself when the clocks are synchronised.
  double Reading(int vehicle, double time) const {
    return synchronised_ ? time : Local(vehicle, time);
  }
  bool synchronised() const { return synchronised_; }
  // The physics step follower i's clock reads at true time t: floor(c_i(t) / dt).
  int64_t LocalStep(int follower, double time) const;

 private:
  double timestep_;
  bool active_;
  bool synchronised_;
  std::vector<double> offset_, drift_;  // [follower]
};

}  // namespace mjf::runner

#endif  // MJFORMATION_CONTROL_AGENT_CLOCK_HPP_
