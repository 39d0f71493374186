// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/record/output.hpp"

#include <errno.h>
#include <fcntl.h>
#include <fmt/format.h>
#include <openssl/evp.h>
#include <sys/stat.h>
#include <unistd.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string_view>

#include "mjformation/config/source_location.hpp"
#include "mjformation/record/estimation_metrics.hpp"
#include "mjformation/sim/simulation.hpp"

namespace mjf::runner {
namespace {

namespace fs = std::filesystem;

// Written first into every run directory: what --overwrite checks before it deletes anything.
constexpr const char* kMarker = ".mjformation-run";

bool EndsWith(std::string_view s, std::string_view end) {
  return s.size() >= end.size() && s.compare(s.size() - end.size(), end.size(), end) == 0;
}

// A snapshot as SnapshotRecorder names it (recorders.cc): t<sss.ss>.png, the time with at least
// three digits before the point and two after; with ".tmp", the leftover of an interrupted write.
bool IsSnapshotName(std::string_view name) {
  if (EndsWith(name, ".tmp")) name.remove_suffix(4);
  if (!EndsWith(name, ".png")) return false;
  name.remove_suffix(4);
  if (name.size() < 7 || name.front() != 't') return false;
  name.remove_prefix(1);
  const size_t point = name.size() - 3;
  if (name[point] != '.') return false;
  for (size_t i = 0; i < name.size(); ++i) {
    if (i != point && (name[i] < '0' || name[i] > '9')) return false;
  }
  return true;
}

// The figures analysis/figures.py draws into RUN_DIR/figures (plots.FIGURE_NAMES).
bool IsFigureName(std::string_view name) {
  static const char* const kFigures[] = {"trajectories_xy.png",     "final_positions.png",
                                         "attitude_pitch_roll.png", "attitude_yaw.png",
                                         "sliding_s1.png",          "sigma_f.png"};
  for (const char* f : kFigures) {
    if (name == f) return true;
  }
  return false;
}

// The runner's own files at the top of a run directory, and leftovers of an interrupted atomic
// write.
bool IsRunFileName(std::string_view name) {
  static const char* const kFiles[] = {kMarker,          "config.toml",  "scene.xml",
                                       "timeseries.csv", "summary.json", "video.mp4",
                                       kCheckpointFile};
  for (const char* f : kFiles) {
    if (name == f) return true;
  }
  return EndsWith(name, ".tmp");
}

// Appends to `foreign` what a run directory holds that the runner did not write: the runner's
// files, snapshots/ with the snapshots and figures/ with the analysis' figures are its own;
// anything else is the user's and stops --overwrite. A folder's foreign files are named inside
// it (snapshots/notes.txt), so the user sees which file is in the way. Links are never the
// run's: nothing is followed out of the run directory.
void ListForeignEntries(const fs::path& dir, std::vector<std::string>* foreign) {
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    const bool link = e.is_symlink();
    if (!link && e.is_regular_file() && IsRunFileName(name)) continue;
    const bool snapshots = name == "snapshots", figures = name == "figures";
    if ((snapshots || figures) && !link && e.is_directory()) {
      for (const auto& child : fs::directory_iterator(e.path())) {
        const std::string file = child.path().filename().string();
        const bool own = !child.is_symlink() && child.is_regular_file() &&
                         (snapshots ? IsSnapshotName(file) : IsFigureName(file));
        if (!own) foreign->push_back(name + "/" + file);
      }
      continue;
    }
    foreign->push_back(name);
  }
}

}  // namespace

// Throws OutputError unless `dir` holds the run marker and only entries the runner wrote.
void CheckRunDirectory(const std::string& path) {
  const fs::path dir(path);
  const fs::path marker = dir / kMarker;
  if (fs::is_symlink(marker) || !fs::is_regular_file(marker)) {
    throw OutputError(dir.string() + ": not a mjformation run directory (no " + kMarker +
                      " marker): --overwrite replaces only run directories; nothing was "
                      "deleted. Choose another --out.");
  }
  std::vector<std::string> foreign;
  ListForeignEntries(dir, &foreign);
  if (!foreign.empty()) {
    std::string list;
    for (const auto& f : foreign) list += (list.empty() ? "" : ", ") + f;
    throw OutputError(dir.string() + ": holds files mjformation did not write (" + list +
                      "); --overwrite deletes only a run's own files, so nothing was deleted. "
                      "Move them or choose another --out.");
  }
}

