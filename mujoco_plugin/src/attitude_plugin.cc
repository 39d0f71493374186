// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "attitude_plugin.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "attach_names.hpp"

namespace mjf::native {
namespace {

struct VehicleHolder final : Holder {
  std::unique_ptr<VehicleHost> host;
  void Tick(int64_t step, const mjModel* m, const mjData* d, double* controls, double*) override {
    host->Tick(step, m, d, controls);
  }
  size_t state_size() const override { return AttitudePlugin::kStateBound; }
  void GetState(double* out) const override {
    std::fill(out, out + AttitudePlugin::kStateBound, 0.0);
    host->GetState(out);
  }
  void SetState(const double* in) override { host->SetState(in); }
};

}  // namespace

VehicleHostConfig AttitudePlugin::Config(const mjModel* m, int instance) {
  VehicleHostConfig c = VehicleConfigFromModel(m, instance, kName);
  const runner::SceneNames names = InstanceNames(m, instance, {c.body}, c.where);
  c.body = names(c.body);
  for (std::string& actuator : c.actuators) actuator = names(actuator);
  return c;
}

std::unique_ptr<Holder> AttitudePlugin::Make(const mjModel* m, int instance) {
  auto holder = std::make_unique<VehicleHolder>();
  holder->host = OnOwnThread([&] { return std::make_unique<VehicleHost>(m, Config(m, instance)); });
  if (holder->host->state_size() > kStateBound) {
    throw std::runtime_error(InstanceWhere(kName, m, instance) + ": its plugins declare " +
                             std::to_string(holder->host->state_size()) +
                             " doubles of state, more than the " + std::to_string(kStateBound) +
                             " this plugin holds");
  }
  return holder;
}

size_t AttitudePlugin::StateSize(const mjModel* m, int instance) {
  Config(m, instance);
  return kStateBound;
}

const PluginKind kAttitudeKind = {AttitudePlugin::kName, AttitudePlugin::Make,
                                  AttitudePlugin::StateSize};

void AttitudePlugin::Register() { ActuatorPlugin<kAttitudeKind>::Register(VehicleAttributes()); }

}  // namespace mjf::native
