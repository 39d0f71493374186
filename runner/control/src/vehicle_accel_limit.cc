// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/control/vehicle_accel_limit.hpp"

#include <algorithm>
#include <cmath>

namespace mjf::runner {

double VehicleAccelBound(const mjfVehicleInfo& info, bool has_tilt, double tilt_max,
                         std::string* why) {
  if (!(info.mass > 0.0)) {
    *why = "the vehicle has no mass";
    return -1.0;
  }
  if (has_tilt) {
    double thrust = 0.0;
    for (int k = 0; k < info.n_actuators; ++k) {
      const mjfActuatorInfo& a = info.actuators[k];
      thrust += std::max(0.0, a.ctrl_max * a.gear[2]);
    }
    const double tilt = info.gravity * std::tan(tilt_max);
    const double ratio = thrust / (info.mass * info.gravity);
    if (!(ratio > 1.0)) {
      *why = "its rotors cannot lift it (thrust/weight <= 1)";
      return -1.0;
    }
    // Holding altitude takes m g of the thrust; what is left tilts the vector sideways.
    const double spare =
        std::isfinite(ratio) ? info.gravity * std::sqrt(ratio * ratio - 1.0) : tilt;
    return std::min(tilt, spare);
  }
  if (info.n_actuators < 2) {
    *why = "it has neither a tilt limit nor two horizontal force actuators";
    return -1.0;
  }
  double bound = INFINITY;
  for (int k = 0; k < 2; ++k) {
    const mjfActuatorInfo& a = info.actuators[k];
    bound = std::min(bound, std::min(-a.ctrl_min, a.ctrl_max) * std::abs(a.gear[0]) / info.mass);
  }
  if (!std::isfinite(bound) || !(bound > 0.0)) {
    *why = "its horizontal actuators have no finite positive control range";
    return -1.0;
  }
  return bound;
}

}  // namespace mjf::runner