namespace {

// Removes a previous run directory's contents, after checking that it is one and that every
// entry in it is the runner's. Throws OutputError (and deletes nothing) otherwise.
void ClearPreviousRun(const fs::path& dir) {
  CheckRunDirectory(dir.string());
  // remove_all removes a symbolic link itself, never what it points to.
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.path().filename() != kMarker) fs::remove_all(e.path());
  }
}

// Writes finite v as printf's "%.9g" (and fmt's "{:.9g}") would, returning the end: the bytes
// of timeseries.csv. std::to_chars(general, 9) is specified to give exactly those bytes; this
// fast path gives the same at about a third of its cost for 1e-12 <= |v| < 1e14: one correctly
// rounded multiplication or division by an exact power of ten puts the 9 significant digits in
// [1e8, 1e9) with an error below 2e-7, so rounding to an integer is certain unless the fraction
// is within 1e-6 of one half; those (and every other case) go to std::to_chars. Checked equal to
// std::to_chars on 6e7 doubles (random bits, near-ties, powers of ten and their neighbours).
constexpr size_t kFastRoom = 24;  // what the fast path may write past p: 17 bytes + 7 of slack

// "00" to "99": two digits per division instead of one.
constexpr char kDigitPairs[] =
    "000102030405060708091011121314151617181920212223242526272829303132333435363738394041424344"
    "454647484950515253545556575859606162636465666768697071727374757677787980818283848586878889"
    "90919293949596979899";

// The 9 digits of d in [1e8, 1e9) at out[0..8] (out has 16 bytes: the rest zeros), and the
// place of the last one that is not '0' (the trailing zeros "%g" drops).
int NineDigits(uint32_t d, char* out) {
  const uint32_t first = d / 100000000u, rest = d - first * 100000000u;
  const uint32_t high = rest / 10000u, low = rest - high * 10000u;
  out[0] = static_cast<char>('0' + first);
  std::memcpy(out + 1, kDigitPairs + 2 * (high / 100u), 2);
  std::memcpy(out + 3, kDigitPairs + 2 * (high % 100u), 2);
  std::memcpy(out + 5, kDigitPairs + 2 * (low / 100u), 2);
  std::memcpy(out + 7, kDigitPairs + 2 * (low % 100u), 2);
  int last = 8;
  while (last > 0 && out[last] == '0') --last;
  return last;
}

// The digits d.ddd with decimal exponent e as "%g" lays them out (fixed for -4 <= e < 9, else
// d.ddde+XX; |e| < 100 here), at p with kFastRoom bytes of room; fixed-size copies only (what
// lies past the returned end is scratch the next number overwrites).
char* LayOut(const char* digits, int last, int e, char* p) {
  if (e >= 0 && e < 9) {
    std::memcpy(p, digits, 9);  // then the fraction moves one place right for the point
    if (last <= e) return p + e + 1;
    p[e + 1] = '.';
    std::memcpy(p + e + 2, digits + e + 1, 8);
    return p + last + 2;
  }
  if (e < 0 && e >= -4) {
    std::memcpy(p, "0.000", 5);  // "0." and up to three zeros before the first digit
    std::memcpy(p + 1 - e, digits, 9);
    return p + 2 - e + last;
  }
  *p++ = digits[0];
  if (last > 0) {
    *p = '.';
    std::memcpy(p + 1, digits + 1, 8);
    p += last + 1;
  }
  p[0] = 'e';
  p[1] = e < 0 ? '-' : '+';
  std::memcpy(p + 2, kDigitPairs + 2 * (e < 0 ? -e : e), 2);
  return p + 4;
}

}  // namespace

