// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/guidance/hermite_path.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "check.hpp"
#include "mjformation/cubic_hermite.hpp"

namespace mjf::guidance {

using check::Refuse;

HermitePath::HermitePath(std::vector<double> times, std::vector<Vec3> positions,
                         std::vector<Vec3> velocities, bool periodic)
    : times_(std::move(times)),
      pos_(std::move(positions)),
      vel_(std::move(velocities)),
      periodic_(periodic) {
  if (times_.size() < 2 || pos_.size() != times_.size() || vel_.size() != times_.size()) {
    Refuse("a path needs at least two timed points");
  }
  for (size_t k = 1; k < times_.size(); ++k) {
    if (!(times_[k] > times_[k - 1])) Refuse("path times must be strictly increasing");
  }
}

std::array<Vec3, 2> HermitePath::SegmentAcc(size_t k) const {
  const double h = times_[k + 1] - times_[k];
  std::array<Vec3, 2> acc{};
  for (int i = 0; i < 3; ++i) {
    const double dp = pos_[k + 1][i] - pos_[k][i];
    const double m0 = vel_[k][i], m1 = vel_[k + 1][i];
    acc[0][i] = (6.0 * dp - h * (4.0 * m0 + 2.0 * m1)) / (h * h);   // p''(s = 0)
    acc[1][i] = (-6.0 * dp + h * (2.0 * m0 + 4.0 * m1)) / (h * h);  // p''(s = 1)
  }
  return acc;
}

std::array<double, 3> HermitePath::max_acc() const {
  std::array<double, 3> m{0, 0, 0};  // the path holds its ends at rest: 0 is attained
  for (size_t k = 0; k < segments(); ++k) {
    for (const Vec3& a : SegmentAcc(k)) {
      for (int i = 0; i < 3; ++i) m[i] = std::max(m[i], a[i]);
    }
  }
  return m;
}

std::array<double, 3> HermitePath::min_acc() const {
  std::array<double, 3> m{0, 0, 0};
  for (size_t k = 0; k < segments(); ++k) {
    for (const Vec3& a : SegmentAcc(k)) {
      for (int i = 0; i < 3; ++i) m[i] = std::min(m[i], a[i]);
    }
  }
  return m;
}

GuidanceOutput HermitePath::Evaluate(double t) const {
  GuidanceOutput out;
  const double t0 = times_.front(), t1 = times_.back();
  if (periodic_) {
    t = t0 + std::fmod(t - t0, t1 - t0);
    if (t < t0) t += t1 - t0;
  }
  if (t <= t0 || t >= t1) {  // hold an end, at rest
    out.pos = t <= t0 ? pos_.front() : pos_.back();
    return out;
  }
  const size_t k =
      static_cast<size_t>(std::upper_bound(times_.begin(), times_.end(), t) - times_.begin()) - 1;
  const double h = times_[k + 1] - times_[k];
  const double s = (t - times_[k]) / h, s2 = s * s;
  // Cubic Hermite basis and its derivatives in s.
  const auto [h00, h10, h01, h11] = CubicHermite(s);
  const double d00 = 6 * s2 - 6 * s, d10 = 3 * s2 - 4 * s + 1, d01 = -6 * s2 + 6 * s,
               d11 = 3 * s2 - 2 * s;
  const double e00 = 12 * s - 6, e10 = 6 * s - 4, e01 = -12 * s + 6, e11 = 6 * s - 2;
  for (int i = 0; i < 3; ++i) {
    const double p0 = pos_[k][i], p1 = pos_[k + 1][i], m0 = h * vel_[k][i], m1 = h * vel_[k + 1][i];
    out.pos[i] = h00 * p0 + h10 * m0 + h01 * p1 + h11 * m1;
    out.vel[i] = (d00 * p0 + d10 * m0 + d01 * p1 + d11 * m1) / h;
    out.acc[i] = (e00 * p0 + e10 * m0 + e01 * p1 + e11 * m1) / (h * h);
  }
  return out;
}

std::vector<Vec3> CatmullRomVelocities(const std::vector<double>& times,
                                       const std::vector<Vec3>& points, bool periodic) {
  const size_t n = points.size();
  std::vector<Vec3> vel(n, Vec3{0, 0, 0});
  for (size_t k = 0; k < n; ++k) {
    if (k == 0 || k + 1 == n) {
      if (!periodic) continue;  // at rest at both ends
      // Periodic: the first and last points coincide; both get the tangent across the seam.
      const double dt = (times[1] - times[0]) + (times[n - 1] - times[n - 2]);
      for (int i = 0; i < 3; ++i) vel[k][i] = (points[1][i] - points[n - 2][i]) / dt;
      continue;
    }
    for (int i = 0; i < 3; ++i) {
      vel[k][i] = (points[k + 1][i] - points[k - 1][i]) / (times[k + 1] - times[k - 1]);
    }
  }
  return vel;
}

}  // namespace mjf::guidance
