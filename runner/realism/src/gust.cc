// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/realism/gust.hpp"

#include <cmath>

namespace mjf::realism {

std::array<double, 3> OneCosineGust::Velocity(double t) const {
  const double x = t - start;
  if (x < 0 || x > duration) return {0, 0, 0};
  const double shape = 0.5 * (1 - std::cos(2 * M_PI * x / duration));
  return {amplitude[0] * shape, amplitude[1] * shape, amplitude[2] * shape};
}

}  // namespace mjf::realism