char* FormatG9(char* p, char* end, double v) {
  static constexpr double kPow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                      1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                      1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  const double a = std::fabs(v);
  if (!(a >= 1e-12 && a < 1e14) || end - p < static_cast<ptrdiff_t>(kFastRoom)) {
    return std::to_chars(p, end, v, std::chars_format::general, 9).ptr;
  }
  // e = floor(log10(a)): floor(log10(2) * binary exponent) is e or e - 1. a is normal here, so
  // its binary exponent is its biased exponent field less 1023 (what ilogb returns).
  uint64_t bits;
  std::memcpy(&bits, &a, sizeof(bits));
  int e = ((static_cast<int>(bits >> 52) - 1023) * 78913) >> 18;
  auto scale = [&](int k) { return k >= 0 ? a * kPow10[k] : a / kPow10[-k]; };
  double scaled = scale(8 - e);
  if (scaled >= 1e9 - 1) scaled = scale(8 - ++e);
  // One correctly rounded operation on exact powers of ten: |error| <= 1e9 * 2^-53 < 2e-7.
  if (!(scaled >= 1e8 + 1 && scaled < 1e9 - 1)) {
    return std::to_chars(p, end, v, std::chars_format::general, 9).ptr;
  }
  const uint32_t truncated = static_cast<uint32_t>(scaled);     // floor: scaled > 0
  const double frac = scaled - static_cast<double>(truncated);  // exact
  if (std::fabs(frac - 0.5) < 1e-6)
    return std::to_chars(p, end, v, std::chars_format::general, 9).ptr;
  const uint32_t d = truncated + (frac > 0.5 ? 1 : 0);
  if (d >= 1000000000u) return std::to_chars(p, end, v, std::chars_format::general, 9).ptr;
  char digits[16] = {};
  const int last = NineDigits(d, digits);
  if (std::signbit(v)) *p++ = '-';
  return LayOut(digits, last, e, p);
}

RunDirectory::RunDirectory(const std::string& path, bool overwrite, bool resume) : path_(path) {
  std::error_code ec;
  const fs::path dir(path);
  if (resume) {
    if (!fs::is_regular_file(dir / kMarker) || fs::is_symlink(dir / kMarker)) {
      throw OutputError(path + ": not a mjformation run directory (no " + kMarker +
                        " marker): nothing to resume; run without --resume");
    }
    return;
  }
  try {
    if (fs::exists(dir) && !fs::is_directory(dir)) {
      throw OutputError(path + ": exists and is not a directory; choose another --out");
    }
    if (fs::exists(dir) && !fs::is_empty(dir)) {
      if (!overwrite) {
        throw OutputError(path +
                          ": the run directory exists and is not empty; choose another "
                          "--out or pass --overwrite to replace it");
      }
      ClearPreviousRun(dir);
    }
    fs::create_directories(dir / "snapshots");
  } catch (const fs::filesystem_error& e) {
    throw OutputError(path + ": " + e.code().message());
  }
  WriteText(kMarker,
            "This folder is a mjformation run directory; `mjformation run --overwrite`\n"
            "may replace it. Delete this file to protect the folder from that.\n");
}

void WriteTextFile(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) throw OutputError(tmp + ": cannot write: " + std::strerror(errno));
  const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  if (std::fclose(f) != 0 || !ok || std::rename(tmp.c_str(), path.c_str()) != 0) {
    throw OutputError(path + ": cannot write: " + std::strerror(errno));
  }
}

void RunDirectory::WriteText(const std::string& name, const std::string& text) const {
  WriteTextFile(Path(name), text);
}

