// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Checkpoint and resume of a run (run --checkpoint-every S, --resume; docs/ARCHITECTURE.md,
// "Checkpoint and resume"). A checkpoint is one file in the run directory, replaced atomically
// (temporary file, fsync, rename: a killed writer leaves the previous checkpoint whole), that
// holds, taken between two steps: the config's sha256, the simulation's state (the step,
// MuJoCo's integration state with plugin_state, the control tick's bus and every plugin
// instance's ABI state, the actuation's state), the online metrics and every recorder's state
// (accumulators, the length of timeseries.csv); and it ends with the SHA-256 of all that.
#ifndef MJFORMATION_RUN_CHECKPOINT_HPP_
#define MJFORMATION_RUN_CHECKPOINT_HPP_

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "mjformation/config/state_archive.hpp"
#include "mjformation/record/metrics.hpp"
#include "mjformation/record/recorders.hpp"
#include "mjformation/sim/simulation.hpp"

namespace mjf::runner {

// What a run checkpoints or resumes from.
struct CheckpointPlan {
  double every_s = 0;   // > 0: a checkpoint every so many simulated seconds
  bool resume = false;  // continue from the run directory's checkpoint
  std::string path;     // the checkpoint file (RunDirectory::Path(kCheckpointFile))
  std::string config_sha256;
};

// Throws ConfigError when the run cannot be checkpointed: the stage and the key that switches
// it on (Simulation::RequireSavable), or video (it cannot be continued).
void RequireCheckpointable(const Simulation& sim, bool render);

// A resume reads and checks the whole checkpoint before the run directory is written to: a
// damaged or foreign checkpoint, or one of another run, throws ConfigError naming the file and
// leaves every file as it was. The steps, in order:
//
// The checkpoint of `plan`, read and checked: its checksum (a damaged file is refused before
// any of it is read), its format (another format names both numbers) and its config hash
// against the run's (a mismatch names both hashes). The archive is left at the simulation's
// state.
StateArchive ReadCheckpoint(const CheckpointPlan& plan);
// Loads the simulation's state from the archive; leaves it at the metrics' state.
void ResumeSimulation(const CheckpointPlan& plan, StateArchive& archive, Simulation& sim);
// Loads the metrics' and the recorders' states from the archive, to its end (the number of
// recorders must be this run's). Touches no file: Recorder::ResumeFiles then continues them.
void ResumeRecording(const CheckpointPlan& plan, StateArchive& archive, OnlineMetrics& metrics,
                     std::vector<std::unique_ptr<Recorder>>& recorders);

// Writes a checkpoint of everything, atomically, at the current step (between steps).
void WriteCheckpoint(const CheckpointPlan& plan, Simulation& sim, OnlineMetrics& metrics,
                     std::vector<std::unique_ptr<Recorder>>& recorders);

// The steps at which a run with `every_s` writes checkpoints: multiples of every_s's nearest
// whole number of steps, not the first step or the last.
bool CheckpointDue(const CheckpointPlan& plan, const Simulation& sim, int64_t step);

// For the command-line tests only: with MJF_TEST_KILL_AT_STEP=K in the environment, the
// process sends itself SIGKILL at the start of step K (a kill at a known place, so that a
// resumed run can be compared with an uninterrupted one deterministically).
void KillPointForTests(int64_t step);

}  // namespace mjf::runner

#endif  // MJFORMATION_RUN_CHECKPOINT_HPP_
