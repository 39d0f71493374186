// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// How much each follower rocks in the metric window: RMS tilt, the dominant frequency
// of its tilt oscillation, and the RMS variation of its collective thrust (control effort).
// Online, memory fixed by the number of followers and frequency bins (not by the run length);
// plain arrays in, no MuJoCo.
#ifndef MJFORMATION_RECORD_FOLLOWER_MOTION_HPP_
#define MJFORMATION_RECORD_FOLLOWER_MOTION_HPP_

#include <mjformation/plugin.h>

#include <complex>
#include <nlohmann/json.hpp>
#include <vector>

namespace mjf::runner {

class FollowerMotion {
 public:
  // Frequency bins of the tilt spectrum, Hz. Below 0.3 Hz is the formation's own motion (circle
  // rates 0.025-0.075 Hz turn the steady tilt vector); above 5 Hz nothing of the closed loops.
  static constexpr double kMinHz = 0.3, kMaxHz = 5.0, kStepHz = 0.02;
  // Spectra are kept for the first kMaxSpectra followers only (7.5 kB each): a 100000-vehicle
  // swarm would otherwise need 750 MB. Beyond them the frequency is null; RMS values are kept.
  static constexpr int kMaxSpectra = 256;

  // window: [t0, t1] s, the metric window; the spectrum is Hann-weighted over it so the slow
  // turning of the steady tilt does not leak into the band.
  FollowerMotion(int n_followers, double t0, double t1);

  // One sample (a record tick inside the window) at time t: call Begin(t), then Add() for every
  // follower 0..n-1. quat: w x y z, body -> world; thrust: N, collective force magnitude.
  void Begin(double t);
  void Add(int follower, const double quat[4], double thrust);

  // Per-follower arrays: "rms_tilt_deg_in_window", "tilt_oscillation_hz_in_window" (null when
  // the tilt never moves), "rms_thrust_variation_n_in_window", added to `metrics`.
  void AddTo(nlohmann::ordered_json* metrics) const;

  // Dominant frequency (Hz) of follower i's tilt vector (the horizontal part of body z), mean
  // removed; NaN with no samples, no motion, no peak inside the band (largest at its lower edge)
  // or i >= kMaxSpectra. Parabolic interpolation between
  // bins. World-frame components: a rocking at f of a tilt whose direction turns at f_c (the
  // formation's rate, <= 0.075 Hz here) shows at f +- f_c.
  double DominantHz(int follower) const;

  // The sums, both ways (checkpoints); phasor_ is one sample's scratch.
  template <typename Archive>
  void VisitState(Archive& a) {
    a(samples_, weight_, weight_sum_, phasor_sum_, spectrum_, tilt_sq_sum_, tilt_x_sum_);
    a(tilt_y_sum_, thrust_mean_, thrust_m2_);
  }

 private:
  int n_, n_spectra_, bins_;
  double t0_, t1_;
  long samples_ = 0;
  double weight_ = 0, weight_sum_ = 0;            // Hann weight of this sample, and the sum
  std::vector<std::complex<double>> phasor_;      // [bins] e^{-i 2 pi f t} of this sample
  std::vector<std::complex<double>> phasor_sum_;  // [bins] sum over samples (mean removal)
  std::vector<std::complex<double>> spectrum_;    // [n][bins][2] sums of x e, y e
  std::vector<double> tilt_sq_sum_;               // [n] rad^2
  std::vector<double> tilt_x_sum_, tilt_y_sum_;   // [n] sums of the tilt vector
  std::vector<double> thrust_mean_, thrust_m2_;   // [n] Welford
};

// |sum_k ctrl_k gear_k[0..2]|: the collective force of a vehicle's actuators, N (rotor thrusts
// along body z; a point mass's world force).
double CollectiveForce(const double* ctrl, const mjfActuatorInfo* info, int n_actuators);

}  // namespace mjf::runner

#endif  // MJFORMATION_RECORD_FOLLOWER_MOTION_HPP_