TimeseriesWriter::TimeseriesWriter(const std::string& path, int n_vehicles, bool measured,
                                   bool wind, const std::vector<std::string>& extra_columns,
                                   bool estimated, bool resume)
    : path_(path),
      n_extra_(extra_columns.size()),
      measured_(measured),
      wind_(wind),
      estimated_(estimated) {
  // The header is in a resumed run's file already: Rewind opens it once the checkpoint has
  // been read whole, and places the next row.
  if (resume) return;
  fd_ = open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd_ < 0) throw OutputError(path + ": cannot write: " + std::strerror(errno));
  static const char* const kColumns[] = {"px",     "py",   "pz",    "vx",     "vy",
                                         "vz",     "roll", "pitch", "yaw",    "ax_cmd",
                                         "ay_cmd", "sx",   "sy",    "slot_x", "slot_y"};
  buffer_ = "t,sigma_f";
  for (int i = 0; i < n_vehicles; ++i) {
    for (const char* c : kColumns) fmt::format_to(std::back_inserter(buffer_), ",uav{}_{}", i, c);
  }
  // What the controllers measured, and the wind, after every usual column (so that the columns
  // of a run without sensors or wind keep their places).
  static const char* const kMeasured[] = {"px", "py",   "pz",    "vx", "vy",
                                          "vz", "roll", "pitch", "yaw"};
  for (int i = 0; measured_ && i < n_vehicles; ++i) {
    for (const char* c : kMeasured) {
      fmt::format_to(std::back_inserter(buffer_), ",uav{}_{}_meas", i, c);
    }
  }
  // With an estimator: the estimate and its 1-sigma per axis, next to what the controllers saw.
  static const char* const kEstimated[] = {"px", "py", "pz", "vx", "vy", "vz"};
  for (int i = 0; estimated_ && i < n_vehicles; ++i) {
    for (const char* suffix : {"est", "std"}) {
      for (const char* c : kEstimated) {
        fmt::format_to(std::back_inserter(buffer_), ",uav{}_{}_{}", i, c, suffix);
      }
    }
    fmt::format_to(std::back_inserter(buffer_), ",uav{}_nees", i);
  }
  for (int i = 0; wind_ && i < n_vehicles; ++i) {
    fmt::format_to(std::back_inserter(buffer_), ",uav{0}_wind_x,uav{0}_wind_y,uav{0}_wind_z", i);
  }
  for (const auto& c : extra_columns) buffer_ += "," + c;
  buffer_ += "\n";
  length_ = buffer_.size();
}

TimeseriesWriter::~TimeseriesWriter() {
  // Never throws: an unfinished writer (the run failed) keeps what it flushed; Close() is the
  // checked path.
  if (fd_ < 0) return;
  WritePending();
  close(fd_);
}

