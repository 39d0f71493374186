// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/sim/step_checks.hpp"

#include <fmt/format.h>

#include <cmath>
#include <string>

#include "mjformation/control/errors.hpp"

namespace mjf::runner {
namespace {
std::string TimeTag(double time) { return fmt::format("t = {:.3f} s", time); }
}  // namespace

namespace {
// The whole model's index behind a warning's `lastinfo` (a qpos, dof or actuator index for
// these warnings, a count for the others).
int WholeModelInfo(int warning, int info, const StateOffsets& o) {
  switch (warning) {
    case mjWARN_BADQPOS:
      return info + o.qpos;
    case mjWARN_INERTIA:
    case mjWARN_BADQVEL:
    case mjWARN_BADQACC:
      return info + o.dof;
    case mjWARN_BADCTRL:
      return info + o.actuator;
    default:
      return info;
  }
}
}  // namespace

void CheckStepState(const mjModel* m, const mjData* d, double time, StateOffsets offsets) {
  for (int w = 0; w < mjNWARNING; ++w) {
    if (w == mjWARN_VGEOMFULL) continue;  // a rendering matter, not the physics'
    if (d->warning[w].number > 0) {
      std::string text = mju_warningText(w, WholeModelInfo(w, d->warning[w].lastinfo, offsets));
      while (!text.empty() && (text.back() == '.' || text.back() == ' ')) text.pop_back();
      throw SimulationError(TimeTag(time) + ": MuJoCo warning: " + text +
                            " (the simulation is no longer trustworthy)");
    }
  }
  for (int i = 0; i < m->nq; ++i) {
    if (!std::isfinite(d->qpos[i])) {
      throw SimulationError(TimeTag(time) + ": non-finite qpos[" +
                            std::to_string(offsets.qpos + i) + "]");
    }
  }
  for (int i = 0; i < m->nv; ++i) {
    if (!std::isfinite(d->qvel[i])) {
      throw SimulationError(TimeTag(time) + ": non-finite qvel[" + std::to_string(offsets.dof + i) +
                            "]");
    }
  }
}

}  // namespace mjf::runner
