// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// random_accel: a maneuvering leader with a smooth seeded random acceleration.
#ifndef MJFORMATION_GUIDANCE_RANDOM_ACCEL_HPP_
#define MJFORMATION_GUIDANCE_RANDOM_ACCEL_HPP_

#include <cstdint>

#include "mjformation/guidance/bounds.hpp"
#include "mjformation/guidance/envelope.hpp"

namespace mjf::guidance {

// A smooth random acceleration per axis. Knots every `correlation_time` seconds hold uniform
// values in [a_min, a_max] (fill the bounds); between knots a cosine blend
// a = a_k + (a_k+1 - a_k) (1 - cos(pi u)) / 2 is monotone, so the signal never leaves the knots'
// range and is C1 (band-limited to about 1 / (2 correlation_time) Hz). The envelope then clips
// it to keep the speed limit and the area.
class RandomAccelGuidance {
 public:
  struct Config {
    AccelBounds bounds;
    Envelope::Config envelope;
    double correlation_time = 2.0;  // 'correlation_time', s, knot spacing (> 0)
    uint64_t seed = 1;              // 'seed'
    double altitude = 5.0;          // m
    double yaw = 0.0;               // rad
  };
  explicit RandomAccelGuidance(const Config& config);
  // The unclipped random signal on one axis at time t (s): inside [a_min, a_max].
  double Signal(int axis, double t) const;
  GuidanceOutput Update(double t, const Vec3& pos, const Vec3& vel) const;
  template <typename Visit>
  void VisitState(Visit&) {}  // no state: its knots are drawn from (seed, index), a function of t

 private:
  Config config_;
  Envelope envelope_;
};

}  // namespace mjf::guidance

#endif  // MJFORMATION_GUIDANCE_RANDOM_ACCEL_HPP_