namespace {

// ",v" as "%.9g", or "," alone (an empty cell) for a non-finite v.
char* Cell(char* p, char* end, double v) {
  *p++ = ',';
  return std::isfinite(v) ? FormatG9(p, end, v) : p;
}

// The _est, _std and _nees cells of every vehicle (13 per vehicle).
char* EstimateCells(const Simulation& sim, char* p, char* end) {
  for (int i = 0; i < sim.n_vehicles(); ++i) {
    const mjfEstimate& e = sim.estimation()->estimates()[i];
    for (double v : e.state.pos) p = Cell(p, end, v);
    for (double v : e.state.vel) p = Cell(p, end, v);
    // sqrt of P's diagonal (an unknown covariance, NaN, gives empty cells)
    for (int k = 0; k < 6; ++k) p = Cell(p, end, std::sqrt(e.covariance[7 * k]));
    const mjfVehicleState& truth = sim.states()[i];
    const double error[6] = {e.state.pos[0] - truth.pos[0], e.state.pos[1] - truth.pos[1],
                             e.state.pos[2] - truth.pos[2], e.state.vel[0] - truth.vel[0],
                             e.state.vel[1] - truth.vel[1], e.state.vel[2] - truth.vel[2]};
    p = Cell(p, end, Nees6(error, e.covariance));  // the full covariance, not its diagonal
  }
  return p;
}

// What a row's per-vehicle cells are formed from.
struct RowInputs {
  const Simulation* sim;
  const std::vector<double>* slots;
};

// Vehicle i's cells of the first block: position, velocity, Euler angles, the horizontal
// command, the sliding variables and its slot (15 numbers).
char* VehicleCells(const RowInputs& in, int i, char* p, char* end) {
  const mjfVehicleState& s = in.sim->states()[i];
  const mjfSetpoint& sp = in.sim->setpoints()[i];
  const auto euler = EulerZYX(s.quat);
  for (double v : s.pos) p = Cell(p, end, v);
  for (double v : s.vel) p = Cell(p, end, v);
  for (double v : euler) p = Cell(p, end, v);
  p = Cell(p, end, sp.acc[0]);
  p = Cell(p, end, sp.acc[1]);
  p = Cell(p, end, sp.sliding[0]);
  p = Cell(p, end, sp.sliding[1]);
  p = Cell(p, end, (*in.slots)[2 * i]);
  return Cell(p, end, (*in.slots)[2 * i + 1]);
}

// Vehicle i's _meas cells: what its controllers measured (9 numbers).
char* MeasuredCells(const RowInputs& in, int i, char* p, char* end) {
  const mjfVehicleState& m = in.sim->measured_states()[i];
  for (double v : m.pos) p = Cell(p, end, v);
  for (double v : m.vel) p = Cell(p, end, v);
  for (double v : EulerZYX(m.quat)) p = Cell(p, end, v);
  return p;
}

constexpr size_t kMaxNumber = 32;  // room per cell: ",-1.23456789e-308" is 17 characters

// Where the partitions' cells of a block wait to be joined (TimeseriesWriter's scratch_,
// range_length_, range_count_).
struct BlockScratch {
  std::vector<char>* bytes;
  std::vector<size_t>* length;  // [first vehicle of a range]: bytes written
  std::vector<int>* count;      // [first vehicle of a range]: vehicles in it
};

// One block of per-vehicle cells (Cells for every vehicle in order) at p; returns the end.
// With partitioned physics the partitions' threads form their own vehicles' cells at once, each
// into its own stretch of scratch (kMaxNumber bytes per number: room for the longest), and the
// caller joins the stretches in vehicle order: the same bytes as the one-thread loop, with the
// formatting (most of a row's cost) off the caller's thread.
template <char* (*Cells)(const RowInputs&, int, char*, char*)>
char* Block(const RowInputs& in, int per_vehicle, const BlockScratch& scratch, char* p, char* end) {
  const Simulation& sim = *in.sim;
  const int n = sim.n_vehicles();
  if (sim.threads() == 1) {
    for (int i = 0; i < n; ++i) p = Cells(in, i, p, end);
    return p;
  }
  const size_t stride = kMaxNumber * static_cast<size_t>(per_vehicle);
  scratch.bytes->resize(stride * n);  // the first row only: later rows reuse the room
  scratch.length->resize(n);
  scratch.count->resize(n);
  struct Job {
    const RowInputs* in;
    char* base;
    size_t stride;
    size_t* length;
    int* count;
  } job{&in, scratch.bytes->data(), stride, scratch.length->data(), scratch.count->data()};
  sim.ForEachVehicleRange(
      [](void* context, int first, int count, char*, size_t) {
        const Job& j = *static_cast<Job*>(context);
        char* const start = j.base + first * j.stride;
        char* q = start;
        for (int i = first; i < first + count; ++i)
          q = Cells(*j.in, i, q, start + count * j.stride);
        j.length[first] = static_cast<size_t>(q - start);
        j.count[first] = count;
      },
      &job);
  for (int first = 0; first < n; first += job.count[first]) {
    std::memcpy(p, job.base + first * stride, job.length[first]);
    p += job.length[first];
  }
  return p;
}

}  // namespace

void TimeseriesWriter::Write(const Simulation& sim, double sigma_f,
                             const std::vector<double>& slots, const double* extra) {
  // Numbers as "%.9g" (FormatG9: the bytes fmt's "{:.9g}" gave, at an eighth of its cost); a
  // row is written into the buffer's spare room directly, with no per-character appends. The
  // room stays allocated between rows and flushes: growing it (which zero-fills) happens for the
  // first rows only.
  const size_t numbers =
      2 +
      (15 + 9 * measured_ + 13 * estimated_ + 3 * wind_) * static_cast<size_t>(sim.n_vehicles()) +
      n_extra_;
  const size_t room = length_ + kMaxNumber * numbers + 1;
  if (buffer_.size() < room) buffer_.resize(room);
  char* p = buffer_.data() + length_;
  char* const end = buffer_.data() + room;
  auto number = [&](double v) {
    *p++ = ',';
    if (std::isfinite(v)) p = FormatG9(p, end, v);
    // else an empty cell: not applicable
  };
  p = std::to_chars(p, end, sim.time(), std::chars_format::fixed, 6).ptr;
  number(sigma_f);
  const RowInputs in{&sim, &slots};
  const BlockScratch scratch{&scratch_, &range_length_, &range_count_};
  p = Block<VehicleCells>(in, 15, scratch, p, end);
  if (measured_) p = Block<MeasuredCells>(in, 9, scratch, p, end);  // the _meas columns
  if (estimated_ && sim.estimation()) p = EstimateCells(sim, p, end);
  for (int i = 0; wind_ && i < sim.n_vehicles(); ++i) {
    for (double v : sim.wind()[i]) number(v);
  }
  for (size_t k = 0; k < n_extra_ && extra; ++k) number(extra[k]);
  *p++ = '\n';
  length_ = static_cast<size_t>(p - buffer_.data());
  if (length_ > (1u << 20)) Flush();
}

