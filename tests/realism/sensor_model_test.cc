// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/realism/sensor_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "mjformation/config/fixed_state_archive.hpp"

namespace mjf::realism {
namespace {

constexpr double kDt = 0.001;
// Two-sided 99.9 % normal quantile: a correct model fails a check 1 time in 1000.
constexpr double kZ = 3.29;

mjfVehicleState State(double k) {
  mjfVehicleState s{};
  for (int a = 0; a < 3; ++a) {
    s.pos[a] = 10 * std::sin(0.01 * k + a);
    s.vel[a] = std::cos(0.02 * k + a);
    s.gyro[a] = 0.1 * std::sin(0.03 * k - a);
  }
  const double half = 0.5 * std::sin(0.001 * k);
  s.quat[0] = std::cos(half);
  s.quat[3] = std::sin(half);
  return s;
}

SensorParams Only(Channel c, ChannelNoise noise) {
  SensorParams p = SensorParams::Ideal();
  p[c] = noise;
  return p;
}

TEST(SensorModel, IdealIsExactPassThrough) {
  SensorModel model(SensorParams::Ideal(), kDt, 7);
  for (int64_t k = 0; k < 1000; ++k) {
    const mjfVehicleState truth = State(static_cast<double>(k));
    mjfVehicleState measured;
    std::memset(&measured, 0xAB, sizeof(measured));
    model.Measure(k, truth, &measured);
    ASSERT_EQ(0, std::memcmp(&truth, &measured, sizeof(truth))) << "step " << k;
  }
}

TEST(SensorModel, WhiteNoiseMeanAndStdWithinConfidenceIntervals) {
  const double sigma = 0.3;
  SensorModel model(Only(Channel::kVelocity, {sigma, 0, 0, 0}), kDt, 11);
  const int n = 200000;
  double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
  for (int64_t k = 0; k < n; ++k) {
    const mjfVehicleState truth = State(static_cast<double>(k));
    mjfVehicleState m;
    model.Measure(k, truth, &m);
    for (int a = 0; a < 3; ++a) {
      const double e = m.vel[a] - truth.vel[a];
      sum[a] += e;
      sum2[a] += e * e;
      ASSERT_EQ(m.pos[a], truth.pos[a]);  // other channels untouched
    }
  }
  for (int a = 0; a < 3; ++a) {
    const double mean = sum[a] / n;
    const double var = (sum2[a] - n * mean * mean) / (n - 1);
    EXPECT_LT(std::abs(mean), kZ * sigma / std::sqrt(n)) << "axis " << a;
    // var / sigma^2 ~ chi^2_{n-1} / (n-1): standard deviation sqrt(2 / (n-1)).
    EXPECT_LT(std::abs(var / (sigma * sigma) - 1), kZ * std::sqrt(2.0 / (n - 1))) << "axis " << a;
  }
}

// var(b(t)) = q^2 t: over many independent vehicles, at several times, with held samples
// (10 Hz) and with samples every step (the walk then steps every 10 ms).
class BiasWalk : public ::testing::TestWithParam<double> {};
INSTANTIATE_TEST_SUITE_P(Rates, BiasWalk, ::testing::Values(100.0, 0.0));
TEST_P(BiasWalk, VarianceGrowsLinearlyInTime) {
  const double q = 0.2;  // m/sqrt(s)
  const int vehicles = 3000;
  const int64_t checkpoints[] = {100, 400, 1600};  // steps (0.1, 0.4, 1.6 s)
  std::vector<double> sum2(3, 0.0);
  for (int v = 0; v < vehicles; ++v) {
    SensorModel model(Only(Channel::kPosition, {0, q, GetParam(), 0}), kDt, StreamSeed(5, v, 1));
    int c = 0;
    for (int64_t k = 0; k <= checkpoints[2]; ++k) {
      mjfVehicleState m;
      const mjfVehicleState truth = State(0);
      model.Measure(k, truth, &m);
      if (k == checkpoints[c]) {
        const double b = model.Bias(Channel::kPosition)[0];
        ASSERT_NEAR(m.pos[0] - truth.pos[0], b, 1e-12);  // what the controller sees
        sum2[c] += b * b;
        ++c;
      }
    }
  }
  for (int c = 0; c < 3; ++c) {
    const double t = checkpoints[c] * kDt;
    const double var = sum2[c] / vehicles;  // the mean is 0 by construction
    EXPECT_LT(std::abs(var / (q * q * t) - 1), kZ * std::sqrt(2.0 / vehicles)) << "t = " << t;
  }
}

// Truth = the step number: the measurement must be the number of the last sampled, delayed step.
TEST(SensorModel, RateAndLatencyAreExact) {
  SensorParams p = SensorParams::Ideal();
  p[Channel::kPosition] = {0, 0, 10.0, 0.030};  // every 100 steps, 30 steps late
  p[Channel::kBodyRate] = {0, 0, 250.0, 0.0};   // every 4 steps
  p[Channel::kVelocity] = {0, 0, 0.0, 0.005};   // every step, 5 steps late
  SensorModel model(p, kDt, 3);
  for (int64_t k = 0; k < 1000; ++k) {
    mjfVehicleState truth = State(0), m;
    for (int a = 0; a < 3; ++a) truth.pos[a] = truth.vel[a] = truth.gyro[a] = k + a;
    model.Measure(k, truth, &m);
    const int64_t seen_pos = k < 30 ? 0 : (k - 30) / 100 * 100;
    const int64_t seen_vel = k < 5 ? 0 : k - 5;
    const int64_t seen_gyro = k / 4 * 4;
    for (int a = 0; a < 3; ++a) {
      ASSERT_EQ(m.pos[a], seen_pos + a) << "step " << k;
      ASSERT_EQ(m.vel[a], seen_vel + a) << "step " << k;
      ASSERT_EQ(m.gyro[a], seen_gyro + a) << "step " << k;
    }
    ASSERT_EQ(0, std::memcmp(m.quat, truth.quat, sizeof(m.quat)));
  }
}

// The native plugin's walk (FixedStateArchive::Updating into the block it loaded from at the
// last step): a latency buffer gets only the slot written since, and the block stays what a
// full save writes, step after step, while the buffers fill and wrap (consumer_gnss: 110 ms).
TEST(SensorModel, StateUpdatedInPlaceIsTheFullSaveAtEveryStep) {
  SensorModel model(SensorParams::ConsumerGnss(), kDt, 11);
  using runner::FixedStateArchive;
  FixedStateArchive sizing = FixedStateArchive::Sizing();
  model.VisitState(sizing);
  std::vector<double> block(sizing.size()), full(sizing.size());
  FixedStateArchive first = FixedStateArchive::Saving(block.data());
  model.VisitState(first);
  for (int64_t k = 0; k < 400; ++k) {
    if (k % 7 == 3) {  // as a copied mjData's holder does: load the block, then go on
      FixedStateArchive loading = FixedStateArchive::Loading(block.data());
      model.VisitState(loading);
    }
    mjfVehicleState truth = State(0), m;
    for (int a = 0; a < 3; ++a) truth.pos[a] = truth.vel[a] = 0.01 * k + a;
    model.Measure(k, truth, &m);
    if (k % 11 == 2) {
      // Two steps between two walks of the block, with a walk that only counts (a host sizing
      // the state) between them: both slots must reach the block.
      FixedStateArchive counting = FixedStateArchive::Sizing();
      model.VisitState(counting);
      model.Measure(++k, truth, &m);
    }
    FixedStateArchive updating = FixedStateArchive::Updating(block.data());
    model.VisitState(updating);
    FixedStateArchive saving = FixedStateArchive::Saving(full.data());
    model.VisitState(saving);
    ASSERT_EQ(block, full) << "step " << k;
  }
}

// The attitude error is a rotation by the drawn vector: its angle has the drawn statistics.
TEST(SensorModel, AttitudeNoiseIsASmallRotationOfTheStatedSize) {
  const double sigma = 0.02;
  SensorModel model(Only(Channel::kAttitude, {sigma, 0, 0, 0}), kDt, 17);
  const int n = 50000;
  double sum2 = 0;
  for (int64_t k = 0; k < n; ++k) {
    const mjfVehicleState truth = State(static_cast<double>(k));
    mjfVehicleState m;
    model.Measure(k, truth, &m);
    double norm = 0, dot = 0;
    for (int j = 0; j < 4; ++j) {
      norm += m.quat[j] * m.quat[j];
      dot += m.quat[j] * truth.quat[j];
    }
    ASSERT_NEAR(norm, 1.0, 1e-12);
    const double angle = 2 * std::acos(std::min(1.0, std::abs(dot)));
    sum2 += angle * angle;
  }
  // |e|^2 / sigma^2 ~ chi^2_3: mean 3, variance 6.
  const double mean = sum2 / n / (sigma * sigma);
  EXPECT_LT(std::abs(mean - 3), kZ * std::sqrt(6.0 / n));
}

TEST(SensorModel, SameSeedSameBytesOtherSeedOtherBytes) {
  auto record = [](uint64_t seed) {
    SensorModel model(SensorParams::Typical(), kDt, seed);
    std::vector<mjfVehicleState> out(3000);
    for (int64_t k = 0; k < 3000; ++k) {
      model.Measure(k, State(static_cast<double>(k)), &out[k]);
    }
    return out;
  };
  const auto a = record(42), b = record(42), c = record(43);
  EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])));
  EXPECT_NE(0, std::memcmp(a.data(), c.data(), a.size() * sizeof(a[0])));
}

