// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// What the guidance law tests share: a law flown on an ideal double integrator (exact zero-order
// hold) with the extremes of its command, position and speed, and a temporary file.
#ifndef MJFORMATION_TESTS_PLUGINS_SUPPORT_GUIDANCE_UTIL_HPP_
#define MJFORMATION_TESTS_PLUGINS_SUPPORT_GUIDANCE_UTIL_HPP_

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "mjformation/guidance/types.hpp"

namespace mjf::guidance::test {

constexpr double kPi = 3.14159265358979323846;

struct Stats {
  std::array<double, 2> a_min{1e9, 1e9}, a_max{-1e9, -1e9};
  std::array<double, 2> p_min{1e9, 1e9}, p_max{-1e9, -1e9};
  double speed_max = 0;    // largest |v| on any axis
  double max_jump = 0;     // largest |a(k+1) - a(k)| on any axis
  std::vector<double> ax;  // the x command per step
};

// Integrates p, v exactly over steps of dt with the law's command held (zero-order hold).
inline Stats Fly(const std::function<GuidanceOutput(double, const Vec3&, const Vec3&)>& law,
                 Vec3 pos, double dt, double duration) {
  Stats s;
  Vec3 vel{0, 0, 0};
  std::array<double, 2> last{0, 0};
  const long steps = std::lround(duration / dt);
  for (long k = 0; k < steps; ++k) {
    const GuidanceOutput out = law(k * dt, pos, vel);
    for (int i = 0; i < 2; ++i) {
      const double a = out.acc[i];
      s.a_min[i] = std::min(s.a_min[i], a);
      s.a_max[i] = std::max(s.a_max[i], a);
      if (k > 0) s.max_jump = std::max(s.max_jump, std::abs(a - last[i]));
      last[i] = a;
      pos[i] += dt * vel[i] + 0.5 * dt * dt * a;
      vel[i] += dt * a;
      s.p_min[i] = std::min(s.p_min[i], pos[i]);
      s.p_max[i] = std::max(s.p_max[i], pos[i]);
      s.speed_max = std::max(s.speed_max, std::abs(vel[i]));
    }
    s.ax.push_back(out.acc[0]);
  }
  return s;
}

inline std::string WriteTemp(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "/" + name;
  std::ofstream(path) << text;
  return path;
}

}  // namespace mjf::guidance::test

#endif  // MJFORMATION_TESTS_PLUGINS_SUPPORT_GUIDANCE_UTIL_HPP_
