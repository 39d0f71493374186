// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/sim/step_checks.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <cstring>
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

// True when x[0..n) are all finite. Each value's exponent field is all ones exactly for
// infinities and NaN, and adding 1 to the field then carries into the sign bit; OR-ing the
// sums keeps one flag for the whole array, without a branch per value (the loops below, which
// name the first non-finite value, run only when it is set).
bool AllFinite(const mjtNum* x, int n) {
  constexpr uint64_t kExponent = 0x7ff0000000000000ull, kOneInExponent = 0x0010000000000000ull;
  uint64_t flag = 0;
  for (int i = 0; i < n; ++i) {
    uint64_t bits;
    std::memcpy(&bits, x + i, sizeof(bits));
    flag |= (bits & kExponent) + kOneInExponent;
  }
  return (flag >> 63) == 0;
}
}  // namespace

void CheckStepState(const mjModel* m, const mjData* d, double time, StateOffsets offsets) {
  for (int w = 0; w < mjNWARNING; ++w) {
    if (d->warning[w].number > 0) {
      std::string text = mju_warningText(w, WholeModelInfo(w, d->warning[w].lastinfo, offsets));
      while (!text.empty() && (text.back() == '.' || text.back() == ' ')) text.pop_back();
      throw SimulationError(TimeTag(time) + ": MuJoCo warning: " + text +
                            " (the simulation is no longer trustworthy)");
    }
  }
  if (AllFinite(d->qpos, m->nq) && AllFinite(d->qvel, m->nv)) return;
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
