// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The [sensors] and [wind] sections of an experiment file as typed structs (parsed by
// runner/config/src/realism_config.cc, called from ParseExperiment).
#ifndef MJFORMATION_CONFIG_REALISM_CONFIG_HPP_
#define MJFORMATION_CONFIG_REALISM_CONFIG_HPP_

#include <nlohmann/json.hpp>
#include <string>

#include "mjformation/realism/drag.hpp"
#include "mjformation/realism/sensor_model.hpp"
#include "mjformation/realism/wind_field.hpp"

namespace mjf::runner {

// [sensors]: what the controllers measure. Default "ideal": the truth, bit for bit.
struct SensorsConfig {
  std::string preset = "ideal";  // "ideal", "typical", "consumer_gnss", "rtk", "mocap"
  double scale = 1.0;            // multiplies the preset's white noise, bias walk and wander
  std::string imu;               // an IMU grade for the accelerometer ("icm42688", "ekf2")
  realism::SensorParams params;  // preset, scaled, then the per-channel keys applied
  bool enabled() const { return !params.IsIdeal(); }
};

// [wind]: mean wind, Dryden turbulence and 1-cosine gusts, acting through the drag model.
struct WindConfig {
  std::string turbulence = "none";  // "none", "light", "moderate", "severe" or "w20"
  double w20 = 0.0;                 // m/s, wind speed at 20 ft setting the Dryden intensities
  realism::WindParams params;
  realism::DragParams drag = realism::DragParams::Iris();
  bool enabled() const { return !params.IsCalm(); }
};

struct ExperimentConfig;

// summary.json's "sensors" and "wind" entries (the resolved parameters), each only when that
// stage is switched on, so default runs keep their summary bytes.
void AddRealismSummary(const ExperimentConfig& c, nlohmann::ordered_json* summary);

}  // namespace mjf::runner

#endif  // MJFORMATION_CONFIG_REALISM_CONFIG_HPP_
