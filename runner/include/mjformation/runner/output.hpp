// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The run directory and its files: atomic small files, a streaming timeseries.csv.
#ifndef MJFORMATION_RUNNER_OUTPUT_HPP_
#define MJFORMATION_RUNNER_OUTPUT_HPP_

#include <cstdio>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "mjformation/runner/config.hpp"

namespace mjf::runner {

class Simulation;

class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A run directory. Refuses to reuse a non-empty directory unless `overwrite` (nothing already
// written is lost by accident); creates snapshots/.
class RunDirectory {
 public:
  RunDirectory(const std::string& path, bool overwrite);
  std::string Path(const std::string& name) const { return path_ + "/" + name; }
  // Writes name + ".tmp" then renames: a file is whole or absent.
  void WriteText(const std::string& name, const std::string& text) const;

 private:
  std::string path_;
};

// timeseries.csv (columns: docs/ARCHITECTURE.md), streamed with a bounded buffer so memory does
// not grow with run length.
class TimeseriesWriter {
 public:
  // measured / wind (issue 11): append per vehicle what the controllers measured
  // (uav<i>_px_meas .. _yaw_meas) / the wind it felt (uav<i>_wind_x, _y, _z), after the usual
  // columns; off by default, so existing runs keep their bytes.
  TimeseriesWriter(const std::string& path, int n_vehicles, bool measured = false,
                   bool wind = false);
  ~TimeseriesWriter();
  void Write(const Simulation& sim, double sigma_f, const std::vector<double>& slots);
  void Close();

 private:
  void Flush();
  std::string path_;
  std::FILE* file_ = nullptr;
  std::string buffer_;
  bool measured_ = false, wind_ = false;  // issue 11 columns
};

// The experiment file as run: its text plus the command-line overrides, as a TOML comment.
std::string ConfigEcho(const ExperimentConfig& config);
std::string Sha256Hex(const std::string& bytes);
// A JSON number, or null for NaN/inf (JSON has no NaN).
nlohmann::ordered_json JsonNumber(double value);

}  // namespace mjf::runner

#endif  // MJFORMATION_RUNNER_OUTPUT_HPP_
