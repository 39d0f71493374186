// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// lemniscate: the figure-eight inside the bounds; too fast refused.
#include "mjformation/guidance/lemniscate.hpp"

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

TEST(LemniscateTest, FigureEightInsideBoundsAndTooFastRefused) {
  LemniscateGuidance::Config c;
  c.half_width = 20;
  c.omega = 0.15;  // peak 2 A w^2 = 0.9
  const LemniscateGuidance law(c);
  // On the reference the command is the reference acceleration; it crosses the centre twice.
  const GuidanceOutput r = law.Reference(kPi / 2 / 0.15);
  EXPECT_NEAR(r.pos[0], 20.0, 1e-9);
  EXPECT_NEAR(r.pos[1], 0.0, 1e-9);
  EXPECT_NEAR(r.acc[0], -20 * 0.15 * 0.15, 1e-12);
  const Stats s = Fly([&](double t, const Vec3& p, const Vec3& v) { return law.Update(t, p, v); },
                      {0, -10, 5}, 0.01, 300.0);
  for (int i = 0; i < 2; ++i) {
    EXPECT_GE(s.a_min[i], -1.0);
    EXPECT_LE(s.a_max[i], 1.0);
  }
  EXPECT_NEAR(s.p_max[0], 20.0, 0.5);  // converged onto the figure-eight
  c.omega = 0.2;                       // 2 A w^2 = 1.6 > 1
  try {
    LemniscateGuidance fast(c);
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("omega"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace mjf::guidance
