// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/record/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mjformation/formation/metrics.hpp"
#include "mjformation/formation/shape.hpp"
#include "mjformation/record/output.hpp"
#include "mjformation/sim/simulation.hpp"

namespace mjf::runner {
namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Band for "reached" when neither the experiment nor the plugin gives one.
constexpr double kDefaultReachingBand = 0.1;
}  // namespace

double MinimumSeparation(const std::vector<double>& xyz,
                         std::vector<std::pair<double, int>>* order) {
  const int n = static_cast<int>(xyz.size() / 3);
  order->clear();
  for (int i = 0; i < n; ++i) order->emplace_back(xyz[3 * i], i);
  std::sort(order->begin(), order->end());
  // The square root is monotone and correctly rounded, so the smallest root is the root of the
  // smallest square: one root per new minimum instead of one per pair, the same bits.
  double best = kInf, best_squared = kInf;
  for (int a = 0; a < n; ++a) {
    const double* p = &xyz[3 * (*order)[a].second];
    for (int b = a + 1; b < n && (*order)[b].first - (*order)[a].first < best; ++b) {
      const double* q = &xyz[3 * (*order)[b].second];
      const double d2 = (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                        (p[2] - q[2]) * (p[2] - q[2]);
      if (d2 < best_squared) {
        best_squared = d2;
        best = std::sqrt(d2);
      }
    }
  }
  return best;
}

OnlineMetrics::OnlineMetrics(const Simulation& sim)
    : window_{sim.config().metric_window[0], sim.config().metric_window[1]},
      min_separation_(kInf),
      timestep_(sim.config().timestep),
      motion_(sim.n_followers(), window_[0], window_[1]),
      transient_(sim.n_followers()) {
  band_ = sim.config().reaching_band;
  band_given_ = band_ > 0;  // a band the experiment names is used as it is, never widened
  if (band_ <= 0) {
    band_ = kDefaultReachingBand;
    const double delta = sim.contracts().law.delta;  // the law's band, eq. (49)
    if (std::isfinite(delta) && delta > 0) band_ = delta;
  }
  std::fill(std::begin(last_violation_time_), std::end(last_violation_time_), -1.0);
  std::fill(std::begin(max_abs_s_since_violation_), std::end(max_abs_s_since_violation_), 0.0);
  const int nf = sim.n_followers();
  follower_pv_.resize(4 * static_cast<size_t>(nf));
  leader_pv_.resize(4);
  shape_now_.resize(6 * static_cast<size_t>(nf));
  sort_buffer_.resize(3 * static_cast<size_t>(sim.n_vehicles()));
  final_errors_.assign(nf, kNaN);
  // StepControls' bounds, [vehicle][actuator] as the controls: the same sums it formed per step.
  const int na = sim.actuators_per_vehicle();
  for (int i = 0; i < sim.n_vehicles(); ++i) {
    for (int k = 0; k < na; ++k) {
      const mjfActuatorInfo& a = sim.binding(i).actuator_info[k];
      saturation_low_.push_back(a.ctrl_min + 1e-9);
      saturation_high_.push_back(a.ctrl_max - 1e-9);
    }
  }
}

double OnlineMetrics::Sample(const Simulation& sim, std::vector<double>* slots, bool accumulate) {
  (*slots)[0] = sim.setpoints()[0].pos[0];
  (*slots)[1] = sim.setpoints()[0].pos[1];
  if (!sim.shape()) {
    HeldSlots(sim, slots);
    if (accumulate) AccumulateSample(sim);
    return kNaN;
  }
  const double sigma_f = FormationSlots(sim, slots);
  if (!accumulate) return sigma_f;
  const double t = sim.time();
  if (!have_initial_) sigma_initial_ = sigma_f;
  have_initial_ = true;
  sigma_final_ = sigma_f;
  for (int i = 0; i < sim.n_followers(); ++i) {
    transient_.Add(i, t, final_errors_[i], sim.setpoints()[i + 1].acc, sim.states()[i + 1].vel);
  }
  if (t >= window_[0] - 1e-9 && t <= window_[1] + 1e-9) {
    sigma_sum_ += sigma_f;
    ++sigma_count_;
    // Tilt = angle between body z and world z: 1 - 2 (x^2 + y^2) is its cosine.
    for (int i = 1; i < sim.n_vehicles(); ++i) {
      const double* q = sim.states()[i].quat;
      const double cos_tilt = std::clamp(1 - 2 * (q[1] * q[1] + q[2] * q[2]), -1.0, 1.0);
      max_follower_tilt_in_window_ = std::max(max_follower_tilt_in_window_, std::acos(cos_tilt));
    }
    SampleFollowerMotion(sim, t);
  }
  AccumulateSample(sim);
  return sigma_f;
}

// Slots = leader + f_i(t) (Definition 1) and sigma_f, eq. (68).
double OnlineMetrics::FormationSlots(const Simulation& sim, std::vector<double>* slots) {
  const int nf = sim.n_followers();
  const auto& states = sim.states();
  const mjfVehicleState& leader = states[0];
  sim.shape()->Evaluate(sim.time(), shape_now_.data());
  leader_pv_ = {leader.pos[0], leader.pos[1], leader.vel[0], leader.vel[1]};
  for (int i = 0; i < nf; ++i) {
    const mjfVehicleState& s = states[i + 1];
    follower_pv_[4 * i + 0] = s.pos[0];
    follower_pv_[4 * i + 1] = s.pos[1];
    follower_pv_[4 * i + 2] = s.vel[0];
    follower_pv_[4 * i + 3] = s.vel[1];
    const double sx = leader.pos[0] + shape_now_[6 * i + 0];
    const double sy = leader.pos[1] + shape_now_[6 * i + 1];
    (*slots)[2 * (i + 1)] = sx;
    (*slots)[2 * (i + 1) + 1] = sy;
    final_errors_[i] = std::hypot(s.pos[0] - sx, s.pos[1] - sy);
  }
  // eq. (68)
  return formation::FormationError(nf, follower_pv_.data(), leader_pv_.data(), shape_now_.data());
}

// Without a formation the slots are the followers' own held setpoints.
void OnlineMetrics::HeldSlots(const Simulation& sim, std::vector<double>* slots) {
  const auto& states = sim.states();
  for (int i = 1; i < sim.n_vehicles(); ++i) {
    (*slots)[2 * i] = sim.setpoints()[i].pos[0];
    (*slots)[2 * i + 1] = sim.setpoints()[i].pos[1];
    final_errors_[i - 1] =
        std::hypot(states[i].pos[0] - (*slots)[2 * i], states[i].pos[1] - (*slots)[2 * i + 1]);
  }
}

// Record ticks: the sliding band (reaching), minimum separation, sample period.
void OnlineMetrics::AccumulateSample(const Simulation& sim) {
  const double t = sim.time();
  // Sliding variables, where the formation plugin reports them.
  double max_abs_s = -1;
  for (int i = 1; i < sim.n_vehicles(); ++i) {
    for (double s : sim.setpoints()[i].sliding) {
      if (std::isfinite(s)) max_abs_s = std::max(max_abs_s, std::abs(s));
    }
  }
  if (max_abs_s >= 0) {
    have_sliding_ = true;
    max_abs_s_ever_ = std::max(max_abs_s_ever_, max_abs_s);
    if (t >= window_[0] - 1e-9 && t <= window_[1] + 1e-9) {
      max_abs_s_in_window_ = std::max(max_abs_s_in_window_, max_abs_s);
    }
    double band = band_;
    for (int k = 0; k < kBands; ++k, band *= 2) {
      if (max_abs_s > band) {
        last_violation_time_[k] = t;
        max_abs_s_since_violation_[k] = 0;
      } else {
        max_abs_s_since_violation_[k] = std::max(max_abs_s_since_violation_[k], max_abs_s);
      }
    }
  }
  for (int i = 0; i < sim.n_vehicles(); ++i) {
    for (int k = 0; k < 3; ++k) sort_buffer_[3 * i + k] = sim.states()[i].pos[k];
  }
  min_separation_ = std::min(min_separation_, MinimumSeparation(sort_buffer_, &order_));
  if (t > last_time_) sample_period_ = t - last_time_;
  last_time_ = t;
}

// Each follower's sums are its own (FollowerMotion::Add touches follower i's entries only): with
// partitioned physics each partition's thread adds its own vehicles, the same operations on
// each follower as on one thread, so the same bits. The rocking spectra, most of the cost, are
// kept for the first kMaxSpectra followers only, so they stay on the first partition's thread.
void OnlineMetrics::SampleFollowerMotion(const Simulation& sim, double t) {
  motion_.Begin(t);
  struct Job {
    const Simulation* sim;
    FollowerMotion* motion;
  } job{&sim, &motion_};
  sim.ForEachVehicleRange(
      [](void* context, int first, int count, char*, size_t) {
        const Job& j = *static_cast<Job*>(context);
        const int na = j.sim->actuators_per_vehicle();
        for (int i = std::max(first, 1); i < first + count; ++i) {
          const double* ctrl = &j.sim->controls()[static_cast<size_t>(i) * na];
          j.motion->Add(i - 1, j.sim->states()[i].quat,
                        CollectiveForce(ctrl, j.sim->binding(i).actuator_info.data(), na));
        }
      },
      &job);
}

void OnlineMetrics::StepControls(const Simulation& sim) {
  // One flat pass over every control of the step (the bounds were formed once, constructor).
  const double* u = sim.controls().data();
  const double* low = saturation_low_.data();
  const double* high = saturation_high_.data();
  const size_t n = saturation_low_.size();
  for (size_t j = 0; j < n; ++j) {
    if (u[j] <= low[j] || u[j] >= high[j]) {
      ++saturated_steps_;
      return;
    }
  }
}

nlohmann::ordered_json OnlineMetrics::Summary(const Simulation& sim) const {
  nlohmann::ordered_json m;
  m["sigma_f_window"] = {window_[0], window_[1]};
  // A run that stopped before the window's end (interrupted, failed, [run] stop_on) averaged
  // over less than the window it names: the last time it sampled is stated beside it. A run
  // that reached the end has sampled there, and its summary has no such key.
  if (have_initial_ && last_time_ < window_[1] - 1e-9) m["sigma_f_sampled_until_s"] = last_time_;
  m["sigma_f_mean"] = JsonNumber(sigma_count_ ? sigma_sum_ / sigma_count_ : kNaN);
  m["sigma_f_samples"] = sigma_count_;
  m["sigma_f_initial"] = JsonNumber(have_initial_ ? sigma_initial_ : kNaN);
  m["sigma_f_final"] = JsonNumber(have_initial_ ? sigma_final_ : kNaN);
  nlohmann::ordered_json errors = nlohmann::ordered_json::array();
  double worst = 0;
  for (double e : final_errors_) {
    errors.push_back(JsonNumber(e));
    worst = std::max(worst, e);
  }
  m["final_slot_error_m"] = errors;
  m["max_final_slot_error_m"] = JsonNumber(final_errors_.empty() ? kNaN : worst);
  m["min_separation_m"] = JsonNumber(min_separation_);
  // Reached (docs/ARCHITECTURE.md, "reaching_time_s"): |s| stays within the band from then to
  // the end. The band is the protocol's (Theorem 2's delta for the discrete protocol) when the
  // run holds it over the metric window; a vehicle with attitude dynamics holds a wider one (Exp
  // 2's quadrotors: |s| up to 1.4 over the window against delta 0.1025, formation within 0.1 m),
  // and then the band is the smallest delta 2^k holding |s| over the window, provided it is at most
  // a tenth of the run's largest |s| (a sliding variable that never came down a decade has reached
  // nothing). A band given in [run] reaching_band is never widened.
  int k = 0;
  double band = band_;
  while (!band_given_ && k + 1 < kBands && max_abs_s_in_window_ > band) {
    ++k;
    band *= 2;
  }
  const bool widened = k > 0;
  m["reaching_band"] = band;
  if (widened) m["reaching_band_widened_from"] = band_;
  if (have_sliding_) {
    const bool reached =
        last_violation_time_[k] < last_time_ &&
        (!widened || (max_abs_s_in_window_ <= band && band <= 0.1 * max_abs_s_ever_));
    const double time = last_violation_time_[k];
    m["reaching_time_s"] = reached ? JsonNumber(time < 0 ? 0.0 : time + sample_period_)
                                   : nlohmann::ordered_json(nullptr);
    m["max_abs_s_after_reaching"] =
        reached ? JsonNumber(max_abs_s_since_violation_[k]) : nlohmann::ordered_json(nullptr);
    m["max_abs_s"] = max_abs_s_ever_;
  } else {
    m["reaching_time_s"] = nullptr;
    m["max_abs_s_after_reaching"] = nullptr;
    m["max_abs_s"] = nullptr;
  }
  m["saturation_time_s"] = static_cast<double>(saturated_steps_) * timestep_;
  // Chattering shows here: a steady formation needs only a few degrees of tilt.
  m["max_follower_tilt_deg_in_window"] = max_follower_tilt_in_window_ * 180.0 / M_PI;
  motion_.AddTo(&m);
  transient_.AddTo(&m);
  (void)sim;
  return m;
}

}  // namespace mjf::runner
