// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Run metrics accumulated online in O(1) memory (nothing grows with run length) and O(N) or
// O(N log N) time per sample: sigma_f (eq. 68) and its window mean (Table 1), reaching time and
// the sliding band after it, final slot errors, minimum separation, actuator saturation time.
#ifndef MJFORMATION_RECORD_METRICS_HPP_
#define MJFORMATION_RECORD_METRICS_HPP_

#include <nlohmann/json.hpp>
#include <vector>

#include "mjformation/record/follower_motion.hpp"
#include "mjformation/record/transient_metrics.hpp"

namespace mjf::runner {

class Simulation;

class OnlineMetrics {
 public:
  explicit OnlineMetrics(const Simulation& sim);
  // One sample of the current state: fills slots[2 i + k] (desired x, y of vehicle i) and
  // returns sigma_f (NaN without a formation). Only samples with `accumulate` (the record ticks)
  // enter the statistics, so they match timeseries.csv whatever the render rates.
  double Sample(const Simulation& sim, std::vector<double>* slots, bool accumulate);
  // Every physics step: counts time with any actuator at a limit of its range.
  void StepControls(const Simulation& sim);
  nlohmann::ordered_json Summary(const Simulation& sim) const;
  // The accumulators, both ways (checkpoints: mjformation/config/state_archive.hpp); what the
  // constructor fixes and the scratch of one sample are not state.
  template <typename Archive>
  void VisitState(Archive& a) {
    a(sigma_sum_, sigma_count_, sigma_initial_, sigma_final_, have_initial_, min_separation_);
    a(last_time_, sample_period_, have_sliding_, last_violation_time_, max_abs_s_since_violation_);
    a(max_abs_s_ever_, max_abs_s_in_window_, final_errors_, saturated_steps_);
    a(max_follower_tilt_in_window_, order_, motion_, transient_);
  }

 private:
  void SampleFollowerMotion(const Simulation& sim, double t);  // in the window, record ticks
  double FormationSlots(const Simulation& sim, std::vector<double>* slots);
  void HeldSlots(const Simulation& sim, std::vector<double>* slots);
  void AccumulateSample(const Simulation& sim);

  double window_[2];
  double band_;  // |s| band defining "reached": the plugin's delta, [run] reaching_band or 0.1
  bool band_given_ = false;  // [run] reaching_band
  std::vector<double> follower_pv_, leader_pv_, shape_now_, sort_buffer_;
  std::vector<std::pair<double, int>> order_;
  double sigma_sum_ = 0;
  long sigma_count_ = 0;
  double sigma_initial_ = 0, sigma_final_ = 0;
  bool have_initial_ = false;
  double min_separation_;
  double last_time_ = 0, sample_period_ = 0;
  bool have_sliding_ = false;
  // Reaching is judged on the bands band_ 2^k, k = 0 .. kBands - 1 (Summary picks the smallest
  // that holds |s| over the metric window): per band, the last sample with max |s_i| above it
  // and the largest max |s_i| since then.
  static constexpr int kBands = 48;
  double last_violation_time_[kBands];
  double max_abs_s_since_violation_[kBands];
  double max_abs_s_ever_ = 0;
  double max_abs_s_in_window_ = -1;  // -1: no sliding sample in the window
  std::vector<double> final_errors_;
  // A control at or beyond these (ctrl_min + 1e-9, ctrl_max - 1e-9), [vehicle][actuator], counts
  // as saturated (StepControls).
  std::vector<double> saturation_low_, saturation_high_;
  long saturated_steps_ = 0;
  double max_follower_tilt_in_window_ = 0;  // rad
  double timestep_;
  FollowerMotion motion_;       // RMS tilt, rocking frequency, thrust variation
  TransientMetrics transient_;  // the reaching transient per follower
};

// Smallest distance between any two of the points (x, y, z triples), O(N log N) by a sweep on x.
double MinimumSeparation(const std::vector<double>& xyz,
                         std::vector<std::pair<double, int>>* order);

}  // namespace mjf::runner

#endif  // MJFORMATION_RECORD_METRICS_HPP_
