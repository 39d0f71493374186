// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Partitioned physics ([run] threads = K > 1): the swarm's vehicles split into K MuJoCo models
// of contiguous vehicle ranges, each stepped on its own thread, in lockstep with the one control
// tick that sees the whole swarm (simulation.cc). Valid only when vehicles do not interact
// through MuJoCo (no inter-vehicle contacts, no shared joints): then every vehicle's free-body
// arithmetic in a partition is the arithmetic it had in the whole-swarm model (see
// docs/history/PERFORMANCE_NOTEBOOK.md, "Both cores: partitioned physics", for why the result
// is the same bit for bit).
//
// One step is two lockstep phases, each run by every partition on its own thread (partition 0
// on the caller's):
//   Step1: mj_step1 -> the partition's vehicles' true states
//   (caller: the control tick and the force stages, for the whole swarm)
//   Step2: controls and external forces -> mj_step2 -> motor lag -> state checks
// A failure in any partition (MuJoCo error, warning, non-finite state) is rethrown on the
// caller's thread once every partition has finished the phase.
#ifndef MJFORMATION_SIM_PARTITIONED_PHYSICS_HPP_
#define MJFORMATION_SIM_PARTITIONED_PHYSICS_HPP_

#include <mjformation/plugin.h>
#include <mujoco/mujoco.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "mjformation/config/config_error.hpp"
#include "mjformation/config/experiment.hpp"
#include "mjformation/config/state_archive.hpp"
#include "mjformation/scene/scene.hpp"

namespace mjf::runner {

class LockstepPool;
struct Partition;

using PartitionModels = std::vector<std::unique_ptr<mjModel, ModelDeleter>>;

// Composes and compiles one model per partition from `request` (the whole swarm's scene request:
// only the vehicle range differs), partition k holding vehicles [n k / K, n (k + 1) / K). Their
// text is not written (the whole swarm's scene is the one a run records). Independent of the
// whole swarm's composition, so a caller may run it on another thread meanwhile.
PartitionModels ComposePartitions(int k_parts, const SceneRequest& request);

class PartitionedPhysics {
 public:
  // Binds the vehicles of `models` (ComposePartitions of the same `request`, config.threads
  // partitions). `whole` is the swarm's single model, used to check the split keeps every degree
  // of freedom exactly once. Throws ConfigError (FILE:LINE: [run] threads: ...) when the model
  // cannot be partitioned.
  PartitionedPhysics(const ExperimentConfig& config, const SceneRequest& request,
                     PartitionModels models, const mjfPlugin& attitude,
                     const std::string& vehicle_xml, const mjModel* whole);
  ~PartitionedPhysics();
  PartitionedPhysics(const PartitionedPhysics&) = delete;
  PartitionedPhysics& operator=(const PartitionedPhysics&) = delete;

  int size() const { return static_cast<int>(parts_.size()); }
  // mj_step1 in every partition; the true states of every vehicle into `truth` (sized 1 + N).
  void Step1(std::vector<mjfVehicleState>* truth);
  // Hands the controls ([vehicle][actuator]) and the external forces ([vehicle][3] at each
  // centre of mass, N; nullptr: none) to every partition, integrates (mj_step2), advances the
  // motor lag and checks the new state. `time_after` (s) names the state in messages.
  void Step2(const std::vector<double>& controls, const std::vector<double>* forces,
             double time_after);
  // After Step2 threw: true when the failed partition had integrated (its state check failed,
  // the step was taken), false when mj_step2 itself failed (an engine error).
  bool failed_after_integration() const { return failed_after_integration_; }
  // Runs job(context, first, count, error, error_size) for every partition's vehicle range
  // [first, first + count), each on its partition's thread, with a message buffer of its own
  // (the attitude plugins, simulation.cc). A job's exception is rethrown as Step2's are.
  using RangeJob = void (*)(void* context, int first, int count, char* error, size_t error_size);
  void ForEachRange(RangeJob job, void* context);
  // Copies the partitions' state into the whole-swarm data and positions every body there
  // (kinematics, centres of mass, cameras and lights): what rendering needs.
  void CopyInto(const mjModel* whole, mjData* data) const;
  // Checkpoints (between steps): each partition's MuJoCo integration state (mj_getState,
  // mjSTATE_INTEGRATION) and its actuation's state, in partition order. Throws
  // StateArchiveError when a saved block has another partition's length.
  void VisitState(StateArchive& archive);
  // Partition k's MuJoCo data (tests: a fault raised inside one partition's step).
  mjData* partition_data(int k);

 private:
  enum class Phase { kStep1, kRange, kStep2 };
  void RunPhase(Phase phase);
  void RunPartition(int k, Phase phase);

  std::vector<std::unique_ptr<Partition>> parts_;
  std::unique_ptr<LockstepPool> pool_;
  // Inputs of the current phase (set by the caller before the phase starts).
  std::vector<mjfVehicleState>* truth_ = nullptr;
  const std::vector<double>* controls_ = nullptr;
  const std::vector<double>* forces_ = nullptr;
  double time_after_ = 0;
  RangeJob range_job_ = nullptr;
  void* range_context_ = nullptr;
  bool failed_after_integration_ = false;
};

// Refuses [run] threads values that cannot work, before anything is built: a thread count
// below 1 (the parser already did), inter-vehicle contacts (vehicles would touch each other
// through MuJoCo, which a split cannot see). Warns (stderr) above the machine's cores.
void CheckPartitionable(const ExperimentConfig& config, const mjModel* whole,
                        const std::vector<int>& vehicle_bodies);

}  // namespace mjf::runner

#endif  // MJFORMATION_SIM_PARTITIONED_PHYSICS_HPP_
