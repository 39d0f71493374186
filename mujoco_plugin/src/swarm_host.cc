// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "swarm_host.hpp"

#include <toml++/toml.h>

#include <sstream>
#include <stdexcept>

#include "mjformation/config/config.hpp"
#include "mjformation/config/paths.hpp"
#include "mjformation/control/control_setup.hpp"
#include "mjformation/scene/rotor_faults.hpp"
#include "mjformation/scene/vehicle_adapter.hpp"
#include "mjformation/scene/vehicle_binding.hpp"
#include "mjformation/sim/actuation.hpp"
#include "scene_files.hpp"

namespace mjf::native {

// The runner names a file and line ("WHERE:3: [formation] q: ..."); the lines of the text built
// above mean nothing to the MJCF's author, the section and key say it all.
std::string WithoutLine(const std::string& message, const std::string& where) {
  std::string out = message;
  for (size_t at = out.find(where + ":"); at != std::string::npos;
       at = out.find(where + ":", at + 1)) {
    size_t digits = at + where.size() + 1;
    size_t end = digits;
    // ":LINE" or ":LINE:COLUMN"
    while (end < out.size() && ((out[end] >= '0' && out[end] <= '9') ||
                                (out[end] == ':' && end + 1 < out.size() && out[end + 1] != ' '))) {
      ++end;
    }
    if (end > digits) out.erase(at + where.size(), end - at - where.size());
  }
  return out;
}

// A <config> value is the body of one inline table. Read alone first, so that a value which
// closes its table and goes on (`1 }&#10;[run]&#10;...`) is refused instead of becoming other
// sections of the text below. A value that does not parse alone is left to the parser below,
// which words the syntax error.
void RequireOneTable(const std::string& key, const std::string& value, const std::string& where) {
  toml::table alone;
  try {
    alone = toml::parse(key + " = {" + value + "}\n");
  } catch (const toml::parse_error&) {
    return;
  }
  if (alone.size() != 1 || !alone.get_as<toml::table>(key)) {
    throw runner::ConfigError(where + ": <config key=\"" + key +
                              "\">: the value must be the keys of one table (a = 1, b = \"x\"); "
                              "this one closes the table and goes on");
  }
}

runner::ExperimentConfig ConfigFromPairs(
    const std::vector<std::pair<std::string, std::string>>& pairs, const std::string& where,
    const std::string& folder) {
  // Each section becomes `section = { ... }`: the runner's parser then checks every name and
  // value and words its messages as it does for an experiment file.
  std::ostringstream toml;
  for (const auto& [key, value] : pairs) {
    if (value.empty()) continue;
    RequireOneTable(key, value, where);
    toml << key << " = {" << value << "}\n";
  }
  try {
    // The scene may have travelled: [run] plugin_path names the folders it was exported with.
    runner::ExperimentChecks checks;
    checks.plugin_folders = false;
    return runner::ParseExperiment(toml.str(), where, RebasedPathOverrides(toml.str(), folder),
                                   checks);
  } catch (const runner::ConfigError& e) {
    std::string message = WithoutLine(e.what(), where);
    // A syntax error: name the <config> key whose value does not parse on its own.
    if (message.find("TOML syntax error") != std::string::npos) {
      for (const auto& [key, value] : pairs) {
        try {
          runner::ParseExperiment(key + " = {" + value + "}\n", where);
        } catch (const runner::ConfigError& alone) {
          if (std::string(alone.what()).find("TOML syntax error") == std::string::npos) continue;
          message = where + ": <config key=\"" + key +
                    "\">: " + message.substr(message.find("TOML syntax error"));
          break;
        }
      }
    }
    throw runner::ConfigError(message);
  }
}

struct SwarmShared {
  runner::ExperimentConfig config;
  std::unique_ptr<runner::PluginRegistry> registry;
  const runner::LoadedPlugin* attitude = nullptr;
  runner::VehicleBindings bindings;             // read only: shared by every host of the model
  std::vector<runner::BoundRotorFault> faults;  // [[vehicles.fault]] (rotor_faults.hpp)
};

struct SwarmHost::Impl {
  std::shared_ptr<const SwarmShared> shared;  // outlives the plugin instances below
  std::unique_ptr<runner::ControlWiring> wiring;
  std::unique_ptr<runner::ControlTick> tick;
  std::vector<mjfVehicleState> truth;
  std::vector<double> faulted;  // the tick's controls with the faults in force
  // The runner's own force stages and wrench rotor model (null with MuJoCo's actuators), whose
  // state is loaded from plugin_state before each use: the same code, the same bits.
  std::vector<std::unique_ptr<runner::ForceStage>> forces;
  std::unique_ptr<runner::Actuation> wrench;  // made at its first use, on the bound model
  const mjModel* wrench_model = nullptr;      // the model `wrench` was made for
  size_t rotors = 0;                          // vehicles x rotors, with the wrench model
  std::vector<double> external;               // the force stages' sum, [vehicle][xyz]
  std::vector<double> controls;  // the held controls as the actuation takes them (scratch)
  size_t tick_state = 0;         // the tick's part of the state
};

// The same construction as the runner's Simulation, on the scene MuJoCo compiled: the bindings
// read the vehicle model of [vehicles] model for mass, inertia and actuator geometry.
std::shared_ptr<const SwarmShared> SwarmHost::Prepare(const mjModel* m,
                                                      const runner::ExperimentConfig& config,
                                                      bool bind_model,
                                                      const runner::SceneNames& names) {
  try {
    auto s = std::make_shared<SwarmShared>();
    s->config = config;
    s->config.timestep = m->opt.timestep;
    s->registry =
        std::make_unique<runner::PluginRegistry>(NativePluginSearchPath(s->config.plugin_path));
    s->attitude = &runner::LoadAttitudePlugin(*s->registry, s->config);
    // A mapped foreign vehicle ([vehicles] body, rotors, thrust, moments): its facts are read
    // from the text the runner adapts and flies, so both faces bind the same numbers.
    const std::string vehicle_xml =
        runner::AdaptConfiguredVehicle(s->config, *s->attitude->descriptor).xml;
    s->bindings =
        bind_model ? runner::BindVehicles(m, s->config, *s->attitude->descriptor, vehicle_xml, 0,
                                          -1, names)
                   : runner::DescribeVehicles(m, s->config, *s->attitude->descriptor, vehicle_xml);
    s->faults = runner::BindRotorFaults(s->config, s->bindings, 0);
    // MuJoCo calls an actuator plugin only in a model with an actuator; the wrench rotor model's
    // rotors have none (export adds one of no force, 'mjformation_swarm_tick').
    if (bind_model && s->config.rotor_model == runner::RotorModel::kWrench && m->nu == 0) {
      throw std::runtime_error(
          "[vehicles] rotor_model = \"wrench\": the scene has no actuator, and MuJoCo calls "
          "the swarm's controllers only in a model with one; export adds a zero-gear "
          "actuator, 'mjformation_swarm_tick', for this: keep it");
    }
    return s;
  } catch (const std::exception& e) {
    throw std::runtime_error(WithoutLine(e.what(), config.source_path));
  }
}

SwarmHost::SwarmHost(std::shared_ptr<const SwarmShared> shared) : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.shared = std::move(shared);
  const runner::ExperimentConfig& config = s.shared->config;
  try {
    s.truth.resize(config.followers + 1);
    runner::VehicleContexts contexts;
    for (const runner::VehicleBinding& b : s.shared->bindings.vehicles) {
      contexts.info.push_back(&b.info);
    }
    contexts.initial_positions = runner::InitialPositions(config);
    runner::ControlSetup control =
        runner::SetUpControl(config, *s.shared->registry, *s.shared->attitude, std::move(contexts),
                             s.shared->bindings.actuators_per_vehicle);
    s.wiring = std::move(control.wiring);
    s.tick = std::move(control.tick);
    s.tick->RequireSavable();
    s.tick_state = s.tick->StateSize();
    s.forces = runner::MakeForceStages(config);
    s.external.assign(3 * s.truth.size(), 0.0);
    if (config.rotor_model == runner::RotorModel::kWrench) {
      const runner::VehicleBindings& b = s.shared->bindings;
      s.rotors = b.vehicles.size() * static_cast<size_t>(b.actuators_per_vehicle);
      s.controls.assign(s.rotors, 0.0);
    }
  } catch (const std::exception& e) {
    throw std::runtime_error(WithoutLine(e.what(), config.source_path));
  }
}

