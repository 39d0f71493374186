// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// accel_limit = "vehicle" of the formation section: the host resolves it, since a formation
// plugin sees no vehicle (mjfCreateContext::vehicle_info is NULL for it).
#ifndef MJFORMATION_CONTROL_VEHICLE_ACCEL_LIMIT_HPP_
#define MJFORMATION_CONTROL_VEHICLE_ACCEL_LIMIT_HPP_

#include <mjformation/plugin.h>

#include <string>

namespace mjf::runner {

// The horizontal acceleration one follower can give, m/s^2, or a negative value with *why set.
// An attitude plugin with a tilt limit (a rotorcraft): min(g tan(tilt_max), sqrt((F_max/m)^2 -
// g^2)), F_max the sum of the actuators' largest body-z forces (ctrl_max * gear[2]): tilt, or
// thrust left over after holding altitude. Without one (direct force, e.g. pointmass_direct):
// actuators 0 and 1 push along x and y; the disc inside their box, min |ctrl| * |gear| / m.
double VehicleAccelBound(const mjfVehicleInfo& info, bool has_tilt, double tilt_max,
                         std::string* why);

}  // namespace mjf::runner

#endif  // MJFORMATION_CONTROL_VEHICLE_ACCEL_LIMIT_HPP_
