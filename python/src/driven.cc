// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "driven.hpp"

#include <cstring>
#include <stdexcept>

#include "mjformation/control/agent_channel.hpp"
#include "mjformation/record/output.hpp"
#include "mjformation/record/recorders.hpp"

namespace mjf::python {
namespace rn = mjf::runner;

namespace {

constexpr int kStateSize = 13;  // pos 3, vel 3, quat 4, gyro 3 (mjfVehicleState)

void CopyState(const mjfVehicleState& s, double* out) {
  std::memcpy(out, &s, kStateSize * sizeof(double));
}

}  // namespace

DrivenSimulation::DrivenSimulation(const rn::ExperimentConfig& config)
    : sim_(std::make_unique<rn::Simulation>(config)) {
  monitor_ = std::make_unique<rn::SafetyMonitor>(config.safety, rn::VehicleRadii(*sim_));
  MakeAllocations();
  sim_->ComputeSetpoints();
  monitor_->Check(sim_->time(), sim_->states());
}

void DrivenSimulation::MakeAllocations() {
  try {
    for (int i = 1; i < sim_->n_vehicles(); ++i) allocations_.emplace_back(sim_->binding(i).info);
  } catch (const std::invalid_argument& e) {
    allocations_.clear();
    allocation_error_ = "vehicle model '" + sim_->config().model + "': " + e.what();
  }
}

// The runner's loop (run.cc StepLoop) is ComputeControls, record, Integrate; here the tick is
// split around the commands, and the safety check sees the states the recorders would.
int64_t DrivenSimulation::Act(const double* commands, int64_t steps) {
  int64_t done = 0;
  for (; done < steps && sim_->step_index() < sim_->total_steps(); ++done) {
    if (commands != nullptr) sim_->CommandFollowers(commands);
    sim_->ComputeActuation();
    sim_->Integrate();
    sim_->ComputeSetpoints();
    monitor_->Check(sim_->time(), sim_->states());
  }
  return done;
}

int64_t DrivenSimulation::ActThrustMoment(const double* commands, const double* wrenches,
                                          const unsigned char* given, int64_t steps) {
  if (!allocation_error_.empty()) throw std::invalid_argument(allocation_error_);
  const int n = sim_->n_followers();
  std::vector<double> controls(static_cast<size_t>(n) * rn::WrenchAllocation::kActuators, 0.0);
  for (int i = 0; i < n; ++i) {
    if (given[i]) allocations_[i].Controls(wrenches + 4 * i, controls.data() + 4 * i);
  }
  int64_t done = 0;
  for (; done < steps && sim_->step_index() < sim_->total_steps(); ++done) {
    if (commands != nullptr) sim_->CommandFollowers(commands);
    sim_->ComputeActuation(controls.data(), given);
    sim_->Integrate();
    sim_->ComputeSetpoints();
    monitor_->Check(sim_->time(), sim_->states());
  }
  return done;
}

void DrivenSimulation::Heard(double* states, double* heard) const {
  const int n = sim_->n_followers();
  const size_t row = static_cast<size_t>(n) + 1;
  std::memset(states, 0, sizeof(double) * n * row * kStateSize);
  std::memset(heard, 0, sizeof(double) * n * row);
  auto put = [&](int follower, int vehicle, const mjfVehicleState& s) {
    const size_t at = follower * row + vehicle;
    CopyState(s, states + at * kStateSize);
    heard[at] = 1.0;
  };
  if (const rn::AgentChannel* channel = sim_->channel()) {
    for (int i = 0; i < n; ++i) {
      const mjfAgentInput& in = channel->LastInput(i);
      if (in.leader != nullptr) put(i, 0, in.leader->state);
      for (int m = 0; m < in.n_messages; ++m) put(i, in.messages[m].sender, in.messages[m].state);
    }
    return;
  }
  const rn::ExperimentConfig& c = sim_->config();
  const auto& measured = sim_->measured();
  for (int i = 0; i < n; ++i) {
    if (c.leader_weight[i] > 0) put(i, 0, measured[0]);
  }
  for (const auto& e : c.edges) put(e.to, e.from + 1, measured[e.from + 1]);
}

std::string DrivenSimulation::GetState() { return SimulationState(*sim_, monitor_.get()); }

void DrivenSimulation::SetState(const std::string& state) {
  RestoreSimulationState(*sim_, monitor_.get(), state);
}

namespace {

constexpr const char* kStateFormat = "mjformation state 1";

void VisitAll(rn::StateArchive& archive, rn::Simulation& sim, rn::SafetyMonitor* monitor) {
  sim.VisitStateAtTick(archive);
  archive.Tag(monitor ? "safety" : "no safety");
  if (monitor) archive(*monitor);
}

}  // namespace

std::string SimulationState(rn::Simulation& sim, rn::SafetyMonitor* monitor) {
  sim.RequireSavable();
  rn::StateArchive archive;
  archive.Tag(kStateFormat);
  std::string sha = rn::Sha256Hex(rn::ConfigEcho(sim.config()));
  archive(sha);
  VisitAll(archive, sim, monitor);
  return archive.bytes();
}

void RestoreSimulationState(rn::Simulation& sim, rn::SafetyMonitor* monitor,
                            const std::string& state) {
  sim.RequireSavable();
  rn::StateArchive archive(state);
  try {
    archive.Tag(kStateFormat);
    std::string sha;
    archive(sha);
    const std::string own = rn::Sha256Hex(rn::ConfigEcho(sim.config()));
    if (sha != own) {
      throw rn::ConfigError(
          "set_state: the state was taken from another configuration (config "
          "sha256 " +
          sha + "), this simulation's is " + own);
    }
    VisitAll(archive, sim, monitor);
  } catch (const rn::StateArchiveError& e) {
    throw rn::ConfigError(std::string("set_state: ") + e.what());
  }
}

}  // namespace mjf::python