int TimeseriesWriter::WritePending() {
  size_t done = 0;
  while (done < length_) {
    const ssize_t n = write(fd_, buffer_.data() + done, length_ - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int error = n < 0 ? errno : EIO;
      KeepWholeRows(done);
      length_ = 0;  // what did not fit is lost; the whole rows before it are on disk
      return error;
    }
    done += static_cast<size_t>(n);
  }
  length_ = 0;
  written_ += done;
  return 0;
}

void TimeseriesWriter::KeepWholeRows(size_t done) {
  // The last line break among the bytes that reached the file ends the last whole row: a reader
  // (replay, Run.timeseries) then meets a shorter file, never a row with cells missing.
  const size_t whole = std::string_view(buffer_.data(), done).rfind('\n');
  written_ += whole == std::string_view::npos ? 0 : whole + 1;
  // A device (/dev/full) cannot be cut back and holds no rows to cut; a file can.
  if (ftruncate(fd_, static_cast<off_t>(written_)) == 0) {
    lseek(fd_, static_cast<off_t>(written_), SEEK_SET);
  }
}

void TimeseriesWriter::Flush() {
  const int error = WritePending();
  if (error != 0) throw OutputError(path_ + ": write failed: " + std::strerror(error));
}

uint64_t TimeseriesWriter::Checkpoint() {
  Flush();
  return written_;
}

void TimeseriesWriter::Rewind(uint64_t length) {
  if (fd_ < 0) fd_ = open(path_.c_str(), O_RDWR | O_CLOEXEC);
  if (fd_ < 0) throw OutputError(path_ + ": cannot write: " + std::strerror(errno));
  struct stat info {};
  if (fstat(fd_, &info) != 0 || static_cast<uint64_t>(info.st_size) < length) {
    throw OutputError(path_ + ": shorter than the checkpoint recorded (" + std::to_string(length) +
                      " bytes): the run directory was changed since; start the run afresh "
                      "(--overwrite) instead of --resume");
  }
  if (ftruncate(fd_, static_cast<off_t>(length)) != 0 ||
      lseek(fd_, static_cast<off_t>(length), SEEK_SET) < 0) {
    throw OutputError(path_ + ": cannot cut back to the checkpoint: " + std::strerror(errno));
  }
  written_ = length;
}

void TimeseriesWriter::Close() {
  if (fd_ < 0) return;
  Flush();
  const int fd = fd_;
  fd_ = -1;
  if (close(fd) != 0) throw OutputError(path_ + ": close failed: " + std::strerror(errno));
}

std::string ConfigEcho(const ExperimentConfig& config) {
  // The file's name only: the same experiment run from another folder gives the same bytes.
  const std::string name = config.source_path.substr(config.source_path.find_last_of('/') + 1);
  std::string echo = "# Experiment file " + name + " as run by mjformation.\n";
  if (config.overrides.empty()) return echo + config.source_text;
  // With --set overrides the merged table is what ran (comments of the original are lost).
  // Each override on one comment line, whatever it holds: no text given on the command line can
  // end the comment and become a line of TOML.
  for (const auto& o : config.overrides) echo += "# with --set " + OneLineEscaped(o) + "\n";
  return echo + config.effective_text;
}

std::string Sha256Hex(const std::string& bytes) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int size = 0;
  EVP_Digest(bytes.data(), bytes.size(), digest, &size, EVP_sha256(), nullptr);
  std::string hex;
  for (unsigned int i = 0; i < size; ++i) hex += fmt::format("{:02x}", digest[i]);
  return hex;
}

nlohmann::ordered_json JsonNumber(double value) {
  return std::isfinite(value) ? nlohmann::ordered_json(value) : nlohmann::ordered_json(nullptr);
}

}  // namespace mjf::runner
