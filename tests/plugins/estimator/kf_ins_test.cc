// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// plugins/estimator/src/kf_ins.cc: the filter alone, on a vehicle integrated here with the
// simulator's scheme (semi-implicit Euler), so every figure below is derived, not recorded.
#include "mjformation/estimator/kf_ins.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace mjf::estimator {
namespace {

constexpr double kDt = 0.002;
constexpr double kG = 9.81;

// A wandering true acceleration (m/s^2) at step n, world frame.
Vec3 TrueAccel(int64_t n) {
  const double t = n * kDt;
  return Vec3(0.8 * std::sin(0.7 * t), 0.5 * std::cos(1.3 * t), 0.2 * std::sin(2.1 * t));
}

struct Truth {
  Vec3 p = Vec3(1.0, -2.0, 3.0), v = Vec3::Zero();
  // The step the simulator takes: v+ = v + a dt, p+ = p + v+ dt.
  void Step(const Vec3& a) {
    v += a * kDt;
    p += v * kDt;
  }
};

// The noise the sensors add (white accelerometer noise, GNSS-like p and v jitter).
struct Noise {
  double accel_density = 0.0, pos_std = 0.0, vel_std = 0.0;
};

struct Scenario {
  double rate_hz = 10.0;
  double latency = 0.11;
  Noise noise;
  double duration = 10.0;
};

KfInsConfig FilterFor(const Scenario& s) {
  KfInsConfig c;
  c.timestep = kDt;
  c.accel_noise_density = s.noise.accel_density;
  c.history = s.latency + 2 * kDt;
  c.initial_position = Truth{}.p;
  c.gravity = kG;
  return c;
}

struct Flight {
  double max_error = 0.0;    // over the whole run, p and v
  double nees_at_end = 0.0;  // (p, v) error' P^-1 error at the end
};

// Flies the scenario: each step the accelerometer of the step just ended propagates, and the
// samples taken `latency` ago (every 1/rate s) are fused at their own time.
Flight Fly(const Scenario& s, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  Truth truth;
  KfIns filter(FilterFor(s));
  const int64_t period = std::llround(1.0 / (s.rate_hz * kDt));
  const int64_t lag = std::llround(s.latency / kDt);
  std::vector<AidingSample> taken;  // by the step they were taken
  Flight run;
  const int64_t steps = std::llround(s.duration / kDt);
  for (int64_t n = 0; n <= steps; ++n) {
    if (n > 0) {
      const Vec3 a = TrueAccel(n - 1);
      truth.Step(a);
      Vec3 f = a - Vec3(0, 0, -kG);
      for (int k = 0; k < 3; ++k) f[k] += s.noise.accel_density / std::sqrt(kDt) * normal(rng);
      filter.Propagate(n, f);
    }
    if (n % period == 0) {
      AidingSample m;
      m.time_taken = n * kDt;
      m.has_position = m.has_velocity = true;
      m.position_std = Vec3::Constant(s.noise.pos_std);
      m.velocity_std = Vec3::Constant(s.noise.vel_std);
      for (int k = 0; k < 3; ++k) {
        m.position[k] = truth.p[k] + s.noise.pos_std * normal(rng);
        m.velocity[k] = truth.v[k] + s.noise.vel_std * normal(rng);
      }
      taken.push_back(m);
    }
    // Arrivals: samples taken exactly `lag` steps ago.
    while (!taken.empty() && std::llround(taken.front().time_taken / kDt) + lag == n) {
      filter.Fuse(taken.front());
      taken.erase(taken.begin());
    }
    Eigen::Matrix<double, 6, 1> e;
    e << filter.position() - truth.p, filter.velocity() - truth.v;
    run.max_error = std::max(run.max_error, e.cwiseAbs().maxCoeff());
    if (n == steps) {
      const Eigen::Matrix<double, 6, 6> P = filter.covariance().topLeftCorner<6, 6>();
      run.nees_at_end = e.dot(P.ldlt().solve(e));
    }
  }
  return run;
}

TEST(KfIns, NoiseFreeSensorsWithLatencyGiveTheTruth) {
  Scenario s;  // 10 Hz, 110 ms late, exact sensors
  const Flight run = Fly(s, 1);
  EXPECT_LT(run.max_error, 1e-6);
}

// The same sample fused on time (then propagated 110 ms) and fused 110 ms late at its own time.
TEST(KfIns, ALateMeasurementFusedAtItsTimeEqualsTheOnTimeOnePropagated) {
  KfInsConfig c;
  c.timestep = kDt;
  c.accel_noise_density = 0.05;
  c.accel_bias_walk = 1e-3;
  c.history = 0.2;
  KfIns on_time(c), late(c);
  AidingSample m;
  m.has_position = m.has_velocity = true;
  m.position = Vec3(0.3, -0.2, 0.1);
  m.velocity = Vec3(0.05, 0.02, -0.01);
  m.position_std = Vec3::Constant(0.3);
  m.velocity_std = Vec3::Constant(0.05);
  const int64_t taken = 40, lag = 55;  // 55 steps of 2 ms: 110 ms
  m.time_taken = taken * kDt;
  for (int64_t n = 1; n <= taken + lag; ++n) {
    const Vec3 f = TrueAccel(n) + Vec3(0, 0, kG);
    on_time.Propagate(n, f);
    late.Propagate(n, f);
    if (n == taken) {
      EXPECT_TRUE(on_time.Fuse(m));
    }
  }
  EXPECT_GT((on_time.state() - late.state()).norm(), 1e-3);  // the sample matters
  EXPECT_TRUE(late.Fuse(m));
  EXPECT_LT((on_time.state() - late.state()).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((on_time.covariance() - late.covariance()).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(KfIns, OutliersAreGatedAndCountedAndTooOldOnesRefused) {
  KfInsConfig c;
  c.timestep = kDt;
  c.accel_noise_density = 0.05;
  c.history = 0.05;
  KfIns f(c);
  for (int64_t n = 1; n <= 100; ++n) f.Propagate(n, Vec3(0, 0, kG));
  AidingSample m;
  m.time_taken = 100 * kDt;
  m.has_position = true;
  m.position_std = Vec3::Constant(0.01);
  m.position = Vec3(0.0, 0.0, 0.0);
  EXPECT_TRUE(f.Fuse(m));
  m.position = Vec3(50.0, 0.0, 0.0);  // far beyond 5 sigma of a 1 m prior
  EXPECT_FALSE(f.Fuse(m));
  EXPECT_EQ(f.rejected(), 1);
  EXPECT_EQ(f.fused(), 1);
  m.position = Vec3::Zero();
  m.time_taken = 10 * kDt;  // 180 ms old, history 50 ms
  EXPECT_FALSE(f.Fuse(m));
  EXPECT_EQ(f.too_old(), 1);
}

// Wilson-Hilferty: the p-quantile of chi-square with k degrees of freedom.
double ChiSquareQuantile(double p, double k) {
  // Standard normal quantile by bisection on erfc.
  double lo = -10, hi = 10;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (0.5 * std::erfc(-mid / std::sqrt(2.0)) < p ? lo : hi) = mid;
  }
  const double z = 0.5 * (lo + hi), h = 2.0 / (9.0 * k);
  return k * std::pow(1.0 - h + z * std::sqrt(h), 3.0);
}

TEST(KfIns, MeanNeesIsInsideTheChiSquareBandOverSeeds) {
  Scenario s;
  s.noise = {0.05, 0.3, 0.05};
  s.duration = 6.0;
  constexpr int kSeeds = 30;
  double sum = 0;
  for (int seed = 0; seed < kSeeds; ++seed) sum += Fly(s, 1000 + seed).nees_at_end;
  const double mean = sum / kSeeds, dof = 6.0 * kSeeds;
  EXPECT_GT(mean, ChiSquareQuantile(0.025, dof) / kSeeds);
  EXPECT_LT(mean, ChiSquareQuantile(0.975, dof) / kSeeds);
}

}  // namespace
}  // namespace mjf::estimator
