// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/guidance/bounds.hpp"

#include <cmath>
#include <cstdint>
#include <string>

#include "check.hpp"

namespace mjf::guidance {

using check::Num;
using check::Refuse;

namespace {

uint64_t Mix(uint64_t x) {  // splitmix64's finaliser
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

}  // namespace

void AccelBounds::Validate() const {
  if (!std::isfinite(min) || !std::isfinite(max))
    Refuse("attributes 'a_min', 'a_max' must be finite");
  if (!(min < max)) {
    Refuse(
        "attributes 'a_min', 'a_max': a_min < a_max is required (Assumption 1: u_min <= u_0 <= "
        "u_max with a non-empty range) (got a_min = " +
        Num(min) + ", a_max = " + Num(max) + ")");
  }
}

void AccelBounds::ValidateBothSigns(const char* why) const {
  Validate();
  if (!(min < 0.0 && max > 0.0)) {
    Refuse(std::string("attributes 'a_min', 'a_max': a_min < 0 < a_max is required ") + why +
           " (got a_min = " + Num(min) + ", a_max = " + Num(max) + ")");
  }
}

double HashUniform(uint64_t seed, uint64_t stream, uint64_t index) {
  const uint64_t x = Mix(Mix(Mix(seed) ^ (stream * 0xD1B54A32D192ED03ull)) ^ index);
  return static_cast<double>(x >> 11) * (1.0 / 9007199254740992.0);  // 53 bits -> [0, 1)
}

GuidanceOutput TrackClamped(const GuidanceOutput& reference, const Vec3& pos, const Vec3& vel,
                            const TrackingGains& gains, const AccelBounds& bounds) {
  GuidanceOutput out = reference;
  for (int i = 0; i < 2; ++i) {
    out.acc[i] = bounds.Clamp(reference.acc[i] + gains.kp * (reference.pos[i] - pos[i]) +
                              gains.kd * (reference.vel[i] - vel[i]));
  }
  return out;
}

}  // namespace mjf::guidance
