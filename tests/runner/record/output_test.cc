// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// timeseries.csv's byte promise: the fast number formatter gives exactly std::to_chars'
// (general, 9 significant digits) bytes, on random bit patterns, near-ties, powers of ten and
// their neighbours, and the magnitudes a run records.
#include "mjformation/record/output.hpp"

#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>

namespace mjf::runner {
namespace {

std::string Reference(double v) {
  char buf[64];
  return std::string(buf,
                     std::to_chars(buf, buf + sizeof(buf), v, std::chars_format::general, 9).ptr);
}
std::string Fast(double v) {
  char buf[64];
  return std::string(buf, FormatG9(buf, buf + sizeof(buf), v));
}

TEST(FormatG9Test, MatchesToCharsOnRandomBitPatterns) {
  std::mt19937_64 rng(20261201);
  int checked = 0;
  for (int k = 0; k < 2000000; ++k) {
    const uint64_t bits = rng();
    double v;
    std::memcpy(&v, &bits, sizeof(v));
    if (!std::isfinite(v)) continue;
    ASSERT_EQ(Fast(v), Reference(v)) << "bits " << bits;
    ++checked;
  }
  EXPECT_GT(checked, 1900000);
}

TEST(FormatG9Test, MatchesToCharsOnRecordedMagnitudes) {
  // Positions, velocities, angles, sliding variables: |v| in [1e-12, 1e4], both signs.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> exponent(-12, 4), mantissa(1, 10);
  for (int k = 0; k < 2000000; ++k) {
    const double v = (k % 2 ? -1 : 1) * mantissa(rng) * std::pow(10.0, std::floor(exponent(rng)));
    ASSERT_EQ(Fast(v), Reference(v)) << v;
  }
}

TEST(FormatG9Test, MatchesToCharsOnTiesPowersOfTenAndTheirNeighbours) {
  for (int e = -20; e <= 20; ++e) {
    const double p = std::pow(10.0, e);
    for (double v : {p, std::nextafter(p, 0.0), std::nextafter(p, 1e300), -p}) {
      ASSERT_EQ(Fast(v), Reference(v)) << v;
    }
    // Near-ties at the 9th significant digit: d.dddddddd5 x 10^e and its neighbours.
    for (int d = 0; d < 1000; ++d) {
      const double tie = (1.000000005 + d * 1.37e-6) * p;
      for (double v : {tie, std::nextafter(tie, 0.0), std::nextafter(tie, 1e300)}) {
        ASSERT_EQ(Fast(v), Reference(v)) << v;
      }
    }
  }
  for (double v : {0.0, -0.0, std::numeric_limits<double>::min(),
                   std::numeric_limits<double>::max(), std::numeric_limits<double>::denorm_min()}) {
    EXPECT_EQ(Fast(v), Reference(v)) << v;
  }
}

}  // namespace
}  // namespace mjf::runner
