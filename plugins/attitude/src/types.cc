// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/attitude/types.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "mjformation/euler_zyx.hpp"

namespace mjf::attitude {

Vec3 EulerZYX(const std::array<double, 4>& q) {
  const std::array<double, 3> e = mjf::EulerZYX(q.data());
  return {e[0], e[1], e[2]};
}

double WrapPi(double angle) {
  const double two_pi = 2 * M_PI;
  double a = angle + M_PI;
  // fmod is exact, so for a already in [0, 2 pi) it returns a itself: the libm call is needed
  // only outside that range (NaN and infinities included), and the bits are the same.
  if (!(a >= 0 && a < two_pi)) a = std::fmod(a, two_pi);
  if (a < 0) a += two_pi;
  return a - M_PI;
}

double AuthorityAttitudeBandwidth(double alpha, double tilt_max) {
  if (!(alpha > 0) || !std::isfinite(alpha) || !(tilt_max > 0)) return INFINITY;
  return std::sqrt(alpha / tilt_max);
}

double AuthorityTiltLimit(double alpha, double nominal_tilt) {
  if (!(alpha > 0) || !std::isfinite(alpha)) return nominal_tilt;
  return std::min(nominal_tilt, alpha / (kMinAttitudeBandwidth * kMinAttitudeBandwidth));
}

void RequirePositive(double value, const char* what) {
  if (!(value > 0) || !std::isfinite(value)) {
    throw std::invalid_argument(std::string(what) + " must be positive and finite (got " +
                                std::to_string(value) + ")");
  }
}

void RequireNonNegative(double value, const char* what) {
  if (!(value >= 0) || !std::isfinite(value)) {
    throw std::invalid_argument(std::string(what) + " must be >= 0 and finite (got " +
                                std::to_string(value) + ")");
  }
}

}  // namespace mjf::attitude
