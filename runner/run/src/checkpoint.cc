// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/run/checkpoint.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "mjformation/config/config_error.hpp"
#include "mjformation/record/output.hpp"
#include "mjformation/time_steps.hpp"

namespace mjf::runner {
namespace {

// The first words of every checkpoint: another file, or a checkpoint of another layout, is
// refused by name. Layout 3: the wind's and the wrench rotor model's forces go into
// qfrc_passive (recomputed every step) instead of qfrc_applied, which a checkpoint carries: a
// layout-2 checkpoint of such a run would add them a second time every step; and a faulted
// wrench model's motor lags are saved. Layout 4: the control tick's block stores the plugin
// ABI's vehicle states and estimates field by field (doubles as themselves), not as 32-bit
// halves, so a layout-3 block has another length. Layout 5: the file ends with the SHA-256 of
// everything before it, checked before any of it is read (a flipped bit in a number would
// otherwise load and resume into another run).
constexpr int kFormatNumber = 5;
constexpr const char* kFormatPrefix = "mjformation checkpoint ";
const std::string kFormat = kFormatPrefix + std::to_string(kFormatNumber);
// The checksum's place: the last bytes of the file, the hex digits of Sha256Hex.
constexpr size_t kChecksumChars = 64;

std::string ReadWholeFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw ConfigError(path + ": no checkpoint to resume from (" + std::strerror(errno) +
                      "): run with --checkpoint-every S first, or without --resume");
  }
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// Writes `bytes` to path + ".tmp", forces it to disk and renames it over `path`: a kill at any
// moment leaves either the previous checkpoint or this one, whole.
void WriteAtomically(const std::string& path, const std::string& bytes) {
  const std::string tmp = path + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) throw OutputError(tmp + ": cannot write: " + std::strerror(errno));
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int error = errno;
      ::close(fd);
      throw OutputError(tmp + ": write failed: " + std::strerror(error));
    }
    done += static_cast<size_t>(n);
  }
  const bool synced = ::fsync(fd) == 0;
  if (::close(fd) != 0 || !synced || std::rename(tmp.c_str(), path.c_str()) != 0) {
    throw OutputError(path + ": cannot write: " + std::strerror(errno));
  }
}

// True when `bytes` end with the SHA-256 of what comes before.
bool ChecksumHolds(const std::string& bytes) {
  if (bytes.size() < kChecksumChars) return false;
  const size_t payload = bytes.size() - kChecksumChars;
  return bytes.compare(payload, kChecksumChars, Sha256Hex(bytes.substr(0, payload))) == 0;
}

// Refuses a file whose checksum does not hold, saying why as closely as its first words tell:
// a checkpoint of another format (an older build's has no checksum), or a damaged file.
[[noreturn]] void RefuseUnverified(const std::string& path, const std::string& bytes) {
  std::string first;
  try {
    StateArchive probe(bytes);
    probe(first);
  } catch (const StateArchiveError&) {
    first.clear();
  }
  const std::string prefix = kFormatPrefix;
  if (first.compare(0, prefix.size(), prefix) == 0 && first != kFormat) {
    throw ConfigError(path + ": a checkpoint of format " +
                      PrintableExcerpt(first.substr(prefix.size())) +
                      ", where this build reads format " + std::to_string(kFormatNumber) +
                      ": a checkpoint resumes a run of the build that wrote it; start the run "
                      "afresh with --overwrite");
  }
  const std::string what = first == kFormat ? "the checkpoint is damaged"
                                            : "not a mjformation checkpoint, or a damaged one";
  throw ConfigError(path + ": " + what +
                    " (its SHA-256 does not match its contents): it cannot be resumed; start "
                    "the run afresh with --overwrite");
}

void VisitRecording(StateArchive& archive, OnlineMetrics& metrics,
                    std::vector<std::unique_ptr<Recorder>>& recorders) {
  archive.Tag("metrics");
  archive(metrics);
  size_t n = recorders.size();
  archive(n);
  if (n != recorders.size()) {
    throw StateArchiveError("the checkpoint holds " + std::to_string(n) +
                            " recorders where this run has " + std::to_string(recorders.size()) +
                            " (were --no-render or the render settings changed?)");
  }
  for (auto& r : recorders) r->VisitState(archive);
  archive.Tag("end");
}

}  // namespace

void RequireCheckpointable(const Simulation& sim, bool render) {
  sim.RequireSavable();
  if (render && sim.config().render.video) {
    throw ConfigError(
        "checkpoints (--checkpoint-every, --resume): the video (an ffmpeg stream) cannot be "
        "continued; [render] video = true switches it on: set it to false or run with "
        "--no-render");
  }
}

StateArchive ReadCheckpoint(const CheckpointPlan& plan) {
  std::string bytes = ReadWholeFile(plan.path);
  if (!ChecksumHolds(bytes)) RefuseUnverified(plan.path, bytes);
  bytes.resize(bytes.size() - kChecksumChars);
  StateArchive archive(std::move(bytes));
  try {
    archive.Tag(kFormat);
  } catch (const StateArchiveError&) {
    throw ConfigError(plan.path + ": not a mjformation checkpoint of format " +
                      std::to_string(kFormatNumber));
  }
  std::string sha;
  archive(sha);
  if (sha != plan.config_sha256) {
    throw ConfigError(plan.path +
                      ": the checkpoint was taken with another configuration (config "
                      "sha256 " +
                      sha + "), this run's is " + plan.config_sha256 +
                      ": resume with the same experiment file and --set options, or start "
                      "afresh with --overwrite");
  }
  return archive;
}

void ResumeSimulation(const CheckpointPlan& plan, StateArchive& archive, Simulation& sim) {
  try {
    sim.VisitState(archive);
  } catch (const StateArchiveError& e) {
    throw ConfigError(plan.path + ": " + e.what());
  }
}

void ResumeRecording(const CheckpointPlan& plan, StateArchive& archive, OnlineMetrics& metrics,
                     std::vector<std::unique_ptr<Recorder>>& recorders) {
  try {
    VisitRecording(archive, metrics, recorders);
    if (!archive.at_end()) {
      throw StateArchiveError("the checkpoint holds more than this run reads");
    }
  } catch (const StateArchiveError& e) {
    throw ConfigError(plan.path + ": " + e.what());
  }
}

void WriteCheckpoint(const CheckpointPlan& plan, Simulation& sim, OnlineMetrics& metrics,
                     std::vector<std::unique_ptr<Recorder>>& recorders) {
  StateArchive archive;
  archive.Tag(kFormat);
  std::string sha = plan.config_sha256;
  archive(sha);
  sim.VisitState(archive);
  VisitRecording(archive, metrics, recorders);
  WriteAtomically(plan.path, archive.bytes() + Sha256Hex(archive.bytes()));
}

bool CheckpointDue(const CheckpointPlan& plan, const Simulation& sim, int64_t step) {
  if (plan.every_s <= 0 || step <= 0 || step >= sim.total_steps()) return false;
  const int64_t every = std::max<int64_t>(1, NearestSteps(plan.every_s, sim.config().timestep));
  return step % every == 0;
}

void KillPointForTests(int64_t step) {
  static const int64_t kill_at = [] {
    const char* text = std::getenv("MJF_TEST_KILL_AT_STEP");
    return text ? std::strtoll(text, nullptr, 10) : int64_t{-1};
  }();
  if (step == kill_at) std::raise(SIGKILL);
}

}  // namespace mjf::runner