TEST(SensorModel, TypicalScaledThreeTimes) {
  const SensorParams t = SensorParams::Typical(), t3 = t.Scaled(3);
  for (int k = 0; k < kChannels; ++k) {
    EXPECT_DOUBLE_EQ(t3.channel[k].white_std, 3 * t.channel[k].white_std);
    EXPECT_DOUBLE_EQ(t3.channel[k].bias_walk, 3 * t.channel[k].bias_walk);
    EXPECT_EQ(t3.channel[k].rate_hz, t.channel[k].rate_hz);
    EXPECT_EQ(t3.channel[k].latency_s, t.channel[k].latency_s);
  }
  EXPECT_FALSE(t.IsIdeal());
  EXPECT_EQ("", t.Validate(kDt));
  // PX4 SITL gyro noise density 1.8665e-4 rad/s/sqrt(Hz) sampled at 1 kHz.
  EXPECT_NEAR(t[Channel::kBodyRate].white_std, 0.0059, 0.0001);
}

TEST(SensorModel, RefusesBadParameters) {
  EXPECT_NE(Only(Channel::kPosition, {-1, 0, 0, 0}).Validate(kDt).find("position_std"),
            std::string::npos);
  EXPECT_NE(Only(Channel::kVelocity, {NAN, 0, 0, 0}).Validate(kDt).find("velocity_std"),
            std::string::npos);
  EXPECT_NE(Only(Channel::kAttitude, {0, -0.1, 0, 0}).Validate(kDt).find("attitude_bias_walk"),
            std::string::npos);
  EXPECT_NE(Only(Channel::kBodyRate, {0, 0, 300, 0}).Validate(kDt).find("body_rate_rate"),
            std::string::npos);  // 1/300 s is not a whole number of 1 ms steps
  EXPECT_NE(Only(Channel::kPosition, {0, 0, 0, 0.0005}).Validate(kDt).find("position_latency"),
            std::string::npos);
  EXPECT_THROW(SensorModel(Only(Channel::kPosition, {-1, 0, 0, 0}), kDt, 1), std::invalid_argument);
  SensorModel model(SensorParams::Typical(), kDt, 1);
  mjfVehicleState m;
  model.Measure(0, State(0), &m);
  EXPECT_THROW(model.Measure(2, State(0), &m), std::logic_error);  // a skipped step
}

}  // namespace
}  // namespace mjf::realism
