// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/record/safety_events.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace mjf::runner {
namespace {

std::string VehicleName(int v) { return v == 0 ? "leader" : fmt::format("follower {}", v); }

// Cosine of the tilt of the body z axis from the world's: R_zz = 1 - 2 (x^2 + y^2) for
// q = (w, x, y, z).
double CosTilt(const double q[4]) {
  return std::clamp(1 - 2 * (q[1] * q[1] + q[2] * q[2]), -1.0, 1.0);
}

// The tilt in degrees from its cosine.
double TiltDeg(double cos_tilt) { return std::acos(cos_tilt) * 180.0 / M_PI; }

// How far p lies outside the box (0 inside).
double DistanceOutside(const std::array<double, 6>& box, const double p[3]) {
  double d2 = 0;
  for (int a = 0; a < 3; ++a) {
    const double out = std::max({box[2 * a] - p[a], p[a] - box[2 * a + 1], 0.0});
    d2 += out * out;
  }
  return std::sqrt(d2);
}

}  // namespace

std::string DescribeEvent(const SafetyEvent& e) {
  const std::string who = VehicleName(e.vehicles.at(0));
  const std::string pair = e.vehicles.size() > 1 ? who + " and " + VehicleName(e.vehicles[1]) : who;
  if (e.kind == "flip") {
    return fmt::format("{} flipped at {:.2f} s (tilt {:.1f} deg)", who, e.time_s, e.value);
  }
  if (e.kind == "ground_impact") {
    return fmt::format("{} hit the ground at {:.2f} s (z = {:.3f} m)", who, e.time_s, e.value);
  }
  if (e.kind == "collision") {
    return fmt::format("{} collided at {:.2f} s (separation {:.3f} m)", pair, e.time_s, e.value);
  }
  if (e.kind == "near_miss") {
    return fmt::format(
        "{} nearly collided at {:.2f} s (separation {:.3f} m, {:.3f} m between "
        "their bounding spheres)",
        pair, e.time_s, e.value, e.clearance);
  }
  return fmt::format("{} left the region at {:.2f} s ({:.3f} m outside)", who, e.time_s, e.value);
}

SafetyMonitor::SafetyMonitor(const SafetyConfig& config, std::vector<double> radii)
    : config_(config), radii_(std::move(radii)), airborne_(radii_.size(), 0) {
  for (double r : radii_) max_radius_ = std::max(max_radius_, r);
  // A pair is an event when its clearance d - r_i - r_j is below the near-miss margin (or 0), so
  // only at d < reach_. A squared distance above reach_^2 (1 + 1e-6) puts the distance above
  // reach_ by 5e-7 of it, far more than the few ulps by which the square, its root and the
  // clearance can err: ScanPairs skips the root there, and the events are the same.
  reach_ = config_.near_miss_m + 2 * max_radius_;
  skip_squared_ = reach_ * reach_ * (1 + 1e-6);
  // A tilt's cosine at or above this leaves the tilt below flip_tilt_deg (in (0, 180], checked
  // by the config): acos falls with slope at least 1, so the 1e-9 margin keeps the tilt at
  // least 1e-9 rad below the limit, far beyond the few ulps by which acos, the degrees and this
  // cosine can err. Below it (or with no finite cosine) the tilt is computed and compared.
  flip_cos_skip_ = std::cos(config_.flip_tilt_deg * M_PI / 180.0) + 1e-9;
  for (size_t i = 0; i < radii_.size(); ++i) order_.emplace_back(0.0, static_cast<int>(i));
  found_.assign(radii_.size(), 0);
  tilt_.assign(radii_.size(), 0.0);
  outside_.assign(radii_.size(), 0.0);
  pair_hits_.resize(radii_.size());
  range_count_.assign(radii_.size(), 0);
}

void SafetyMonitor::Report(const std::string& kind, double t, std::vector<int> vehicles,
                           double value, double clearance) {
  const int other = vehicles.size() > 1 ? vehicles[1] : -1;
  if (!seen_.insert({kind, vehicles[0], other}).second) return;  // once per kind and vehicles
  ++total_;
  if (events_.size() < kMaxListed) {
    events_.push_back({kind, t, std::move(vehicles), value, clearance});
  }
}

// Flip, ground impact (the bounding sphere reaches z = 0 after the vehicle was above it) and
// leaving the region: found here, reported by Finish. Touches vehicle i's entries only.
void SafetyMonitor::ScanVehicle(int i, const mjfVehicleState& s) {
  char found = 0;
  const double cos_tilt = CosTilt(s.quat);
  if (!(cos_tilt >= flip_cos_skip_)) {  // the libm call only where a flip is possible
    const double tilt = TiltDeg(cos_tilt);
    if (tilt > config_.flip_tilt_deg) {
      found |= kFlip;
      tilt_[i] = tilt;
    }
  }
  const double clearance = s.pos[2] - radii_[i];
  if (clearance > 0) airborne_[i] = 1;
  if (airborne_[i] && clearance <= 0) found |= kGroundImpact;
  if (config_.has_region) {
    const double out = DistanceOutside(config_.region, s.pos);
    if (out > 0) {
      found |= kLeftRegion;
      outside_[i] = out;
    }
  }
  found_[i] = found;
}

