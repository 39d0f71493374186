// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstring>
#include <vector>

#include "mjformation/realism/drag.hpp"
#include "mjformation/realism/dryden.hpp"
#include "mjformation/realism/gust.hpp"
#include "mjformation/realism/wind_field.hpp"

namespace mjf::realism {
namespace {

// MIL-F-8785C low-altitude forms evaluated here by hand, in feet, for h = 5 m and W20 = 15 m/s.
TEST(Dryden, LowAltitudeIntensitiesAndScaleLengths) {
  const DrydenParams p = DrydenParams::LowAltitude(5.0, 15.0, 10.0);
  const double h_ft = 5.0 / 0.3048;  // 16.404 ft
  const double lu_ft = h_ft / std::pow(0.177 + 0.000823 * h_ft, 1.2);
  EXPECT_NEAR(p.scale_length[0], lu_ft * 0.3048, 1e-9);
  EXPECT_NEAR(p.scale_length[0], 36.5, 0.2);  // about 120 ft
  EXPECT_DOUBLE_EQ(p.scale_length[1], p.scale_length[0]);
  EXPECT_NEAR(p.scale_length[2], 5.0, 1e-12);  // L_w = h
  EXPECT_NEAR(p.sigma[2], 1.5, 1e-12);         // 0.1 W20
  EXPECT_NEAR(p.sigma[0], 1.5 / std::pow(0.177 + 0.000823 * h_ft, 0.4), 1e-12);
  EXPECT_NEAR(p.sigma[0], 2.91, 0.01);
  EXPECT_THROW(DrydenParams::LowAltitude(2.0, 15.0, 10.0), std::invalid_argument);    // < 10 ft
  EXPECT_THROW(DrydenParams::LowAltitude(400.0, 15.0, 10.0), std::invalid_argument);  // > 1000 ft
}

// Welch's averaged periodogram (Hann window, half overlap) of a long record against the Dryden
// PSD, at log-spaced frequencies from 0.6x to 60x the corner 1 / (2 pi tau). With ~500 segments
// a bin's estimate has a relative standard deviation of about 5 %; the tolerance is 15 % (3
// standard deviations); the bias from sampling (aliasing) at these frequencies is below 2 %.
TEST(Dryden, PowerSpectralDensityMatchesTheDrydenForm) {
  DrydenParams p;
  p.sigma = {2.0, 1.5, 1.0};
  p.scale_length = {50.0, 50.0, 20.0};
  p.airspeed = 10.0;
  const double dt = 0.05;
  const int n = 1 << 20, segment = 4096;
  DrydenTurbulence turbulence(p, dt, 99);
  std::vector<std::array<double, 3>> x(n);
  for (auto& v : x) v = turbulence.Step();

  std::vector<double> window(segment);
  double window_power = 0;
  for (int j = 0; j < segment; ++j) {
    window[j] = 0.5 - 0.5 * std::cos(2 * M_PI * j / segment);
    window_power += window[j] * window[j];
  }
  for (int k = 0; k < 3; ++k) {
    double var = 0;
    for (const auto& v : x) var += v[k] * v[k];
    var /= n;
    // Effective independent samples ~ n dt / (2 tau): a few thousand; 6 % is > 3 sigma.
    EXPECT_NEAR(var / (p.sigma[k] * p.sigma[k]), 1.0, 0.06) << "component " << k;
    const double tau = p.scale_length[k] / p.airspeed;
    const double corner_hz = 1 / (2 * M_PI * tau);
    for (double factor = 0.6; factor <= 60; factor *= 1.8) {
      // The nearest bin of the segment's DFT, evaluated directly.
      const int bin = static_cast<int>(std::lround(factor * corner_hz * segment * dt));
      const double f = bin / (segment * dt);
      double psd = 0;
      int segments = 0;
      for (int start = 0; start + segment <= n; start += segment / 2, ++segments) {
        std::complex<double> sum = 0;
        const std::complex<double> step = std::polar(1.0, -2 * M_PI * bin / segment);
        std::complex<double> phase = 1;
        for (int j = 0; j < segment; ++j, phase *= step) sum += window[j] * x[start + j][k] * phase;
        psd += 2 * dt * std::norm(sum) / window_power;  // one-sided, per Hz
      }
      psd /= segments;
      const double expected = 2 * p.TwoSidedPsd(k, 2 * M_PI * f);  // one-sided, per Hz
      EXPECT_NEAR(psd / expected, 1.0, 0.15) << "component " << k << " f = " << f << " Hz";
    }
  }
}

TEST(Dryden, AnalyticPsdIntegratesToTheVariance) {
  DrydenParams p;
  p.sigma = {2.0, 1.5, 1.0};
  p.scale_length = {30.0, 30.0, 5.0};
  p.airspeed = 3.0;
  for (int k = 0; k < 3; ++k) {
    // (1 / 2 pi) integral S d omega with omega = tan(theta) V / L (the tails are O(1/omega^2)).
    double integral = 0;
    const int steps = 200000;
    for (int j = 0; j < steps; ++j) {
      const double theta = (j + 0.5) / steps * M_PI / 2;
      const double scale = p.airspeed / p.scale_length[k];
      const double omega = std::tan(theta) * scale;
      integral += 2 * p.TwoSidedPsd(k, omega) * scale / std::pow(std::cos(theta), 2);
    }
    integral *= (M_PI / 2) / steps / (2 * M_PI);
    EXPECT_NEAR(integral, p.sigma[k] * p.sigma[k], 1e-6) << "component " << k;
  }
}

TEST(Gust, OneCosineShapeAndPeak) {
  OneCosineGust g{10.0, 4.0, {3.0, -1.0, 0.5}};
  for (double t : {0.0, 9.99, 14.01, 40.0}) {
    const auto v = g.Velocity(t);
    EXPECT_EQ(v[0], 0.0) << t;
    EXPECT_EQ(v[1], 0.0) << t;
  }
  const auto peak = g.Velocity(12.0);
  EXPECT_DOUBLE_EQ(peak[0], 3.0);
  EXPECT_DOUBLE_EQ(peak[1], -1.0);
  EXPECT_DOUBLE_EQ(peak[2], 0.5);
  EXPECT_NEAR(g.Velocity(11.0)[0], 1.5, 1e-12);  // a quarter in: half the peak
  EXPECT_NEAR(g.Velocity(13.0)[0], 1.5, 1e-12);
  EXPECT_NEAR(g.Velocity(10.5)[0], 3.0 * 0.5 * (1 - std::cos(M_PI / 4)), 1e-12);
  double previous = -1;
  for (double t = 10.0; t <= 12.0; t += 0.01) {  // rising monotonically to the peak
    EXPECT_GE(g.Velocity(t)[0], previous);
    previous = g.Velocity(t)[0];
  }
}

TEST(Drag, ForceAgainstAirspeedAsDocumented) {
  const DragParams d = DragParams::Iris();
  // 4 rotors x omega_hover (794 rad/s) x 8.06428e-5 N s/(m rad).
  EXPECT_NEAR(d.rotor_linear, 0.2561, 0.0005);
  const double calm[3] = {0, 0, 0};
  for (double speed : {0.0, 1.0, 3.0, 6.0, 10.0}) {
    const double v[3] = {speed, 0, 0};
    const auto f = d.Force(v, calm);
    const double expected = -(0.2561 * speed + 0.5 * 1.225 * 0.47 * 0.11 * speed * speed);
    EXPECT_NEAR(f[0], expected, 0.0005 * (1 + speed)) << speed;
    EXPECT_EQ(f[1], 0.0);
    EXPECT_EQ(f[2], 0.0);
  }
  // Hovering in a 6 m/s wind from the west: pushed east, as hard as flying west at 6 m/s.
  const double still[3] = {0, 0, 0}, wind[3] = {6, 0, 0}, west[3] = {-6, 0, 0};
  EXPECT_GT(d.Force(still, wind)[0], 0.0);
  EXPECT_DOUBLE_EQ(d.Force(still, wind)[0], d.Force(west, calm)[0]);
  // Moving with the air: no force.
  EXPECT_EQ(d.Force(wind, wind)[0], 0.0);
  // Vertical: body drag only, on the top area.
  const double up[3] = {0, 0, 2};
  EXPECT_NEAR(d.Force(up, calm)[2], -0.5 * 1.225 * 0.47 * 0.47 * 4, 1e-12);
}

TEST(WindField, CalmMeanGustAndTurbulenceAxes) {
  WindParams calm;
  EXPECT_TRUE(calm.IsCalm());
  WindParams p;
  p.mean = {0, 5, 0};  // from the south: u along world y
  p.gusts.push_back({1.0, 2.0, {0, 0, 2}});
  WindField mean_only(p, 3, 0.01, 1);
  for (int64_t k = 0; k < 400; ++k) {
    const auto& w = mean_only.Update(k);
    const double gust = (k >= 100 && k <= 300) ? 1 - std::cos(2 * M_PI * (k * 0.01 - 1) / 2) : 0;
    for (const auto& v : w) {
      EXPECT_EQ(v[1], 5.0);
      EXPECT_NEAR(v[2], gust, 1e-12);
    }
  }
  p.gusts.clear();
  p.turbulence = true;
  p.dryden.sigma = {2.0, 0.5, 0.0};
  p.dryden.scale_length = {10, 10, 10};
  p.dryden.airspeed = 5;
  WindField field(p, 2, 0.05, 3);
  double var[2][2] = {{0, 0}, {0, 0}};
  const int n = 200000;
  double cross = 0;
  for (int64_t k = 0; k < n; ++k) {
    const auto& w = field.Update(k);
    for (int i = 0; i < 2; ++i) {
      var[i][0] += w[i][0] * w[i][0];
      var[i][1] += (w[i][1] - 5) * (w[i][1] - 5);
    }
    cross += w[0][1] - 5 == w[1][1] - 5;
  }
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(var[i][1] / n, 4.0, 0.4) << "u (along the wind) is world y";
    EXPECT_NEAR(var[i][0] / n, 0.25, 0.025) << "v (across) is world x";
  }
  EXPECT_LT(cross, 10) << "vehicles get independent realisations";
}

// Partly shared turbulence: the stated correlation between vehicles, the variance unchanged.
TEST(WindField, TurbulenceCorrelationBetweenVehicles) {
  WindParams p;
  p.turbulence = true;
  p.dryden.sigma = {2.0, 1.0, 1.0};
  p.dryden.scale_length = {10, 10, 10};
  p.dryden.airspeed = 5;
  p.turbulence_correlation = 0.7;
  WindField field(p, 2, 0.05, 12);
  const int n = 400000;
  double s00 = 0, s11 = 0, s01 = 0;
  for (int64_t k = 0; k < n; ++k) {
    const auto& w = field.Update(k);
    s00 += w[0][0] * w[0][0];
    s11 += w[1][0] * w[1][0];
    s01 += w[0][0] * w[1][0];
  }
  // ~ n dt / (2 tau) = 2000 effective samples: a few percent of scatter.
  EXPECT_NEAR(s00 / n, 4.0, 0.4);
  EXPECT_NEAR(s11 / n, 4.0, 0.4);
  EXPECT_NEAR(s01 / std::sqrt(s00 * s11), 0.7, 0.05);
}

// Turbulence is sampled at turbulence_rate_hz and held in between.
TEST(WindField, TurbulenceIsHeldBetweenSamples) {
  WindParams p;
  p.turbulence = true;
  p.dryden = DrydenParams::LowAltitude(5, 15.4, 3.0);
  p.turbulence_rate_hz = 100.0;  // every 10 steps of 1 ms
  WindField f(p, 1, 0.001, 4);
  std::array<double, 3> previous = f.Update(0)[0];
  for (int64_t k = 1; k < 200; ++k) {
    const auto v = f.Update(k)[0];
    if (k % 10 == 0) {
      EXPECT_NE(v[0], previous[0]) << k;
    } else {
      EXPECT_EQ(v, previous) << k;
    }
    previous = v;
  }
}

TEST(WindField, SameSeedSameBytes) {
  WindParams p;
  p.mean = {3, 1, 0};
  p.turbulence = true;
  p.dryden = DrydenParams::LowAltitude(5, 15.4, 3.2);
  auto record = [&](uint64_t seed) {
    WindField f(p, 4, 0.001, seed);
    std::vector<std::array<double, 3>> out;
    for (int64_t k = 0; k < 2000; ++k) {
      for (const auto& v : f.Update(k)) out.push_back(v);
    }
    return out;
  };
  const auto a = record(8), b = record(8), c = record(9);
  EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])));
  EXPECT_NE(0, std::memcmp(a.data(), c.data(), a.size() * sizeof(a[0])));
}

}  // namespace
}  // namespace mjf::realism
