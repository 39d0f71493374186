// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The reaching transient per follower, from the record ticks: the largest distance from its slot
// after a settle time (5 s), the time from which it stays within 1 m of its slot, and the peak
// demanded (setpoint acc x, y) and delivered (finite difference of the true velocity between
// record ticks) horizontal acceleration. O(N) per sample, nothing grows with the run.
#ifndef MJFORMATION_RECORD_TRANSIENT_METRICS_HPP_
#define MJFORMATION_RECORD_TRANSIENT_METRICS_HPP_

#include <nlohmann/json.hpp>
#include <vector>

namespace mjf::runner {

class TransientMetrics {
 public:
  static constexpr double kSettleTime = 5.0;  // s: "farther than ... after t = 5 s"
  static constexpr double kNearSlot = 1.0;    // m: "within 1 m of its slot"

  explicit TransientMetrics(int n_followers);
  // Follower i at time t: its distance from the slot, its demanded horizontal acceleration and
  // its true horizontal velocity. Call for i = 0..n-1 at each record tick, times increasing.
  void Add(int i, double t, double slot_distance, const double* demand_xy, const double* vel_xy);
  // Adds max_slot_distance_after_5s_m, time_within_1m_s (the last record time farther than
  // 1 m, 0 if never; null if still farther at the last tick),
  // peak_demanded_accel, peak_delivered_accel (m/s^2, per follower) to the metrics object.
  void AddTo(nlohmann::ordered_json* metrics) const;
  // Each follower's running values, both ways (checkpoints).
  template <typename Archive>
  void VisitState(Archive& a) {
    a(followers_);
  }

 private:
  struct Follower {
    double max_distance_after = 0.0;
    double last_outside = 0.0;  // last record time farther than 1 m (or the first time)
    bool ever_outside = false;
    double peak_demand = 0.0, peak_delivered = 0.0;
    double last_t = 0.0, last_vel[2] = {0.0, 0.0};
    bool has_last = false;
    bool has_sample = false;
    template <typename Archive>
    void VisitState(Archive& a) {
      a(max_distance_after, last_outside, ever_outside, peak_demand, peak_delivered, last_t);
      a(last_vel, has_last, has_sample);
    }
  };
  std::vector<Follower> followers_;
};

}  // namespace mjf::runner

#endif  // MJFORMATION_RECORD_TRANSIENT_METRICS_HPP_
