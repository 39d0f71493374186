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

#include "mjformation/config/experiment.hpp"
#include "mjformation/plugin.h"

namespace mjf::runner {

struct SafetyEvent {
  std::string kind;           // one of kSafetyEventKinds
  double time_s = 0;          // first seen
  std::vector<int> vehicles;  // 0 = leader, i = follower i
  double value = 0;           // tilt (deg), separation (m), altitude (m) or distance outside (m)
  double clearance = 0;       // pairs: separation minus both bounding radii (m); 0 otherwise
  template <typename Archive>
  void VisitState(Archive& a) {
    a(kind, time_s, vehicles, value, clearance);
  }
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
  // Check in three parts, so that the tests of each vehicle and of the pairs can run on several
  // threads at once (the partitions' threads, recorders.cc): Begin (sorts the vehicles along x),
  // then Scan for ranges of [0, n) that cover it once, at the same time on different threads,
  // then Finish, which reports what the scans found in Check's order (each vehicle's tests in
  // vehicle order, then the pairs in the sweep's order) and returns what Check returns. The same
  // events, values and order as Check for any split into ranges.
  void Begin(const std::vector<mjfVehicleState>& states);
  void Scan(int first, int count, const std::vector<mjfVehicleState>& states);
  size_t Finish(double t, const std::vector<mjfVehicleState>& states);
  const std::vector<SafetyEvent>& events() const { return events_; }
  // summary.json "events": the list (at most kMaxListed) and the count per kind.
  nlohmann::ordered_json Summary() const;

  static constexpr size_t kMaxListed = 1000;

  // What was seen so far, both ways (checkpoints); the vehicles' order along x is kept too,
  // since the next sort starts from it. found_ .. range_count_ are one check's scratch.
  template <typename Archive>
  void VisitState(Archive& a) {
    a(airborne_, seen_, order_, events_, total_);
  }

 private:
  // A pair closer than the near-miss margin or its radii, found by Scan.
  struct PairHit {
    int i, j;  // i < j
    double distance, clearance;
  };
  // What Scan found for vehicle i (bits of found_[i]) and the values it found.
  enum : char { kFlip = 1, kGroundImpact = 2, kLeftRegion = 4 };
  void ScanVehicle(int i, const mjfVehicleState& s);
  void ScanPairs(int first, int count, const std::vector<mjfVehicleState>& states);
  void Report(const std::string& kind, double t, std::vector<int> vehicles, double value,
              double clearance = 0);

  SafetyConfig config_;
  std::vector<double> radii_;
  double flip_cos_skip_ = 0;  // a tilt's cosine at or above it cannot be a flip (constructor)
  double max_radius_ = 0;
  double reach_ = 0;            // near_miss_m + 2 max_radius_: no pair farther apart is an event
  double skip_squared_ = 0;     // a squared distance above it cannot be an event (constructor)
  std::vector<char> airborne_;  // seen above the ground: impacts count after
  std::set<std::tuple<std::string, int, int>> seen_;  // (kind, vehicle, other or -1)
  std::vector<std::pair<double, int>> order_;         // vehicles by x, kept nearly sorted
  // Scan's findings, [vehicle]: kFlip | kGroundImpact | kLeftRegion, the tilt (deg) and the
  // distance outside the region (m); [first of a range]: the range's pairs in sweep order and
  // its size (0: not the first of a range). Sized once; a range's list grows only with hits.
  std::vector<char> found_;
  std::vector<double> tilt_, outside_;
  std::vector<std::vector<PairHit>> pair_hits_;
  std::vector<int> range_count_;
  std::vector<SafetyEvent> events_;
  int64_t total_ = 0;
};

}  // namespace mjf::runner

#endif  // MJFORMATION_RECORD_SAFETY_EVENTS_HPP_
