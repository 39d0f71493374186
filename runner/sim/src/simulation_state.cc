// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// What a checkpoint of one simulation holds, and which stages cannot be saved yet
// (docs/ARCHITECTURE.md, "Checkpoint and resume").
#include <algorithm>
#include <string>
#include <vector>

#include "mjformation/sim/simulation.hpp"

namespace mjf::runner {
namespace {

// Refuses a stage the checkpoint does not carry: its name, the key that switched it on, and
// what to do.
[[noreturn]] void Unsavable(const std::string& stage, const std::string& key) {
  throw ConfigError("checkpoints (--checkpoint-every, --resume, get_state): " + stage +
                    " does not save its state yet; " + key +
                    " switches it on: remove it (or set it to its default) to checkpoint this "
                    "run");
}

// A block of doubles whose length is fixed by the configuration: checked on load.
void FixedBlock(StateArchive& archive, const char* what, std::vector<double>* block) {
  const size_t expected = block->size();
  archive(*block);
  if (block->size() != expected) {
    throw StateArchiveError(std::string("the saved state's ") + what + " holds " +
                            std::to_string(block->size()) +
                            " numbers where this configuration has " + std::to_string(expected));
  }
}

}  // namespace

void Simulation::RequireSavable() const {
  // The channel's state is in the control tick's block, whatever its configuration.
  if (!tick_->sensors().saves_state()) Unsavable("the sensor stage", "[sensors]");
  for (const auto& stage : force_stages_) {
    if (!stage->saves_state()) Unsavable("a force stage", "[wind]");
  }
}

void Simulation::VisitState(StateArchive& archive) {
  archive.Tag("simulation");
  archive(step_);
  std::vector<double> physics(static_cast<size_t>(mj_stateSize(model_.get(), mjSTATE_INTEGRATION)));
  if (!archive.loading())
    mj_getState(model_.get(), data_.get(), physics.data(), mjSTATE_INTEGRATION);
  FixedBlock(archive, "MuJoCo state", &physics);
  if (archive.loading())
    mj_setState(model_.get(), data_.get(), physics.data(), mjSTATE_INTEGRATION);
  std::vector<double> tick(tick_->StateSize());
  if (!archive.loading()) tick_->GetState(tick.data());
  FixedBlock(archive, "control tick", &tick);
  if (archive.loading()) tick_->SetState(tick.data());
  tick_->VisitGrowingState(archive);
  actuation_->VisitState(archive);
  if (partitions_) {
    // The partitions hold the swarm's physics; the whole-swarm data is brought up to date
    // from them when next read.
    partitions_->VisitState(archive);
    if (archive.loading()) whole_data_stale_ = true;
  }
  archive.Tag("realism");  // the sensor stage is in the control tick's block
  for (auto& stage : force_stages_) stage->VisitState(archive);
}

void Simulation::VisitStateAtTick(StateArchive& archive) {
  // At a tick the partitions stand between their two phases, which mj_step1 of the whole
  // model cannot restore.
  if (partitions_) Unsavable("partitioned physics at a control tick", "[run] threads > 1");
  VisitState(archive);
  archive.Tag("tick outputs");
  std::vector<mjfVehicleState> measured = tick_->measured();
  std::vector<double> controls = tick_->controls();
  archive(truth_, measured, controls);
  // The forces ComputeActuation added into qfrc_passive (the wrench model's, [wind]'s): a
  // derived quantity to MuJoCo, which mj_step1 below recomputes without them.
  const bool adds_forces = config_.rotor_model == RotorModel::kWrench || !force_stages_.empty();
  std::vector<double> passive;
  if (adds_forces) passive.assign(data_->qfrc_passive, data_->qfrc_passive + model_->nv);
  if (adds_forces) FixedBlock(archive, "passive forces", &passive);
  if (!archive.loading()) return;
  mj_step1(model_.get(), data_.get());
  if (adds_forces) std::copy(passive.begin(), passive.end(), data_->qfrc_passive);
  tick_->RestoreOutputs(step_, measured, controls,
                        reinterpret_cast<const struct mjModel_*>(model_.get()),
                        reinterpret_cast<const struct mjData_*>(data_.get()));
}

}  // namespace mjf::runner