// Pairs closer than the near-miss margin or their radii: a sweep along x over the vehicles
// kept sorted by insertion (they move little per step, so this is close to linear), from the
// vehicles at sorted places [first, first + count) to every later one within reach.
void SafetyMonitor::ScanPairs(int first, int count, const std::vector<mjfVehicleState>& states) {
  std::vector<PairHit>& hits = pair_hits_[first];
  hits.clear();
  for (size_t a = first; a < static_cast<size_t>(first + count); ++a) {
    const double* p = states[order_[a].second].pos;
    for (size_t b = a + 1; b < order_.size() && order_[b].first - order_[a].first < reach_; ++b) {
      const double* q = states[order_[b].second].pos;
      const double d2 = (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                        (p[2] - q[2]) * (p[2] - q[2]);
      if (d2 > skip_squared_) continue;  // no event (constructor): most pairs of the sweep
      const double d = std::sqrt(d2);
      const int i = std::min(order_[a].second, order_[b].second);
      const int j = std::max(order_[a].second, order_[b].second);
      const double clearance = d - radii_[i] - radii_[j];  // between the bounding spheres
      if ((config_.near_miss_m > 0 && clearance < config_.near_miss_m) || clearance < 0) {
        hits.push_back({i, j, d, clearance});
      }
    }
  }
}

void SafetyMonitor::Begin(const std::vector<mjfVehicleState>& states) {
  if (states.size() != radii_.size()) return;  // Finish then checks the vehicles only
  for (auto& [x, i] : order_) x = states[i].pos[0];
  for (size_t a = 1; a < order_.size(); ++a) {
    for (size_t b = a; b > 0 && order_[b].first < order_[b - 1].first; --b) {
      std::swap(order_[b], order_[b - 1]);
    }
  }
}

void SafetyMonitor::Scan(int first, int count, const std::vector<mjfVehicleState>& states) {
  const int n = static_cast<int>(std::min(states.size(), radii_.size()));
  for (int i = first; i < std::min(first + count, n); ++i) ScanVehicle(i, states[i]);
  if (states.size() != radii_.size() || count <= 0) return;
  ScanPairs(first, count, states);
  range_count_[first] = count;
}

size_t SafetyMonitor::Finish(double t, const std::vector<mjfVehicleState>& states) {
  const size_t before = events_.size();
  const size_t n = std::min(states.size(), radii_.size());
  for (size_t i = 0; i < n; ++i) {
    if (!found_[i]) continue;
    const int v = static_cast<int>(i);
    if (found_[i] & kFlip) Report("flip", t, {v}, tilt_[i]);
    if (found_[i] & kGroundImpact) Report("ground_impact", t, {v}, states[i].pos[2]);
    if (found_[i] & kLeftRegion) Report("left_region", t, {v}, outside_[i]);
  }
  if (states.size() != radii_.size()) return events_.size() - before;
  for (size_t first = 0; first < radii_.size(); first += std::max(1, range_count_[first])) {
    if (range_count_[first] == 0) continue;  // not scanned: Scan's ranges must cover [0, n)
    for (const PairHit& h : pair_hits_[first]) {
      if (config_.near_miss_m > 0 && h.clearance < config_.near_miss_m) {
        Report("near_miss", t, {h.i, h.j}, h.distance, h.clearance);
      }
      if (h.clearance < 0) Report("collision", t, {h.i, h.j}, h.distance, h.clearance);
    }
    range_count_[first] = 0;
  }
  return events_.size() - before;
}

size_t SafetyMonitor::Check(double t, const std::vector<mjfVehicleState>& states) {
  Begin(states);
  Scan(0, static_cast<int>(std::min(states.size(), radii_.size())), states);
  return Finish(t, states);
}

nlohmann::ordered_json SafetyMonitor::Summary() const {
  nlohmann::ordered_json counts = nlohmann::ordered_json::object();
  for (const char* kind : kSafetyEventKinds) counts[kind] = 0;
  for (const auto& [kind, v, other] : seen_) counts[kind] = counts[kind].get<int64_t>() + 1;
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const SafetyEvent& e : events_) {
    nlohmann::ordered_json item = {
        {"kind", e.kind}, {"time_s", e.time_s}, {"vehicles", e.vehicles}, {"value", e.value}};
    if (e.vehicles.size() > 1) item["clearance_m"] = e.clearance;
    item["what"] = DescribeEvent(e);
    list.push_back(item);
  }
  nlohmann::ordered_json s = {{"count", total_}, {"by_kind", counts}, {"list", list}};
  if (total_ > static_cast<int64_t>(events_.size())) s["not_listed"] = total_ - events_.size();
  return s;
}

}  // namespace mjf::runner
