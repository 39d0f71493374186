// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/guidance/leaders.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace mjf::guidance {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::string Num(double v) {
  std::ostringstream out;
  out.precision(6);
  out << v;
  return out.str();
}

[[noreturn]] void Refuse(const std::string& message) { throw std::invalid_argument(message); }

void RequireFinite(double v, const char* key) {
  if (!std::isfinite(v)) Refuse(std::string("attribute '") + key + "' must be finite");
}

uint64_t Mix(uint64_t x) {  // splitmix64's finaliser
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// Allowed acceleration toward +: `up` below v_lim - ramp, 0 at v_lim, -down above v_lim + ramp.
double UpperLimit(double v, double v_lim, double up, double down, double ramp) {
  const double x = (v - v_lim) / ramp;  // -1 .. 1 across the ramp
  if (x <= -1.0) return up;
  if (x >= 1.0) return -down;
  return x < 0.0 ? -x * up : -x * down;
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

// ---------------------------------------------------------------------------------------------
// Envelope

Envelope::Envelope(const Config& config, const AccelBounds& bounds)
    : config_(config), bounds_(bounds) {
  bounds.ValidateBothSigns("to brake for the speed limit and the area");
  if (!(config.ramp > 0.0) || !std::isfinite(config.ramp)) {
    Refuse("attribute 'ramp' must be > 0 (got " + Num(config.ramp) + ")");
  }
  if (!(config.speed_max > 2.0 * config.ramp) || !std::isfinite(config.speed_max)) {
    Refuse("attribute 'speed_max' must be > 2 ramp = " + Num(2.0 * config.ramp) + " m/s (got " +
           Num(config.speed_max) + ")");
  }
  const double b = 0.5 * std::min(-bounds.min, bounds.max);  // half the weaker braking
  margin_ = config.ramp * config.ramp / b;
  for (int axis = 0; axis < 2; ++axis) {
    RequireFinite(config.area_min[axis], "area");
    RequireFinite(config.area_max[axis], "area");
    const double width = config.area_max[axis] - config.area_min[axis];
    if (!(width > 4.0 * margin_)) {
      Refuse(std::string("attribute 'area': the ") + (axis == 0 ? "x" : "y") + " extent " +
             Num(width) + " m must exceed 4 x the braking margin ramp^2 / b = " + Num(margin_) +
             " m (b = half the weaker bound) to turn around inside it");
    }
  }
}

std::array<double, 2> Envelope::SpeedLimits(int axis, double p) const {
  // Toward + the vehicle brakes with a_min, toward - with a_max; half of it in the envelope so
  // the ramp can follow the shrinking limit.
  const double gap_up = std::max(config_.area_max[axis] - margin_ - p, 0.0);
  const double gap_down = std::max(p - config_.area_min[axis] - margin_, 0.0);
  return {std::min(config_.speed_max, std::sqrt(2.0 * 0.5 * -bounds_.min * gap_up)),
          std::min(config_.speed_max, std::sqrt(2.0 * 0.5 * bounds_.max * gap_down))};
}

std::array<double, 2> Envelope::Allowed(int axis, double p, double v) const {
  const auto limits = SpeedLimits(axis, p);
  const double ramp = config_.ramp;
  const double hi = UpperLimit(v, limits[0], bounds_.max, -bounds_.min, ramp);
  const double lo = -UpperLimit(-v, limits[1], -bounds_.min, bounds_.max, ramp);
  if (lo > hi) {  // both walls close (only in a box near its minimum size): split the difference
    const double mid = bounds_.Clamp(0.5 * (lo + hi));
    return {mid, mid};
  }
  return {bounds_.Clamp(lo), bounds_.Clamp(hi)};
}

// ---------------------------------------------------------------------------------------------
// random_accel

RandomAccelGuidance::RandomAccelGuidance(const Config& config)
    : config_(config), envelope_(config.envelope, config.bounds) {
  if (!(config.correlation_time > 0.0) || !std::isfinite(config.correlation_time)) {
    Refuse("attribute 'correlation_time' must be > 0 s (got " + Num(config.correlation_time) + ")");
  }
  RequireFinite(config.altitude, "altitude");
  RequireFinite(config.yaw, "yaw");
}

double RandomAccelGuidance::Signal(int axis, double t) const {
  const double x = std::max(t, 0.0) / config_.correlation_time;
  const double k = std::floor(x);
  const uint64_t index = static_cast<uint64_t>(k);
  const double range = config_.bounds.max - config_.bounds.min;
  const double a0 = config_.bounds.min + range * HashUniform(config_.seed, axis, index);
  const double a1 = config_.bounds.min + range * HashUniform(config_.seed, axis, index + 1);
  const double blend = 0.5 * (1.0 - std::cos(kPi * (x - k)));  // in [0, 1], monotone
  return config_.bounds.Clamp(a0 + (a1 - a0) * blend);
}

GuidanceOutput RandomAccelGuidance::Update(double t, const Vec3& pos, const Vec3& vel) const {
  GuidanceOutput out;
  for (int axis = 0; axis < 2; ++axis) {
    const auto allowed = envelope_.Allowed(axis, pos[axis], vel[axis]);
    out.acc[axis] = std::clamp(Signal(axis, t), allowed[0], allowed[1]);
    out.pos[axis] = pos[axis];
    out.vel[axis] = vel[axis];
  }
  out.pos[2] = config_.altitude;
  out.yaw = config_.yaw;
  return out;
}

// ---------------------------------------------------------------------------------------------
// bang_bang

BangBangGuidance::BangBangGuidance(const Config& config)
    : config_(config), envelope_(config.envelope, config.bounds) {
  if (!(config.dwell_min > 0.0) || !std::isfinite(config.dwell_min)) {
    Refuse("attribute 'dwell': the shortest dwell time must be > 0 s (got " +
           Num(config.dwell_min) + ")");
  }
  if (!(config.dwell_max >= config.dwell_min) || !std::isfinite(config.dwell_max)) {
    Refuse("attribute 'dwell': expected 'min max' with min <= max (got " + Num(config.dwell_min) +
           ", " + Num(config.dwell_max) + ")");
  }
  RequireFinite(config.altitude, "altitude");
  RequireFinite(config.yaw, "yaw");
  Reset();
}

double BangBangGuidance::Dwell(int axis, uint64_t index) const {
  return config_.dwell_min +
         (config_.dwell_max - config_.dwell_min) * HashUniform(config_.seed, 16 + axis, index);
}

void BangBangGuidance::Reset() {
  for (int axis = 0; axis < 2; ++axis) {
    sign_[axis] = HashUniform(config_.seed, 32 + axis, 0) < 0.5 ? -1 : 1;
    draws_[axis] = 0;
    switch_time_[axis] = Dwell(axis, draws_[axis]++);
  }
  last_time_ = 0;
}

GuidanceOutput BangBangGuidance::Update(double t, const Vec3& pos, const Vec3& vel) {
  if (t < last_time_) {
    Refuse("bang_bang: time went backwards (" + Num(t) + " < " + Num(last_time_) +
           " s); call Reset() to start again");
  }
  last_time_ = t;
  GuidanceOutput out;
  for (int axis = 0; axis < 2; ++axis) {
    const auto limits = envelope_.SpeedLimits(axis, pos[axis]);
    const double v = vel[axis];
    // A sign is forbidden when the speed toward that side already reaches its limit.
    auto forbidden = [&](int sign) { return sign > 0 ? v >= limits[0] : v <= -limits[1]; };
    while (t >= switch_time_[axis]) {  // dwell over: switch unless the other side is forbidden
      if (!forbidden(-sign_[axis])) sign_[axis] = -sign_[axis];
      switch_time_[axis] += Dwell(axis, draws_[axis]++);
    }
    if (forbidden(sign_[axis]) && !forbidden(-sign_[axis])) {  // envelope: switch now
      sign_[axis] = -sign_[axis];
      switch_time_[axis] = t + Dwell(axis, draws_[axis]++);
    }
    out.acc[axis] = sign_[axis] > 0 ? config_.bounds.max : config_.bounds.min;
    out.pos[axis] = pos[axis];
    out.vel[axis] = vel[axis];
  }
  out.pos[2] = config_.altitude;
  out.yaw = config_.yaw;
  return out;
}

// ---------------------------------------------------------------------------------------------
// Reference tracking, clamped

GuidanceOutput TrackClamped(const GuidanceOutput& reference, const Vec3& pos, const Vec3& vel,
                            const TrackingGains& gains, const AccelBounds& bounds) {
  GuidanceOutput out = reference;
  for (int i = 0; i < 2; ++i) {
    out.acc[i] = bounds.Clamp(reference.acc[i] + gains.kp * (reference.pos[i] - pos[i]) +
                              gains.kd * (reference.vel[i] - vel[i]));
  }
  return out;
}

namespace {
void ValidateTracking(const TrackingGains& g, double altitude, double yaw) {
  if (!(g.kp >= 0) || !(g.kd >= 0) || !std::isfinite(g.kp) || !std::isfinite(g.kd)) {
    Refuse("attributes 'kp', 'kd' must be finite and >= 0");
  }
  RequireFinite(altitude, "altitude");
  RequireFinite(yaw, "yaw");
}
}  // namespace

// ---------------------------------------------------------------------------------------------
// lemniscate

LemniscateGuidance::LemniscateGuidance(const Config& config) : config_(config) {
  config.bounds.Validate();
  ValidateTracking(config.gains, config.altitude, config.yaw);
  RequireFinite(config.omega, "omega");
  RequireFinite(config.phase, "phase");
  RequireFinite(config.center[0], "center");
  RequireFinite(config.center[1], "center");
  if (!(config.half_width > 0.0) || !std::isfinite(config.half_width)) {
    Refuse("attribute 'half_width' must be > 0 m (got " + Num(config.half_width) + ")");
  }
  // Peak reference accelerations: A w^2 on x, 2 A w^2 on y, both signs (sines).
  const double peak = 2.0 * config.half_width * config.omega * config.omega;
  if (!(peak <= config.bounds.max && -peak >= config.bounds.min)) {
    Refuse(
        "attributes 'half_width', 'omega': the figure-eight needs accelerations up to +-2 A "
        "w^2 = +-" +
        Num(peak) + " m/s^2 on y, outside [a_min, a_max] = [" + Num(config.bounds.min) + ", " +
        Num(config.bounds.max) + "]; lower omega or half_width");
  }
}

GuidanceOutput LemniscateGuidance::Reference(double t) const {
  const double a = config_.half_width, w = config_.omega, th = w * t + config_.phase;
  GuidanceOutput out;
  out.pos = {config_.center[0] + a * std::sin(th), config_.center[1] + 0.5 * a * std::sin(2 * th),
             config_.altitude};
  out.vel = {a * w * std::cos(th), a * w * std::cos(2 * th), 0};
  out.acc = {-a * w * w * std::sin(th), -2.0 * a * w * w * std::sin(2 * th), 0};
  out.yaw = config_.yaw;
  return out;
}

GuidanceOutput LemniscateGuidance::Update(double t, const Vec3& pos, const Vec3& vel) const {
  return TrackClamped(Reference(t), pos, vel, config_.gains, config_.bounds);
}

// ---------------------------------------------------------------------------------------------
// HermitePath

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
  const double s = (t - times_[k]) / h, s2 = s * s, s3 = s2 * s;
  // Cubic Hermite basis and its derivatives in s.
  const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2,
               h11 = s3 - s2;
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

// ---------------------------------------------------------------------------------------------
// waypoints

HermitePath WaypointGuidance::Build(const Config& config) {
  config.bounds.Validate();
  ValidateTracking(config.gains, config.altitude, config.yaw);
  if (!(config.speed > 0.0) || !std::isfinite(config.speed)) {
    Refuse("attribute 'speed' must be > 0 m/s (got " + Num(config.speed) + ")");
  }
  if (config.points.size() < 2) Refuse("attribute 'points': at least two waypoints 'x y' needed");
  std::vector<Vec3> points;
  for (const auto& p : config.points) {
    RequireFinite(p[0], "points");
    RequireFinite(p[1], "points");
    points.push_back({p[0], p[1], config.altitude});
  }
  if (config.loop) points.push_back(points.front());
  std::vector<double> times = {0.0};
  for (size_t k = 1; k < points.size(); ++k) {
    const double length =
        std::hypot(points[k][0] - points[k - 1][0], points[k][1] - points[k - 1][1]);
    if (!(length > 0.0)) {
      Refuse("attribute 'points': waypoints " + std::to_string(k - 1) + " and " +
             std::to_string(k % config.points.size()) + " coincide");
    }
    times.push_back(times.back() + length / config.speed);
  }
  HermitePath path(times, points, CatmullRomVelocities(times, points, config.loop), config.loop);
  // The acceleration is linear on each segment: its extremes are at the knots (exact check).
  for (size_t k = 0; k < path.segments(); ++k) {
    for (const Vec3& a : path.SegmentAcc(k)) {
      for (int i = 0; i < 2; ++i) {
        if (a[i] > config.bounds.max || a[i] < config.bounds.min) {
          Refuse("attribute 'points': waypoints " + std::to_string(k) + " -> " +
                 std::to_string((k + 1) % config.points.size()) +
                 " are too close for the bounds at 'speed' = " + Num(config.speed) +
                 " m/s: the smooth path needs a_" + (i == 0 ? "x" : "y") + " = " + Num(a[i]) +
                 " m/s^2, outside [a_min, a_max] = [" + Num(config.bounds.min) + ", " +
                 Num(config.bounds.max) + "]; space them further apart or lower 'speed'");
        }
      }
    }
  }
  return path;
}

WaypointGuidance::WaypointGuidance(const Config& config) : config_(config), path_(Build(config)) {}

GuidanceOutput WaypointGuidance::Update(double t, const Vec3& pos, const Vec3& vel) const {
  GuidanceOutput ref = path_.Evaluate(t);
  ref.pos[2] = config_.altitude;
  ref.vel[2] = ref.acc[2] = 0.0;
  ref.yaw = config_.yaw;
  return TrackClamped(ref, pos, vel, config_.gains, config_.bounds);
}

// ---------------------------------------------------------------------------------------------
// trajectory

TrajectoryTable ReadTrajectoryCsv(const std::string& path) {
  std::ifstream in(path);
  if (!in) Refuse("attribute 'file': cannot read '" + path + "'");
  TrajectoryTable table;
  std::string line;
  int line_no = 0, columns = 0;
  bool header_allowed = true;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    std::vector<std::string> cells;
    std::stringstream row(line);
    std::string cell;
    while (std::getline(row, cell, ',')) cells.push_back(cell);
    const std::string where = "attribute 'file': " + path + ":" + std::to_string(line_no) + ": ";
    std::vector<double> values;
    bool numeric = true;
    for (const auto& c : cells) {
      char* end = nullptr;
      const double v = std::strtod(c.c_str(), &end);
      while (end && (*end == ' ' || *end == '\t')) ++end;
      if (end == c.c_str() || *end != '\0') {
        numeric = false;
        break;
      }
      values.push_back(v);
    }
    if (!numeric) {
      if (header_allowed) {  // the first non-comment line may name the columns
        header_allowed = false;
        continue;
      }
      Refuse(where + "expected numbers t,x,y[,z], got '" + line + "'");
    }
    header_allowed = false;
    if (values.size() != 3 && values.size() != 4) {
      Refuse(where + "expected 3 (t,x,y) or 4 (t,x,y,z) columns, got " +
             std::to_string(values.size()));
    }
    if (columns == 0) columns = static_cast<int>(values.size());
    if (static_cast<int>(values.size()) != columns) {
      Refuse(where + "expected " + std::to_string(columns) + " columns like the first row, got " +
             std::to_string(values.size()));
    }
    for (double v : values) {
      if (!std::isfinite(v)) Refuse(where + "a value is not finite (NaN or inf)");
    }
    if (!table.t.empty() && !(values[0] > table.t.back())) {
      Refuse(where + "t = " + Num(values[0]) + " is not after the previous row's t = " +
             Num(table.t.back()) + " (t must be strictly increasing)");
    }
    table.t.push_back(values[0]);
    table.pos.push_back({values[1], values[2], columns == 4 ? values[3] : 0.0});
  }
  if (table.t.size() < 2) {
    Refuse("attribute 'file': " + path + ": at least two rows t,x,y[,z] are needed (got " +
           std::to_string(table.t.size()) + ")");
  }
  table.has_z = columns == 4;
  return table;
}

TrajectoryGuidance::TrajectoryGuidance(const Config& config, const TrajectoryTable& table)
    : config_(config),
      has_z_(table.has_z),
      path_(table.t, table.pos, CatmullRomVelocities(table.t, table.pos, false), false) {
  config.bounds.Validate();
  ValidateTracking(config.gains, config.altitude, config.yaw);
  RequireFinite(config.time_offset, "time_offset");
}

GuidanceOutput TrajectoryGuidance::Reference(double t) const {
  GuidanceOutput ref = path_.Evaluate(t + config_.time_offset);
  if (!has_z_) {
    ref.pos[2] = config_.altitude;
    ref.vel[2] = ref.acc[2] = 0.0;
  }
  ref.yaw = config_.yaw;
  return ref;
}

GuidanceOutput TrajectoryGuidance::Update(double t, const Vec3& pos, const Vec3& vel) const {
  return TrackClamped(Reference(t), pos, vel, config_.gains, config_.bounds);
}

}  // namespace mjf::guidance
