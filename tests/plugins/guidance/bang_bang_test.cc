// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// bang_bang: always at a bound, inside the speed limit and the area, deterministic, and bad
// dwell times or bounds refused.
#include "mjformation/guidance/bang_bang.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "guidance_util.hpp"

namespace mjf::guidance {
namespace {

using test::Fly;
using test::Stats;

BangBangGuidance::Config BangConfig(uint64_t seed) {
  BangBangGuidance::Config c;
  c.bounds = {-1.0, 1.0};
  c.dwell_min = 0.5;
  c.dwell_max = 3.0;
  c.envelope.speed_max = 3.0;
  c.envelope.area_min = {-40, -40};
  c.envelope.area_max = {40, 40};
  c.seed = seed;
  return c;
}

TEST(BangBangTest, AlwaysAtABoundAndInsideSpeedAndArea) {
  for (uint64_t seed : {1u, 5u, 99u}) {
    BangBangGuidance law(BangConfig(seed));
    const double dt = 0.001;
    const Stats s = Fly([&](double t, const Vec3& p, const Vec3& v) { return law.Update(t, p, v); },
                        {0, 0, 5}, dt, 1000.0);
    int switches = 0, at_min = 0;
    for (size_t k = 0; k < s.ax.size(); ++k) {
      ASSERT_TRUE(s.ax[k] == -1.0 || s.ax[k] == 1.0) << s.ax[k] << " at step " << k;
      if (k > 0 && s.ax[k] != s.ax[k - 1]) ++switches;
      at_min += s.ax[k] < 0;
    }
    // Dwell times average 1.75 s: about 570 switches in 1000 s (envelope switches add some).
    EXPECT_GT(switches, 300) << "seed " << seed;
    EXPECT_LT(switches, 2000) << "seed " << seed;
    EXPECT_GT(at_min, static_cast<int>(0.3 * s.ax.size()));
    EXPECT_LT(at_min, static_cast<int>(0.7 * s.ax.size()));
    for (int i = 0; i < 2; ++i) {
      EXPECT_GE(s.p_min[i], -40.0);
      EXPECT_LE(s.p_max[i], 40.0);
    }
    EXPECT_LE(s.speed_max, 3.0 + 2 * dt) << "seed " << seed;  // switches as the limit is reached
  }
}

TEST(BangBangTest, DeterministicResetAndTimeMustNotGoBack) {
  BangBangGuidance a(BangConfig(3)), b(BangConfig(3));
  auto fly = [](BangBangGuidance& law) {
    return Fly([&](double t, const Vec3& p, const Vec3& v) { return law.Update(t, p, v); },
               {0, 0, 5}, 0.01, 300.0)
        .ax;
  };
  const auto first = fly(a);
  EXPECT_EQ(first, fly(b));
  EXPECT_THROW(a.Update(1.0, {0, 0, 5}, {0, 0, 0}), std::invalid_argument);
  a.Reset();
  EXPECT_EQ(first, fly(a));
  BangBangGuidance c(BangConfig(4));
  EXPECT_NE(first, fly(c));
}

TEST(BangBangTest, BadDwellAndBoundsRefused) {
  auto refused = [](BangBangGuidance::Config c, const std::string& key) {
    try {
      BangBangGuidance law(c);
      ADD_FAILURE() << "accepted, expected a complaint about " << key;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  };
  auto c = BangConfig(1);
  c.dwell_min = 0;
  refused(c, "dwell");
  c.dwell_min = -1;
  refused(c, "dwell");
  c = BangConfig(1);
  c.dwell_max = 0.1;  // < dwell_min
  refused(c, "dwell");
  c = BangConfig(1);
  c.bounds = {2.0, -2.0};
  refused(c, "a_max");
}

}  // namespace
}  // namespace mjf::guidance
