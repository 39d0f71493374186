// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The cubic Hermite basis on one interval, s in [0, 1]: p(s) = h00 p0 + h10 m0 + h01 p1 + h11 m1
// with m = h v the end tangents scaled by the interval length h. The guidance plugins' timed
// paths (hermite_path.cc) and the formation's sampled shape tables (shape.cc) both interpolate
// with it. Header-only and plain C++, like euler_zyx.hpp.
#ifndef MJFORMATION_CUBIC_HERMITE_HPP_
#define MJFORMATION_CUBIC_HERMITE_HPP_

namespace mjf {

// The four basis polynomials at s, or their first or second derivative in s.
struct HermiteBasis {
  double h00, h10, h01, h11;
};

// h00 = 2s^3 - 3s^2 + 1, h10 = s^3 - 2s^2 + s, h01 = -2s^3 + 3s^2, h11 = s^3 - s^2, summed from
// s^2 and s^3 (the guidance paths, hermite_path.cc, which reuses s^2 for the derivatives).
inline HermiteBasis CubicHermite(double s) {
  const double s2 = s * s, s3 = s2 * s;
  return {2 * s3 - 3 * s2 + 1, s3 - 2 * s2 + s, -2 * s3 + 3 * s2, s3 - s2};
}

// The same four polynomials in Horner form (the formation's sampled shape tables, shape.cc).
// Two forms remain because they round differently in the last bit, and each caller's recorded
// runs were made with its own: one form for both moved a leader trajectory run
// (experiments/leaders/exp2_trajectory.toml, 1e-7 m in the printed slot) or a shape-table run
// (1e-11 in the printed yaw), so unifying them is a change of results, not a tidy-up.
inline HermiteBasis CubicHermiteHorner(double s) {
  return {(2 * s - 3) * s * s + 1, ((s - 2) * s + 1) * s, (3 - 2 * s) * s * s, (s - 1) * s * s};
}

}  // namespace mjf

#endif  // MJFORMATION_CUBIC_HERMITE_HPP_
