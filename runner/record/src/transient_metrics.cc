// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/record/transient_metrics.hpp"

#include <algorithm>
#include <cmath>

#include "mjformation/record/output.hpp"

namespace mjf::runner {

TransientMetrics::TransientMetrics(int n_followers) : followers_(n_followers) {}

void TransientMetrics::Add(int i, double t, double slot_distance, const double* demand_xy,
                           const double* vel_xy) {
  Follower& f = followers_[i];
  if (t >= kSettleTime - 1e-9) f.max_distance_after = std::max(f.max_distance_after, slot_distance);
  if (!(slot_distance <= kNearSlot)) {  // NaN counts as outside
    f.last_outside = t;
    f.ever_outside = true;
  }
  if (std::isfinite(demand_xy[0]) && std::isfinite(demand_xy[1])) {
    f.peak_demand = std::max(f.peak_demand, std::hypot(demand_xy[0], demand_xy[1]));
  }
  if (f.has_last && t > f.last_t) {
    const double dt = t - f.last_t;
    f.peak_delivered = std::max(
        f.peak_delivered, std::hypot(vel_xy[0] - f.last_vel[0], vel_xy[1] - f.last_vel[1]) / dt);
  }
  f.last_t = t;
  f.last_vel[0] = vel_xy[0];
  f.last_vel[1] = vel_xy[1];
  f.has_last = true;
  f.has_sample = true;
}

void TransientMetrics::AddTo(nlohmann::ordered_json* metrics) const {
  nlohmann::ordered_json distance = nlohmann::ordered_json::array(),
                         settle = nlohmann::ordered_json::array(),
                         demand = nlohmann::ordered_json::array(),
                         delivered = nlohmann::ordered_json::array();
  for (const Follower& f : followers_) {
    distance.push_back(JsonNumber(f.max_distance_after));
    // Settled: within 1 m from some record tick on to the end. The time is the first tick after
    // the last one outside (0 if never outside); null if the last tick is outside.
    if (!f.has_sample || (f.ever_outside && f.last_outside >= f.last_t)) {
      settle.push_back(nullptr);
    } else {
      settle.push_back(JsonNumber(f.ever_outside ? f.last_outside : 0.0));
    }
    demand.push_back(JsonNumber(f.peak_demand));
    delivered.push_back(JsonNumber(f.peak_delivered));
  }
  (*metrics)["max_slot_distance_after_5s_m"] = distance;
  (*metrics)["time_within_1m_s"] = settle;
  (*metrics)["peak_demanded_accel"] = demand;
  (*metrics)["peak_delivered_accel"] = delivered;
}

}  // namespace mjf::runner
