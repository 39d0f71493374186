// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// random_accel on an ideal double integrator: the command never leaves [a_min, a_max] over
// long seeded runs, the speed limit and the area hold, same seed same commands, and bad input
// is refused naming the attribute.
#include "mjformation/guidance/random_accel.hpp"

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
using test::kPi;
using test::Stats;

RandomAccelGuidance::Config RandomConfig(uint64_t seed) {
  RandomAccelGuidance::Config c;
  c.bounds = {-0.8, 1.2};  // asymmetric on purpose
  c.envelope.speed_max = 3.0;
  c.envelope.area_min = {-30, -20};
  c.envelope.area_max = {30, 20};
  c.seed = seed;
  return c;
}

TEST(RandomAccelTest, StaysInsideBoundsSpeedAndAreaOverLongSeededRuns) {
  for (uint64_t seed : {1u, 2u, 3u, 42u, 1234u}) {
    const RandomAccelGuidance law(RandomConfig(seed));
    const Stats s = Fly([&](double t, const Vec3& p, const Vec3& v) { return law.Update(t, p, v); },
                        {0, 0, 5}, 0.01, 3000.0);
    for (int i = 0; i < 2; ++i) {
      EXPECT_GE(s.a_min[i], -0.8) << "seed " << seed;
      EXPECT_LE(s.a_max[i], 1.2) << "seed " << seed;
      // It fills the bounds: over 1500 knots both ends are approached.
      EXPECT_LT(s.a_min[i], -0.7) << "seed " << seed;
      EXPECT_GT(s.a_max[i], 1.1) << "seed " << seed;
    }
    EXPECT_GE(s.p_min[0], -30.0);
    EXPECT_LE(s.p_max[0], 30.0);
    EXPECT_GE(s.p_min[1], -20.0);
    EXPECT_LE(s.p_max[1], 20.0);
    // It uses the room: a random walk confined by the envelope reaches near the walls.
    EXPECT_GT(s.p_max[0] - s.p_min[0], 40.0) << "seed " << seed;
    // The speed may pass the limit by at most the ramp (the envelope's band) plus one step.
    EXPECT_LE(s.speed_max, 3.0 + 0.3 + 0.02) << "seed " << seed;
    // Band-limited: the cosine blend's slope is at most pi (a_max - a_min) / (2 tau) per second;
    // the envelope adds at most its own ramp slope (bounds / ramp x |dv| per step).
    const double signal_slope = kPi * 2.0 / (2 * 2.0);
    const double envelope_step = 2.0 / 0.3 * 1.2 * 0.01 + 2.0 / 0.3 * 0.01 * 3.0 / 0.05;
    EXPECT_LE(s.max_jump, signal_slope * 0.01 + envelope_step) << "seed " << seed;
  }
}

TEST(RandomAccelTest, SameSeedSameCommandsOtherSeedOtherCommands) {
  const RandomAccelGuidance a(RandomConfig(7)), b(RandomConfig(7)), c(RandomConfig(8));
  auto fly = [](const RandomAccelGuidance& law) {
    return Fly([&](double t, const Vec3& p, const Vec3& v) { return law.Update(t, p, v); },
               {1, 2, 5}, 0.01, 200.0)
        .ax;
  };
  const auto xa = fly(a), xb = fly(b), xc = fly(c);
  EXPECT_EQ(xa, xb);  // bit for bit
  EXPECT_NE(xa, xc);
  // A pure function of time: evaluating out of order gives the same values.
  EXPECT_EQ(a.Signal(0, 17.3), a.Signal(0, 17.3));
  const double late = a.Signal(1, 99.0);
  (void)a.Signal(1, 3.0);
  EXPECT_EQ(a.Signal(1, 99.0), late);
}

TEST(RandomAccelTest, BadInputRefusedNamingTheKey) {
  auto refused = [](RandomAccelGuidance::Config c, const std::string& key) {
    try {
      RandomAccelGuidance law(c);
      ADD_FAILURE() << "accepted, expected a complaint about " << key;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  };
  auto c = RandomConfig(1);
  c.bounds = {1.0, 1.0};
  refused(c, "a_min");  // a_min >= a_max
  c.bounds = {0.5, 1.0};
  refused(c, "a_min");  // cannot brake
  c = RandomConfig(1);
  c.correlation_time = 0;
  refused(c, "correlation_time");
  c = RandomConfig(1);
  c.envelope.area_max = {-29.9, 20};
  refused(c, "area");
  c = RandomConfig(1);
  c.envelope.speed_max = 0.1;
  refused(c, "speed_max");
}

}  // namespace
}  // namespace mjf::guidance
