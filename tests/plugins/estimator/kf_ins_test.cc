// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// plugins/estimator/src/kf_ins.cc: the filter alone, on a vehicle integrated here with the
// simulator's scheme (semi-implicit Euler), so every figure below is derived, not recorded.
#include "mjformation/estimator/kf_ins.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <stdexcept>
#include <vector>

#include "mjformation/realism/sensor_model.hpp"

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
  // The position source's Gauss-Markov wander (the sensor model's): stationary sigma, tau.
  double wander_sigma = 0.0, wander_tau = 100.0;
};

struct Scenario {
  double rate_hz = 10.0;
  double latency = 0.11;
  Noise noise;
  double duration = 10.0;
  // Start the filter off the truth by a draw from its own prior (p, v, b; the wander starts
  // stationary in both), as consistency requires; false: at the truth.
  bool start_from_prior = false;
};

KfInsConfig FilterFor(const Scenario& s) {
  KfInsConfig c;
  c.timestep = kDt;
  c.accel_noise_density = s.noise.accel_density;
  c.history = s.latency + 2 * kDt;
  c.initial_position = Truth{}.p;
  c.gravity = kG;
  c.position_wander_std = s.noise.wander_sigma;
  c.position_wander_tau = s.noise.wander_tau;
  return c;
}

struct Flight {
  double max_error = 0.0;    // over the whole run, p and v
  double nees_at_end = 0.0;  // (p, v) error' P^-1 error at the end
};

