// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// A discrete "1 - cosine" gust (MIL-F-8785C 3.7.3 / MIL-HDBK-1797 discrete gust, in time rather
// than distance): it rises from zero to its peak over half its duration and falls back to zero.
#ifndef MJFORMATION_REALISM_GUST_HPP_
#define MJFORMATION_REALISM_GUST_HPP_

#include <array>

namespace mjf::realism {

struct OneCosineGust {
  double start = 0.0;                 // s, gust onset
  double duration = 1.0;              // s, > 0; the peak is at start + duration / 2
  std::array<double, 3> amplitude{};  // m/s, world frame, the peak velocity

  // v(t) = (A / 2) (1 - cos(2 pi (t - start) / duration)) for start <= t <= start + duration,
  // zero outside.
  std::array<double, 3> Velocity(double t) const;
};

}  // namespace mjf::realism

#endif  // MJFORMATION_REALISM_GUST_HPP_
