// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The contract's inertial site and sensors added to an adapted vehicle (vehicle_adapter.cc's
// last step) through MuJoCo's model editing API, private to scene/.
#ifndef MJFORMATION_SCENE_SRC_VEHICLE_SENSORS_HPP_
#define MJFORMATION_SCENE_SRC_VEHICLE_SENSORS_HPP_

#include <string>
#include <vector>

namespace mjf::runner {

// Adds to the model `xml` the site `imu` at the centre of mass of the body `vehicle` (with its
// child bodies), axes those of the body, and the sensors pos, vel, quat and gyro on it; returns
// the model as MuJoCo writes it (as written: it compiles to the model the spec does). The centre
// of mass comes from compiling the model as it stands (`label` names it in a compile error).
std::string AddImuAndSensors(const std::string& xml, const std::string& label,
                             std::vector<std::string>* notes);

}  // namespace mjf::runner

#endif  // MJFORMATION_SCENE_SRC_VEHICLE_SENSORS_HPP_