// Flies the scenario: each step the accelerometer of the step just ended propagates, and the
// samples taken `latency` ago (every 1/rate s) are fused at their own time.
// `model` is what the filter is told of the noise (its wander state, the stated white std of a
// position sample); the sensors follow s.noise.
Flight FlyWithFilterModel(const Scenario& s, const Noise& model, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  Truth truth;
  KfInsConfig config = FilterFor(s);
  config.position_wander_std = model.wander_sigma;
  config.position_wander_tau = model.wander_tau;
  Vec3 bias = Vec3::Zero();  // the true accelerometer bias (world frame), constant
  if (s.start_from_prior) {
    for (int k = 0; k < 3; ++k) {
      truth.p[k] += config.initial_position_std * normal(rng);
      truth.v[k] += config.initial_velocity_std * normal(rng);
      bias[k] = config.initial_bias_std * normal(rng);
    }
  }
  KfIns filter(config);
  const int64_t period = std::llround(1.0 / (s.rate_hz * kDt));
  // The wander per sample: w+ = phi w + sigma sqrt(1 - phi^2) n, stationary from the first.
  const double phi = std::exp(-period * kDt / s.noise.wander_tau);
  Vec3 wander;
  for (int k = 0; k < 3; ++k) wander[k] = s.noise.wander_sigma * normal(rng);
  bool first_sample = true;
  const int64_t lag = std::llround(s.latency / kDt);
  std::vector<AidingSample> taken;  // by the step they were taken
  Flight run;
  const int64_t steps = std::llround(s.duration / kDt);
  for (int64_t n = 0; n <= steps; ++n) {
    if (n > 0) {
      const Vec3 a = TrueAccel(n - 1);
      truth.Step(a);
      Vec3 f = a - Vec3(0, 0, -kG) + bias;
      for (int k = 0; k < 3; ++k) f[k] += s.noise.accel_density / std::sqrt(kDt) * normal(rng);
      filter.Propagate(n, f);
    }
    if (n % period == 0) {
      AidingSample m;
      m.time_taken = n * kDt;
      m.has_position = m.has_velocity = true;
      m.position_std = Vec3::Constant(model.pos_std);
      m.velocity_std = Vec3::Constant(model.vel_std);
      if (!first_sample) {
        for (int k = 0; k < 3; ++k) {
          wander[k] =
              phi * wander[k] + s.noise.wander_sigma * std::sqrt(1.0 - phi * phi) * normal(rng);
        }
      }
      first_sample = false;
      for (int k = 0; k < 3; ++k) {
        m.position[k] = truth.p[k] + wander[k] + s.noise.pos_std * normal(rng);
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

Flight Fly(const Scenario& s, uint64_t seed) { return FlyWithFilterModel(s, s.noise, seed); }

TEST(KfIns, NoiseFreeSensorsWithLatencyGiveTheTruth) {
  Scenario s;  // 10 Hz, 110 ms late, exact sensors
  const Flight run = Fly(s, 1);
  EXPECT_LT(run.max_error, 1e-6);
}

// The filter the late-fusion tests fly twice, once fusing on time and once late.
KfInsConfig LateFusionConfig() {
  KfInsConfig c;
  c.timestep = kDt;
  c.accel_noise_density = 0.05;
  c.accel_bias_walk = 1e-3;
  c.history = 0.2;
  return c;
}

// A position and velocity sample taken at step `taken`.
AidingSample PositionAndVelocityAt(int64_t taken) {
  AidingSample m;
  m.has_position = m.has_velocity = true;
  m.position = Vec3(0.3, -0.2, 0.1);
  m.velocity = Vec3(0.05, 0.02, -0.01);
  m.position_std = Vec3::Constant(0.3);
  m.velocity_std = Vec3::Constant(0.05);
  m.time_taken = static_cast<double>(taken) * kDt;
  return m;
}

// Propagates both filters with the true specific force over steps 1..last; fuse_due(n) fuses
// what either takes at step n.
void FlyTwins(KfIns& on_time, KfIns& late, int64_t last,
              const std::function<void(int64_t)>& fuse_due) {
  for (int64_t n = 1; n <= last; ++n) {
    const Vec3 f = TrueAccel(n) + Vec3(0, 0, kG);
    on_time.Propagate(n, f);
    late.Propagate(n, f);
    fuse_due(n);
  }
}

void ExpectSameEstimate(const KfIns& a, const KfIns& b) {
  EXPECT_LT((a.state() - b.state()).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((a.covariance() - b.covariance()).cwiseAbs().maxCoeff(), 1e-12);
}

// The same sample fused on time (then propagated 110 ms) and fused 110 ms late at its own time.
TEST(KfIns, ALateMeasurementFusedAtItsTimeEqualsTheOnTimeOnePropagated) {
  const KfInsConfig c = LateFusionConfig();
  KfIns on_time(c), late(c);
  const int64_t taken = 40, lag = 55;  // 55 steps of 2 ms: 110 ms
  const AidingSample m = PositionAndVelocityAt(taken);
  FlyTwins(on_time, late, taken + lag, [&](int64_t n) {
    if (n == taken) {
      EXPECT_TRUE(on_time.Fuse(m));
    }
  });
  EXPECT_GT((on_time.state() - late.state()).norm(), 1e-3);  // the sample matters
  EXPECT_TRUE(late.Fuse(m));
  ExpectSameEstimate(on_time, late);
}

// Two late samples whose windows overlap: the second is taken at a step whose stored posterior
// the first fusion left stale (it was stored before the first arrived). Both fused late, each at
// its own time, equal both fused on time, propagated.
TEST(KfIns, OverlappingLateMeasurementsEqualTheOnTimeOnesPropagated) {
  KfInsConfig c = LateFusionConfig();
  c.position_wander_std = 2.0;
  c.position_wander_tau = 100.0;
  KfIns on_time(c), late(c);
  const int64_t taken_first = 40, taken_second = 60, lag = 55;
  const AidingSample first = PositionAndVelocityAt(taken_first);
  AidingSample second;
  second.has_velocity = true;  // velocity only, 20 steps later
  second.velocity = Vec3(-0.04, 0.03, 0.02);
  second.velocity_std = Vec3::Constant(0.05);
  second.time_taken = taken_second * kDt;
  FlyTwins(on_time, late, taken_second + lag, [&](int64_t n) {
    if (n == taken_first) {
      EXPECT_TRUE(on_time.Fuse(first));
    }
    if (n == taken_second) {
      EXPECT_TRUE(on_time.Fuse(second));
    }
    if (n == taken_first + lag) {
      EXPECT_TRUE(late.Fuse(first));
    }
  });
  EXPECT_GT((on_time.state() - late.state()).norm(), 1e-4);  // the second sample matters
  EXPECT_TRUE(late.Fuse(second));
  ExpectSameEstimate(on_time, late);
  EXPECT_EQ(late.fused(), 2);
}

// Samples taken only on the aiding schedule (every 20 steps here): a history of only those
// steps' posteriors fuses them late exactly as the every-step history does, bit for bit, in a
// fraction of the state; a sample off the schedule is a caller's error.
TEST(KfIns, AHistoryOfTheAidingScheduleOnlyIsTheEveryStepOneBitForBit) {
  KfInsConfig c = LateFusionConfig();  // history 0.2 s: 101 steps
  c.position_wander_std = 2.0;
  KfIns every_step(c);
  c.aiding_period = 20 * kDt;
  KfIns scheduled(c);
  EXPECT_EQ(every_step.history_slots(), 101u);
  EXPECT_EQ(scheduled.history_slots(), 6u);  // (101 - 1) / 20 + 1
  EXPECT_EQ(scheduled.max_corrections(), 14u);
  const int64_t lag = 55;
  AidingSample velocity_only;
  velocity_only.has_velocity = true;
  velocity_only.velocity = Vec3(-0.04, 0.03, 0.02);
  velocity_only.velocity_std = Vec3::Constant(0.05);
  for (int64_t n = 1; n <= 400; ++n) {
    const Vec3 f = TrueAccel(n) + Vec3(0, 0, kG);
    every_step.Propagate(n, f);
    scheduled.Propagate(n, f);
    // Every scheduled step's sample arrives `lag` late, alternately both and velocity only:
    // their windows overlap (three in flight at once).
    if (n >= lag && (n - lag) % 20 == 0) {
      AidingSample m = PositionAndVelocityAt(n - lag);
      if ((n - lag) % 40 == 20) {
        m = velocity_only;
        m.time_taken = static_cast<double>(n - lag) * kDt;
      }
      EXPECT_EQ(every_step.Fuse(m), scheduled.Fuse(m)) << n;
    }
  }
  EXPECT_EQ(every_step.fused(), scheduled.fused());
  EXPECT_GT(every_step.fused(), 0);
  EXPECT_EQ(every_step.fused() + every_step.rejected(), 18);  // none too old
  EXPECT_TRUE(every_step.state() == scheduled.state());
  EXPECT_TRUE(every_step.covariance() == scheduled.covariance());
  EXPECT_THROW(scheduled.Fuse(PositionAndVelocityAt(390)), std::logic_error);
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

// The consumer-GNSS case: most of the position error is a Gauss-Markov wander (2.12 m, 100 s),
// 0.3 m of white jitter on top. With the wander a state, the filter is consistent; fusing the
// same samples as white noise of their whole stated accuracy (the wander taken as white, as the
// filter once did) is grossly overconfident.
TEST(KfIns, MeanNeesWithGnssWanderIsInsideTheBandOnlyWithTheWanderAState) {
  Scenario s;
  s.noise = {0.05, 0.3, 0.05, 2.5 / 1.1774, 100.0};
  s.duration = 6.0;
  s.start_from_prior = true;
  constexpr int kSeeds = 30;
  double sum = 0;
  for (int seed = 0; seed < kSeeds; ++seed) sum += Fly(s, 2000 + seed).nees_at_end;
  const double mean = sum / kSeeds, dof = 6.0 * kSeeds;
  std::printf("wander as a state: mean NEES %.3f (band [%.3f, %.3f])\n", mean,
              ChiSquareQuantile(0.025, dof) / kSeeds, ChiSquareQuantile(0.975, dof) / kSeeds);
  EXPECT_GT(mean, ChiSquareQuantile(0.025, dof) / kSeeds);
  EXPECT_LT(mean, ChiSquareQuantile(0.975, dof) / kSeeds);

  // The same flights (the truth still wanders) through a filter told nothing of the wander,
  // fusing the whole stated accuracy sqrt(white^2 + wander^2) as white noise.
  Noise white = s.noise;
  white.pos_std = std::hypot(s.noise.pos_std, s.noise.wander_sigma);
  white.wander_sigma = 0.0;
  double white_sum = 0;
  for (int seed = 0; seed < kSeeds; ++seed) {
    white_sum += FlyWithFilterModel(s, white, 2000 + seed).nees_at_end;
  }
  std::printf("wander taken as white: mean NEES %.3f\n", white_sum / kSeeds);
  EXPECT_GT(white_sum / kSeeds, 3.0 * ChiSquareQuantile(0.975, dof) / kSeeds);
}

// Steady hover, white-noise part: the steady-state Riccati solution per axis
// for each suite, derived here from its own 3-state model (p, v, b; semi-implicit Euler), must
// reach the targets, and the filter's covariance must converge to it.
struct Suite {
  const char* name;
  realism::SensorParams params;
  double position_target, velocity_target;  // 1 sigma per axis, m and m/s
};

// What the filter is told of the accelerometer: its density and the attitude channel's tilt
// error times g (estimated_sensors.cc, SuiteInfo).
double AssumedDensity(const realism::SensorParams& p) {
  const auto& att = p[realism::Channel::kAttitude];
  return std::hypot(p.accel.noise_density, kG * att.white_std / std::sqrt(att.rate_hz));
}
double AssumedWalk(const realism::SensorParams& p) {
  return std::hypot(p.accel.bias_walk, kG * p[realism::Channel::kAttitude].bias_walk);
}

// Iterates the discrete Riccati recursion of one axis to its periodic steady state; returns
// the largest 1-sigma of (p, v) over one sample period after the latency's propagation.
std::array<double, 2> SteadySigma(const realism::SensorParams& sp, double dt) {
  const auto& pos = sp[realism::Channel::kPosition];
  const auto& vel = sp[realism::Channel::kVelocity];
  const double n = AssumedDensity(sp), w = AssumedWalk(sp);
  Eigen::Matrix3d F, Q, P = Eigen::Vector3d(1.0, 0.25, 0.04).asDiagonal();
  F << 1, dt, -dt * dt, 0, 1, -dt, 0, 0, 1;
  Q << n * n * dt * dt * dt / 3, n * n * dt * dt / 2, 0, n * n * dt * dt / 2, n * n * dt, 0, 0, 0,
      w * w * dt;
  Eigen::Matrix<double, 2, 3> H;
  H << 1, 0, 0, 0, 1, 0;
  const Eigen::Matrix2d R =
      Eigen::Vector2d(pos.white_std * pos.white_std, vel.white_std * vel.white_std).asDiagonal();
  const int64_t period = std::llround(1.0 / (pos.rate_hz * dt));
  const int64_t lag = std::llround(pos.latency_s / dt);
  // 120 s of sample periods, each ending with the fusion of the sample taken then.
  for (int64_t k = 0; k < std::llround(120.0 / (period * dt)); ++k) {
    for (int64_t j = 0; j < period; ++j) P = F * P * F.transpose() + Q;
    const Eigen::Matrix<double, 3, 2> K = P * H.transpose() * (H * P * H.transpose() + R).inverse();
    P = (Eigen::Matrix3d::Identity() - K * H) * P;
  }
  std::array<double, 2> worst{0, 0};
  // The estimate for now is worst just before the next arrival: period + lag - 1 steps after the
  // time the last fused sample was taken.
  for (int64_t k = 0; k < period + lag - 1; ++k) {
    P = F * P * F.transpose() + Q;
    worst = {std::max(worst[0], std::sqrt(P(0, 0))), std::max(worst[1], std::sqrt(P(1, 1)))};
  }
  return worst;
}

TEST(KfIns, SteadyHoverRiccatiFiguresMeetTheSuiteTargets) {
  const Suite suites[] = {{"consumer_gnss", realism::SensorParams::ConsumerGnss(), 0.11, 0.06},
                          {"rtk", realism::SensorParams::Rtk(), 0.01, 0.025},
                          {"mocap", realism::SensorParams::MotionCapture(), 0.0005, 0.01}};
  for (const Suite& s : suites) {
    const auto sigma = SteadySigma(s.params, 0.001);
    RecordProperty(std::string(s.name) + "_position_sigma", std::to_string(sigma[0]));
    RecordProperty(std::string(s.name) + "_velocity_sigma", std::to_string(sigma[1]));
    std::printf("%s: steady hover 1 sigma per axis: position %.5f m, velocity %.5f m/s\n", s.name,
                sigma[0], sigma[1]);
    EXPECT_LE(sigma[0], s.position_target) << s.name;
    EXPECT_LE(sigma[1], s.velocity_target) << s.name;
    EXPECT_GT(sigma[0], 0.0) << s.name;
  }
}

// The filter's own covariance, at a sample arrival after 30 s of hover, equals the recursion's.
TEST(KfIns, TheFilterCovarianceConvergesToTheDerivedRiccatiSolution) {
  const realism::SensorParams sp = realism::SensorParams::ConsumerGnss();
  KfInsConfig c;
  c.timestep = 0.001;
  c.accel_noise_density = AssumedDensity(sp);
  c.accel_bias_walk = AssumedWalk(sp);
  c.history = 0.2;
  KfIns f(c);
  AidingSample m;
  m.has_position = m.has_velocity = true;
  m.position_std = Vec3::Constant(sp[realism::Channel::kPosition].white_std);
  m.velocity_std = Vec3::Constant(sp[realism::Channel::kVelocity].white_std);
  double largest[2] = {0, 0};
  for (int64_t n = 1; n <= 40000; ++n) {
    f.Propagate(n, Vec3(0, 0, kG));
    if (n % 100 == 10 && n > 110) {
      m.time_taken = (n - 110) * 0.001;
      f.Fuse(m);
    }
    if (n > 30000) {
      largest[0] = std::max(largest[0], std::sqrt(f.covariance()(0, 0)));
      largest[1] = std::max(largest[1], std::sqrt(f.covariance()(3, 3)));
    }
  }
  const auto derived = SteadySigma(sp, 0.001);
  EXPECT_NEAR(largest[0], derived[0], 1e-3 * derived[0]);
  EXPECT_NEAR(largest[1], derived[1], 1e-3 * derived[1]);
}

}  // namespace
}  // namespace mjf::estimator
