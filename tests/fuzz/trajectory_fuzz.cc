// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The leader trajectory CSV (guidance plugin `trajectory`, attribute `file`): read, then flown
// as the plugin flies it (the path interpolated, its reference taken across and beyond the
// table's times), so a file the reader accepts must also give finite references.
#include <cmath>
#include <stdexcept>

#include "fuzz_util.hpp"
#include "mjformation/guidance/trajectory.hpp"

namespace {

mjf::fuzz::ScratchDir& Scratch() {
  static mjf::fuzz::ScratchDir dir;
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > 64 * 1024) return 0;
  using mjf::guidance::TrajectoryGuidance;
  const std::string path = Scratch().Write("leader.csv", mjf::fuzz::AsText(data, size));
  mjf::guidance::TrajectoryTable table;
  try {
    table = mjf::guidance::ReadTrajectoryCsv(path);
  } catch (const std::invalid_argument&) {
    return 0;  // a refusal naming the file, the line and the reason
  }
  const TrajectoryGuidance law(TrajectoryGuidance::Config{}, table);
  const double first = table.t.front(), last = table.t.back();
  for (int k = -1; k <= 9; ++k) {  // before, inside (8 points) and after the table
    const double t = first + (last - first) * k / 8.0;
    const mjf::guidance::GuidanceOutput out = law.Reference(t);
    for (int i = 0; i < 3; ++i) {
      if (!std::isfinite(out.pos[i]) || !std::isfinite(out.vel[i]) || !std::isfinite(out.acc[i]))
        throw std::logic_error("an accepted trajectory gave a non-finite reference");
    }
  }
  return 0;
}