SwarmHost::~SwarmHost() {
  // Plugin instances before the wiring and the libraries (held by `shared`).
  if (impl_) impl_->tick.reset();
}

namespace {
// The force stages' state, walked by one archive (Sizing, Saving or Loading).
void VisitForceState(std::vector<std::unique_ptr<runner::ForceStage>>& forces,
                     runner::FixedStateArchive& archive) {
  for (auto& stage : forces) stage->VisitState(archive);
}
}  // namespace

size_t SwarmHost::state_size() const {
  runner::FixedStateArchive sizing = runner::FixedStateArchive::Sizing();
  VisitForceState(impl_->forces, sizing);
  return impl_->tick_state + sizing.size();
}
void SwarmHost::GetState(double* out) const {
  impl_->tick->GetState(out);
  runner::FixedStateArchive saving = runner::FixedStateArchive::Saving(out + impl_->tick_state);
  VisitForceState(impl_->forces, saving);
}
void SwarmHost::UpdateState(double* block) const {
  impl_->tick->UpdateState(block);
  runner::FixedStateArchive updating =
      runner::FixedStateArchive::Updating(block + impl_->tick_state);
  VisitForceState(impl_->forces, updating);
}
void SwarmHost::SetState(const double* in) {
  impl_->tick->SetState(in);
  runner::FixedStateArchive loading = runner::FixedStateArchive::Loading(in + impl_->tick_state);
  VisitForceState(impl_->forces, loading);
}

