// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/guidance/trajectory.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "check.hpp"

namespace mjf::guidance {

using check::Num;
using check::Refuse;
using check::RequireFiniteAttribute;
using check::ValidateTracking;

namespace {

// The numbers of one CSV row; false when a cell is not a number (a header line, or an error).
bool ParseNumbers(const std::string& line, std::vector<double>* values) {
  std::stringstream row(line);
  std::string cell;
  while (std::getline(row, cell, ',')) {
    char* end = nullptr;
    const double v = std::strtod(cell.c_str(), &end);
    while (end && (*end == ' ' || *end == '\t')) ++end;
    if (end == cell.c_str() || *end != '\0') return false;
    values->push_back(v);
  }
  return true;
}

// Appends one row t,x,y[,z] to the table after the checks that name the row (`where`); the
// first row fixes the number of columns.
void AppendRow(const std::vector<double>& values, const std::string& where, int* columns,
               TrajectoryTable* table) {
  if (values.size() != 3 && values.size() != 4) {
    Refuse(where + "expected 3 (t,x,y) or 4 (t,x,y,z) columns, got " +
           std::to_string(values.size()));
  }
  if (*columns == 0) *columns = static_cast<int>(values.size());
  if (static_cast<int>(values.size()) != *columns) {
    Refuse(where + "expected " + std::to_string(*columns) + " columns like the first row, got " +
           std::to_string(values.size()));
  }
  for (double v : values) {
    if (!std::isfinite(v)) Refuse(where + "a value is not finite (NaN or inf)");
    // Positions beyond 1e6 m (and times beyond 1e7 s) are typing errors, not a flight plan.
    if (std::fabs(v) > 1e7) Refuse(where + "a value is beyond +-1e7 (t in s, x, y, z in m)");
  }
  if (!table->t.empty() && !(values[0] > table->t.back())) {
    Refuse(where + "t = " + Num(values[0]) + " is not after the previous row's t = " +
           Num(table->t.back()) + " (t must be strictly increasing)");
  }
  table->t.push_back(values[0]);
  table->pos.push_back({values[1], values[2], *columns == 4 ? values[3] : 0.0});
}

}  // namespace

TrajectoryTable ReadTrajectoryCsv(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    Refuse("attribute 'file': '" + path + "' is a folder, not a CSV file");
  }
  std::ifstream in(path);
  if (!in) Refuse("attribute 'file': cannot read '" + path + "'");
  TrajectoryTable table;
  std::string line;
  int line_no = 0, columns = 0;
  bool header_allowed = true;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    const std::string where = "attribute 'file': " + path + ":" + std::to_string(line_no) + ": ";
    std::vector<double> values;
    if (!ParseNumbers(line, &values)) {
      if (header_allowed) {  // the first non-comment line may name the columns
        header_allowed = false;
        continue;
      }
      Refuse(where + "expected numbers t,x,y[,z], got '" + line + "'");
    }
    header_allowed = false;
    AppendRow(values, where, &columns, &table);
  }
  if (table.t.size() < 2) {
    Refuse("attribute 'file': " + path + ": at least two rows t,x,y[,z] are needed (got " +
           std::to_string(table.t.size()) + ")");
  }
  table.has_z = columns == 4;
  return table;
}

TrajectoryGuidance::TrajectoryGuidance(const Config& config, const TrajectoryTable& table)
    : config_(config),
      has_z_(table.has_z),
      path_(table.t, table.pos, CatmullRomVelocities(table.t, table.pos, false), false) {
  config.bounds.Validate();
  ValidateTracking(config.gains, config.altitude, config.yaw);
  RequireFiniteAttribute(config.time_offset, "time_offset");
}

GuidanceOutput TrajectoryGuidance::Reference(double t) const {
  GuidanceOutput ref = path_.Evaluate(t + config_.time_offset);
  if (!has_z_) {
    ref.pos[2] = config_.altitude;
    ref.vel[2] = ref.acc[2] = 0.0;
  }
  ref.yaw = config_.yaw;
  return ref;
}

GuidanceOutput TrajectoryGuidance::Update(double t, const Vec3& pos, const Vec3& vel) const {
  return TrackClamped(Reference(t), pos, vel, config_.gains, config_.bounds);
}

}  // namespace mjf::guidance
