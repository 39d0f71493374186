// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// [formation.shape] -> the core's Shape: the paper's circle, fixed offsets, or a sampled table.
#include "mjformation/config/shape_config.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include "mjformation/config/source_location.hpp"
#include "mjformation/formation/shape.hpp"

namespace mjf::runner {
namespace {

// A table file: a header line, then rows "t, px1, py1, vx1, vy1, px2, ..." (m, m/s).
std::unique_ptr<formation::Shape> ReadTable(const std::string& path, int n) {
  std::ifstream in(path);
  if (!in) throw ConfigError(path + ": cannot open the formation shape table");
  std::vector<double> times, samples;
  std::string line;
  int line_number = 0;
  const size_t columns = 1 + 4 * static_cast<size_t>(n);
  while (std::getline(in, line)) {
    ++line_number;
    if (line.empty() || line[0] == '#') continue;
    std::vector<double> row;
    std::istringstream cells(line);
    std::string cell;
    bool numeric = true;
    while (std::getline(cells, cell, ',')) {
      char* end = nullptr;
      const double v = std::strtod(cell.c_str(), &end);
      if (end == cell.c_str() || !std::isfinite(v)) numeric = false;
      row.push_back(v);
    }
    if (!numeric && times.empty() && line_number == 1) continue;  // the header
    if (!numeric || row.size() != columns) {
      throw ConfigError(path + ":" + std::to_string(line_number) + ": expected " +
                        std::to_string(columns) + " numbers (t, then px, py, vx, vy for each of " +
                        std::to_string(n) + " followers)");
    }
    if (!times.empty() && !(row[0] > times.back())) {
      throw ConfigError(path + ":" + std::to_string(line_number) + ": times must increase");
    }
    times.push_back(row[0]);
    samples.insert(samples.end(), row.begin() + 1, row.end());
  }
  if (times.size() < 2) throw ConfigError(path + ": the shape table needs at least two rows");
  return formation::MakeSampledShape(n, std::move(times), std::move(samples));
}

}  // namespace

std::unique_ptr<formation::Shape> MakeShape(const ExperimentConfig& c) {
  const ShapeConfig& s = c.shape;
  try {
    if (s.type == ShapeType::kCircle) {
      // Section 6: f_i = r [cos(w t + phase0 + (i-1) phase_step), sin(...)].
      const double step = s.phase_step >= 0 ? s.phase_step : 2 * M_PI / c.followers;
      return formation::MakeCircleShape(c.followers, s.radius, s.omega, s.phase0, step);
    }
    if (s.type == ShapeType::kOffsets) {
      std::vector<formation::FollowerTerms> terms(c.followers);
      for (int i = 0; i < c.followers; ++i) {
        terms[i].x.polynomial = {s.offsets[i][0]};
        terms[i].y.polynomial = {s.offsets[i][1]};
      }
      return formation::MakeTermsShape(std::move(terms));
    }
    if (s.type == ShapeType::kTable) return ReadTable(s.file, c.followers);
  } catch (const std::invalid_argument& e) {
    SourceLocation{c.source_path, 0, SectionKey("formation.shape")}.Fail(e.what());
  }
  return nullptr;
}

}  // namespace mjf::runner
