// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// What the maneuvering (non-cooperative) leaders share: guidance laws whose horizontal
// acceleration command stays, per axis, exactly inside [a_min, a_max] (the paper's Assumption 1,
// u_min <= u_0 <= u_max, Remark 1). No MuJoCo, no plugin ABI: state in, command out.
// Deterministic: the same seed and the same sequence of calls give the same commands.
#ifndef MJFORMATION_GUIDANCE_BOUNDS_HPP_
#define MJFORMATION_GUIDANCE_BOUNDS_HPP_

#include <cstdint>

#include "mjformation/guidance/types.hpp"

namespace mjf::guidance {

// Per-axis acceleration bounds (m/s^2) applied to x and y alike (Assumption 1).
struct AccelBounds {
  double min = -1.0;  // 'a_min'
  double max = 1.0;   // 'a_max'
  // a_min < a_max, both finite; throws std::invalid_argument naming the keys.
  void Validate() const;
  // Also 0 strictly inside: a law that must brake (speed limit, area) needs both signs.
  void ValidateBothSigns(const char* why) const;
  double Clamp(double a) const { return a < min ? min : (a > max ? max : a); }
};

// A uniform number in [0, 1) that depends only on (seed, stream, index) (splitmix64 mixing):
// random signals become pure functions of time, identical whatever the call pattern.
double HashUniform(uint64_t seed, uint64_t stream, uint64_t index);

// A reference (position, velocity, acceleration at t) tracked with the PD law of the circle and
// the command clamped per axis to the bounds: a = clamp(a_ref + kp (p_ref - p) + kd (v_ref - v)).
GuidanceOutput TrackClamped(const GuidanceOutput& reference, const Vec3& pos, const Vec3& vel,
                            const TrackingGains& gains, const AccelBounds& bounds);

}  // namespace mjf::guidance

#endif  // MJFORMATION_GUIDANCE_BOUNDS_HPP_
