// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/scene/rotor_faults.hpp"

#include <string>

#include "mjformation/config/source_location.hpp"

namespace mjf::runner {

std::vector<BoundRotorFault> BindRotorFaults(const ExperimentConfig& config,
                                             const VehicleBindings& bindings, int first_vehicle) {
  std::vector<BoundRotorFault> faults;
  const int per = bindings.actuators_per_vehicle;
  for (const ExperimentConfig::RotorFault& f : config.rotor_faults) {
    if (f.rotor >= per) {
      SourceLocation{config.source_path, f.line, SectionKey("vehicles", "fault")}.Fail(
          "rotor " + std::to_string(f.rotor) + ": the vehicle has rotors 0.." +
          std::to_string(per - 1) + " (the attitude plugin's actuator order)");
    }
    const int local = f.follower - first_vehicle;  // vehicle f.follower, 0 = leader
    if (local < 0 || local >= static_cast<int>(bindings.vehicles.size())) continue;
    const mjfActuatorInfo& a = bindings.vehicles[local].actuator_info[f.rotor];
    faults.push_back({static_cast<size_t>(local) * per + f.rotor, f.at, 1.0 - f.thrust_share,
                      a.ctrl_min, a.ctrl_max});
  }
  return faults;
}

}  // namespace mjf::runner
