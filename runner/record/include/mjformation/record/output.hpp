// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The run directory and its files: atomic small files, a streaming timeseries.csv.
#ifndef MJFORMATION_RECORD_OUTPUT_HPP_
#define MJFORMATION_RECORD_OUTPUT_HPP_

#include <cstdint>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "mjformation/config/experiment.hpp"

namespace mjf::runner {

class Simulation;

class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Writes `text` to path.tmp, then renames it to `path`: a reader never sees half a file, and a
// failed write leaves the previous file. Throws OutputError naming the file and the reason.
void WriteTextFile(const std::string& path, const std::string& text);

// Throws OutputError (naming the folder and what is wrong) unless `dir` is a run directory:
// its .mjformation-run marker is there and every entry is one the runner writes. What a
// sweep's --overwrite / --resume check before they touch a run folder.
void CheckRunDirectory(const std::string& dir);

// A run directory. Refuses to reuse a non-empty directory unless `overwrite` (nothing already
// written is lost by accident); creates snapshots/.
// The last checkpoint of a run (run --checkpoint-every), in its run directory.
inline constexpr const char* kCheckpointFile = "checkpoint.mjfstate";

class RunDirectory {
 public:
  // resume: the run directory of a checkpointed run, opened as it is (it must be one: the
  // marker and only the runner's own files); nothing is deleted.
  RunDirectory(const std::string& path, bool overwrite, bool resume = false);
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
  // measured / wind: append per vehicle what the controllers measured
  // (uav<i>_px_meas .. _yaw_meas) / the wind it felt (uav<i>_wind_x, _y, _z); extra_columns:
  // further names (e.g. leader_ax, leader_ay), all after the usual columns and only when
  // switched on, so existing runs keep their bytes. estimated: after the _meas columns, each
  // vehicle's estimate (uav<i>_{px..vz}_est) and its standard deviation from the covariance's
  // diagonal (uav<i>_{px..vz}_std) and the NEES of (p, v) against the truth (uav<i>_nees), for
  // an [estimator] other than passthrough.
  TimeseriesWriter(const std::string& path, int n_vehicles, bool measured = false,
                   bool wind = false, const std::vector<std::string>& extra_columns = {},
                   bool estimated = false, bool resume = false);
  ~TimeseriesWriter();
  // Checkpoints: Checkpoint() puts every row written so far on disk and returns the file's
  // length; a writer made with `resume` opens nothing until Rewind(length) opens the existing
  // file (its header is there) and cuts it back to a checkpoint's length (the rows after it are
  // written again).
  uint64_t Checkpoint();
  void Rewind(uint64_t length);
  // extra: one value per extra column (NaN: an empty cell), or nullptr when there are none.
  void Write(const Simulation& sim, double sigma_f, const std::vector<double>& slots,
             const double* extra = nullptr);
  void Close();

 private:
  // Writes the rows not yet written and returns 0, or the failed write's errno after cutting
  // the file back to its last whole row (the file never ends in part of a row).
  int WritePending();
  // After a write that put only `done` of the pending bytes in the file.
  void KeepWholeRows(size_t done);
  // WritePending, throwing OutputError on a failed write.
  void Flush();
  std::string path_;
  int fd_ = -1;
  uint64_t written_ = 0;  // the file's length: whole rows (and the header) only
  std::string buffer_;    // [0, length_): rows not yet written; the rest: room for the next row
  size_t length_ = 0;
  // Partitioned physics: the partitions' cells of a block before they are joined (output.cc,
  // Block): [first vehicle of a range] its bytes and its vehicles.
  std::vector<char> scratch_;
  std::vector<size_t> range_length_;
  std::vector<int> range_count_;
  size_t n_extra_ = 0;
  bool measured_ = false, wind_ = false;  // the [sensors] / [wind] columns
  bool estimated_ = false;                // the [estimator] columns
};

// Writes finite v as std::to_chars(general, precision 9) would (printf's "%.9g") at p and
// returns the end: the number format of timeseries.csv, at a fraction of to_chars' cost.
char* FormatG9(char* p, char* end, double v);

// The experiment file as run: its text plus the command-line overrides, as a TOML comment.
std::string ConfigEcho(const ExperimentConfig& config);
std::string Sha256Hex(const std::string& bytes);
// A JSON number, or null for NaN/inf (JSON has no NaN).
nlohmann::ordered_json JsonNumber(double value);

}  // namespace mjf::runner

#endif  // MJFORMATION_RECORD_OUTPUT_HPP_
