// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Safety events (docs/ARCHITECTURE.md, "Safety events"): a vehicle flips, hits the ground,
// collides with another, passes another closer than the near-miss margin, or leaves the
// configured region. Each is reported once, when it is first seen, with the time, the vehicles
// and the value that crossed the threshold. Knows only vehicle states, not MuJoCo: the radii
// come from the vehicles' geometry (VehicleRadii, recorders.cc).
#ifndef MJFORMATION_RECORD_SAFETY_EVENTS_HPP_
#define MJFORMATION_RECORD_SAFETY_EVENTS_HPP_

#include <cstdint>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "mjformation/config/config.hpp"
#include "mjformation/plugin.h"

namespace mjf::runner {

struct SafetyEvent {
  std::string kind;           // one of kSafetyEventKinds
  double time_s = 0;          // first seen
  std::vector<int> vehicles;  // 0 = leader, i = follower i
  double value = 0;           // tilt (deg), separation (m), altitude (m) or distance outside (m)
  double clearance = 0;       // pairs: separation minus both bounding radii (m); 0 otherwise
};

// "follower 6 flipped at 34.19 s (tilt 95.2 deg)": for messages and the closing line.
std::string DescribeEvent(const SafetyEvent& event);

class SafetyMonitor {
 public:
  // radii: each vehicle's bounding radius (m) about its body origin; collision below the sum.
  SafetyMonitor(const SafetyConfig& config, std::vector<double> radii);
  // Checks the vehicles at time t; returns how many events were first seen now (the last ones
  // of events()).
  size_t Check(double t, const std::vector<mjfVehicleState>& states);
  const std::vector<SafetyEvent>& events() const { return events_; }
  // summary.json "events": the list (at most kMaxListed) and the count per kind.
  nlohmann::ordered_json Summary() const;

  static constexpr size_t kMaxListed = 1000;

 private:
  void CheckVehicle(double t, int i, const mjfVehicleState& s);
  void CheckPairs(double t, const std::vector<mjfVehicleState>& states);
  void Report(const std::string& kind, double t, std::vector<int> vehicles, double value,
              double clearance = 0);

  SafetyConfig config_;
  std::vector<double> radii_;
  double flip_cos_skip_ = 0;  // a tilt's cosine at or above it cannot be a flip (constructor)
  double max_radius_ = 0;
  std::vector<char> airborne_;                        // seen above the ground: impacts count after
  std::set<std::tuple<std::string, int, int>> seen_;  // (kind, vehicle, other or -1)
  std::vector<std::pair<double, int>> order_;         // vehicles by x, kept nearly sorted
  std::vector<SafetyEvent> events_;
  int64_t total_ = 0;
};

}  // namespace mjf::runner

#endif  // MJFORMATION_RECORD_SAFETY_EVENTS_HPP_
