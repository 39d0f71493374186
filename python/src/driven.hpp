// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// A simulation driven from outside, one command at a time (Simulation.reset / step(actions) and
// the environments of mjformation.envs, docs/PYTHON.md). It stands between the two parts of a
// tick: the sensors, the leader and the formation stage have run for time(), so what each
// follower knows is there, and the formation law's own commands are on the bus; Act() replaces
// the followers' commands (or keeps the law's), runs the attitude plugins and integrates,
// for as many physics steps as asked, each followed by the next tick's first part and the
// runner's safety check. Flying the law's own commands is the runner's flight, bit for bit.
#ifndef MJFORMATION_PYTHON_DRIVEN_HPP_
#define MJFORMATION_PYTHON_DRIVEN_HPP_

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "mjformation/config/experiment.hpp"
#include "mjformation/control/wrench_allocation.hpp"
#include "mjformation/record/safety_events.hpp"
#include "mjformation/sim/simulation.hpp"

namespace mjf::python {

class DrivenSimulation {
 public:
  // Builds the simulation and runs the first part of its tick at t = 0. Throws as Simulation.
  explicit DrivenSimulation(const runner::ExperimentConfig& config);

  // Up to `steps` physics steps (fewer at the experiment's end) with the followers' commands
  // `commands` ([follower][3]: acceleration x, y and the vertical feedforward, m/s^2, world
  // frame) held, or the formation law's own when null. Returns the steps done. Throws
  // SimulationError (a non-finite command or state, a plugin's failure).
  int64_t Act(const double* commands, int64_t steps);
  // The lower level: follower i with given[i] != 0 flies wrenches[i * 4 ..] (collective thrust
  // along body z, N; body moments about x, y, z, N m), turned into its actuator controls by its
  // allocation (clamped into the ctrlranges) in place of its attitude plugin, held for `steps`;
  // the other followers fly `commands` (or the law's, when null) as Act does. The caller checks
  // that every given wrench is finite. Throws std::invalid_argument when a vehicle has no
  // allocation (why: WrenchAllocationError), SimulationError as Act.
  int64_t ActThrustMoment(const double* commands, const double* wrenches,
                          const unsigned char* given, int64_t steps);
  // Why the followers have no thrust-and-moment allocation (empty: they have one).
  const std::string& allocation_error() const { return allocation_error_; }
  // Follower i's allocation; only when allocation_error() is empty.
  const runner::WrenchAllocation& allocation(int follower) const { return allocations_[follower]; }

  runner::Simulation& sim() { return *sim_; }
  const runner::Simulation& sim() const { return *sim_; }
  // The safety events seen so far (flip, ground impact, collision, ...), checked every step.
  const std::vector<runner::SafetyEvent>& events() const { return monitor_->events(); }
  // What each follower i holds of vehicle v (0 the leader, 1..N the followers):
  // states[(i * (N + 1) + v) * 13 ..] and heard[i * (N + 1) + v] = 1, else zeros. Central
  // execution: the measured states of the vehicles it hears in the graph (an ideal network);
  // per-agent execution: the newest messages it was handed through [network].
  void Heard(double* states, double* heard) const;
  // get_state() / set_state(): the simulation at this tick and the safety events seen so far
  // (SimulationState below).
  std::string GetState();
  void SetState(const std::string& state);

 private:
  void MakeAllocations();

  std::unique_ptr<runner::Simulation> sim_;
  std::unique_ptr<runner::SafetyMonitor> monitor_;
  std::vector<runner::WrenchAllocation> allocations_;  // one per follower
  std::string allocation_error_;
};

// Simulation.get_state() / set_state(state): the simulation as it stands at a control tick
// (Simulation::VisitStateAtTick: the same serialisation as the runner's checkpoints), and the
// safety monitor's when there is one, behind the config's sha256. A state restored into a
// simulation of the same configuration continues bit for bit as from where it was taken.
// Throws ConfigError for a stage that cannot be saved yet or a state of another configuration.
std::string SimulationState(runner::Simulation& sim, runner::SafetyMonitor* monitor);
void RestoreSimulationState(runner::Simulation& sim, runner::SafetyMonitor* monitor,
                            const std::string& state);

}  // namespace mjf::python

#endif  // MJFORMATION_PYTHON_DRIVEN_HPP_