// The wrench model on `m` (its rotors' sites and the vehicles' bodies are m's), loaded with the
// motor lags of `held`.
runner::Actuation& SwarmHost::Wrench(const mjModel* m, const double* held) {
  Impl& s = *impl_;
  if (!s.wrench || s.wrench_model != m) {
    s.wrench = runner::MakeActuation(runner::RotorModel::kWrench, m, s.shared->bindings,
                                     s.shared->config.timestep);
    s.wrench_model = m;
  }
  std::copy(held, held + s.rotors, s.controls.begin());
  runner::FixedStateArchive lags = runner::FixedStateArchive::Loading(held + s.rotors);
  s.wrench->VisitState(lags);
  return *s.wrench;
}

size_t SwarmHost::held_size() const {
  return 2 * impl_->rotors + (impl_->forces.empty() ? 0 : impl_->external.size());
}

void SwarmHost::Tick(int64_t step, const mjModel* m, const mjData* d, double* controls,
                     double* held) {
  Impl& s = *impl_;
  const runner::VehicleBindings& bindings = s.shared->bindings;
  runner::ReadTrueStates(d, bindings, &s.truth);
  s.tick->Run(step, s.truth, reinterpret_cast<const struct mjModel_*>(m),
              reinterpret_cast<const struct mjData_*>(d));
  // The range topology's changes are the runner's to report; the flight needs only the links'
  // state, which is in plugin_state.
  s.tick->ForgetTopologyEvents();
  const std::vector<double>* c = &s.tick->controls();
  if (!s.shared->faults.empty()) {
    // Where the runner's actuation applies them (sim/actuation.cc, FaultedActuation), at the
    // step's time: the plugin's Applied() then clamps as MuJoCo clamps the runner's d->ctrl.
    s.faulted = *c;
    runner::ApplyRotorFaults(s.shared->faults, static_cast<double>(step) * m->opt.timestep,
                             m->opt.timestep, s.faulted.data());
    c = &s.faulted;
  }
  if (s.rotors) {
    std::copy(c->begin(), c->end(), held);  // the wrench model's rotors have no actuator
  } else {
    const int per = bindings.actuators_per_vehicle;
    for (size_t i = 0; i < bindings.vehicles.size(); ++i) {
      const std::vector<int>& ids = bindings.vehicles[i].actuators;
      for (int k = 0; k < per; ++k) controls[ids[k]] = (*c)[i * per + k];
    }
  }
  if (s.forces.empty()) return;
  // Simulation::ComputeForces: every stage's force from the tick's true states.
  std::fill(s.external.begin(), s.external.end(), 0.0);
  const double time = static_cast<double>(step) * s.shared->config.timestep;
  for (auto& stage : s.forces) stage->AddForces(step, time, s.truth, &s.external);
  std::copy(s.external.begin(), s.external.end(), held + 2 * s.rotors);
}

void SwarmHost::AddForces(const mjModel* m, mjData* d, const double* held) {
  Impl& s = *impl_;
  const runner::VehicleBindings& bindings = s.shared->bindings;
  if (s.rotors) {
    // Simulation::HandOverControls: the rotor wrenches first, from the held controls and the
    // motor lags of this step.
    Wrench(m, held).Apply(s.controls, d);
  }
  if (s.forces.empty()) return;
  // Simulation::ApplyForces: then each vehicle's external force at its centre of mass.
  const double* f = held + 2 * s.rotors;
  for (size_t i = 0; i < bindings.vehicles.size(); ++i) {
    const mjtNum wrench[6] = {f[3 * i], f[3 * i + 1], f[3 * i + 2], 0, 0, 0};
    runner::AddWrenchAtCentreOfMass(m, d, bindings.vehicles[i].body, wrench);
  }
}

void SwarmHost::Advance(const mjModel* m, double* held) {
  Impl& s = *impl_;
  if (!s.rotors) return;
  Wrench(m, held).Advance(s.controls);
  runner::FixedStateArchive saving = runner::FixedStateArchive::Saving(held + s.rotors);
  s.wrench->VisitState(saving);
}

}  // namespace mjf::native
