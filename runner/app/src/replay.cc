// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/app/replay.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "mjformation/scene/scene.hpp"

namespace mjf::runner {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kTrailPeriod = 0.1;  // s, run.cc samples trails every 0.1 s

std::string ReadText(const std::string& path, const char* what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ReplayError(path + ": cannot read the run's " + what);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

std::vector<std::string> SplitCsv(const std::string& line) {
  std::vector<std::string> out;
  size_t start = 0;
  while (true) {
    const size_t comma = line.find(',', start);
    out.push_back(line.substr(start, comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

// [render], [vehicles] altitude, [formation.shape] and [run] name of the run's config.toml;
// defaults as the runner's (config.hpp) where a key is absent.
void ReadConfig(const std::string& path, Recording* r) {
  toml::table t;
  try {
    t = toml::parse(ReadText(path, "configuration"), path);
  } catch (const toml::parse_error& e) {
    throw ReplayError(path + ": " + std::string(e.description()));
  }
  RenderConfig& v = r->render;
  const auto render = t["render"];
  v.width = render["width"].value_or(v.width);
  v.height = render["height"].value_or(v.height);
  const std::string camera = render["camera"].value_or(std::string(ToString(v.camera)));
  v.camera = camera == "leader"  ? CameraMode::kLeader
             : camera == "fixed" ? CameraMode::kFixed
                                 : CameraMode::kFollow;
  v.distance = render["distance"].value_or(v.distance);
  v.azimuth = render["azimuth"].value_or(v.azimuth);
  v.elevation = render["elevation"].value_or(v.elevation);
  if (const toml::array* a = render["lookat"].as_array(); a && a->size() == 3) {
    for (int k = 0; k < 3; ++k) v.lookat[k] = a->get(k)->value_or(0.0);
  }
  v.shadows = render["shadows"].value_or(v.shadows);
  v.trail_seconds = render["trail_seconds"].value_or(v.trail_seconds);
  v.video_fps = render["video_fps"].value_or(v.video_fps);
  v.video_shadows = render["video_shadows"].value_or(v.video_shadows);
  v.video_width = render["video_width"].value_or(v.video_width);
  v.video_height = render["video_height"].value_or(v.video_height);
  if (const toml::array* a = render["snapshots"].as_array()) {
    for (const auto& x : *a) v.snapshots.push_back(x.value_or(0.0));
  }
  r->altitude = t["vehicles"]["altitude"].value_or(5.0);
  const auto shape = t["formation"]["shape"];
  if (shape["type"].value_or(std::string("circle")) == "circle") {
    r->ring_radius = shape["radius"].value_or(10.0);
  }
  r->name = t["run"]["name"].value_or(std::string());
}

}  // namespace

int Recording::Frame(double time) const {
  int best = 0;
  for (int k = 1; k < static_cast<int>(t.size()); ++k) {
    if (std::abs(t[k] - time) < std::abs(t[best] - time)) best = k;
  }
  return best;
}

namespace {

// summary.json's experiment name, else the run folder's name.
std::string RecordedName(const std::string& run_dir) {
  std::ifstream in(run_dir + "/summary.json");
  nlohmann::json s = nlohmann::json::parse(in, nullptr, false);
  if (!s.is_discarded() && s.contains("experiment") && s["experiment"].is_string()) {
    return s["experiment"].get<std::string>();
  }
  return run_dir.substr(run_dir.find_last_of('/') + 1);
}

// summary.json's safety events (none when absent or unreadable: the pictures then just lack
// the marks; the numbers are read from timeseries.csv alone).
std::vector<Recording::Event> RecordedEvents(const std::string& run_dir) {
  std::vector<Recording::Event> out;
  std::ifstream in(run_dir + "/summary.json");
  const nlohmann::json s = nlohmann::json::parse(in, nullptr, false);
  if (s.is_discarded() || !s.contains("events") || !s["events"].contains("list")) return out;
  for (const auto& e : s["events"]["list"]) {
    try {
      out.push_back({e.at("kind").get<std::string>(), e.at("time_s").get<double>(),
                     e.at("vehicles").get<std::vector<int>>()});
    } catch (const nlohmann::json::exception&) {
      continue;  // a malformed entry is not drawn
    }
  }
  return out;
}

int ColumnOf(const std::vector<std::string>& header, const std::string& name) {
  for (size_t k = 0; k < header.size(); ++k) {
    if (header[k] == name) return static_cast<int>(k);
  }
  return -1;
}

// Per vehicle, the columns of px, py, pz, roll, pitch, yaw, slot_x, slot_y in `header`.
std::vector<std::array<int, 8>> VehicleColumns(const std::vector<std::string>& header,
                                               const std::string& csv_path) {
  auto column = [&](const std::string& name) { return ColumnOf(header, name); };
  const char* const kPerVehicle[] = {"px", "py", "pz", "roll", "pitch", "yaw", "slot_x", "slot_y"};
  std::vector<std::array<int, 8>> cols;
  for (int i = 0; column(fmt::format("uav{}_px", i)) >= 0; ++i) {
    std::array<int, 8> c;
    for (int k = 0; k < 8; ++k) {
      c[k] = column(fmt::format("uav{}_{}", i, kPerVehicle[k]));
      if (c[k] < 0) {
        throw ReplayError(csv_path + ": no column uav" + std::to_string(i) + "_" + kPerVehicle[k]);
      }
    }
    cols.push_back(c);
  }
  return cols;
}

// A cell of the time series: empty (NaN, as the writer leaves it) or a finite number of
// plausible size; anything else is refused, naming the row and the column.
double Cell(const std::vector<std::string>& f, int k, const std::string& where,
            const std::vector<std::string>& header) {
  if (f[k].empty()) return kNaN;
  char* end = nullptr;
  const double v = std::strtod(f[k].c_str(), &end);
  if (end != f[k].c_str() + f[k].size() || !std::isfinite(v) || std::fabs(v) > 1e9) {
    throw ReplayError(where + ": column " + header[k] + ": '" + f[k] +
                      "' is not a finite number within 1e9");
  }
  return v;
}

// One row of the time series appended to `r`.
void AppendRow(const std::vector<std::string>& f, int ct, int cs,
               const std::vector<std::array<int, 8>>& cols, const std::string& where,
               const std::vector<std::string>& header, Recording* r) {
  auto num = [&](int k) { return Cell(f, k, where, header); };
  r->t.push_back(num(ct));
  r->sigma_f.push_back(cs >= 0 ? num(cs) : kNaN);
  std::vector<Vec3> p, a;
  std::vector<std::array<double, 2>> s;
  for (const auto& c : cols) {
    p.push_back({num(c[0]), num(c[1]), num(c[2])});
    a.push_back({num(c[3]), num(c[4]), num(c[5])});
    s.push_back({num(c[6]), num(c[7])});
  }
  r->pos.push_back(std::move(p));
  r->rpy.push_back(std::move(a));
  r->slot.push_back(std::move(s));
}

}  // namespace

Recording LoadRecording(const std::string& run_dir) {
  Recording r;
  r.dir = run_dir;
  ReadConfig(run_dir + "/config.toml", &r);
  r.name = RecordedName(run_dir);
  r.events = RecordedEvents(run_dir);

  const std::string csv_path = run_dir + "/timeseries.csv";
  std::istringstream csv(ReadText(csv_path, "recorded states"));
  std::string line;
  if (!std::getline(csv, line)) throw ReplayError(csv_path + ": empty");
  const std::vector<std::string> header = SplitCsv(line);
  const std::vector<std::array<int, 8>> cols = VehicleColumns(header, csv_path);
  const int ct = ColumnOf(header, "t"), cs = ColumnOf(header, "sigma_f");
  if (ct < 0 || cols.empty()) throw ReplayError(csv_path + ": no t or uav0_px column");
  r.n_vehicles = static_cast<int>(cols.size());
  int row = 1;
  while (std::getline(csv, line)) {
    ++row;
    if (line.empty()) continue;
    const std::vector<std::string> f = SplitCsv(line);
    if (f.size() != header.size()) {
      throw ReplayError(csv_path + ":" + std::to_string(row) + ": " + std::to_string(f.size()) +
                        " fields, the header has " + std::to_string(header.size()));
    }
    AppendRow(f, ct, cs, cols, csv_path + ":" + std::to_string(row), header, &r);
    if (!std::isfinite(r.t.back())) {
      throw ReplayError(csv_path + ":" + std::to_string(row) + ": column t is empty");
    }
  }
  if (r.t.empty()) throw ReplayError(csv_path + ": no recorded rows");
  return r;
}

ReplayScene::ReplayScene(const Recording& recording) : rec_(recording) {
  const std::string scene_path = rec_.dir + "/scene.xml";
  model_ = CompileModel(ReadText(scene_path, "scene"), scene_path);
  data_ = mj_makeData(model_);
  mj_kinematics(model_, data_);  // at qpos0: the slide joints' axes and rest positions
  for (int i = 0; i < rec_.n_vehicles; ++i) {
    const std::string prefix = VehiclePrefix(i);
    const int body = mj_name2id(model_, mjOBJ_BODY, (prefix + "vehicle").c_str());
    const int site = mj_name2id(model_, mjOBJ_SITE, (prefix + "imu").c_str());
    VehicleJoints joints;
    if (body >= 0 && site >= 0 && model_->site_bodyid[site] == body)
      joints = BindJoints(body, site);
    if (joints.free_qpos < 0 && joints.slide_qpos.size() != 3) {
      Free();
      throw ReplayError(scene_path + ": no body " + prefix + "vehicle with a free joint or three " +
                        "slide joints and its site " + prefix + "imu for vehicle " +
                        std::to_string(i) + " of timeseries.csv");
    }
    joints_.push_back(std::move(joints));
    imu_offset_.push_back({model_->site_pos[3 * site], model_->site_pos[3 * site + 1],
                           model_->site_pos[3 * site + 2]});
  }
}

ReplayScene::VehicleJoints ReplayScene::BindJoints(int body, int site) const {
  VehicleJoints joints;
  for (int j = model_->body_jntadr[body]; j < model_->body_jntadr[body] + model_->body_jntnum[body];
       ++j) {
    if (model_->jnt_type[j] == mjJNT_FREE) joints.free_qpos = model_->jnt_qposadr[j];
    if (model_->jnt_type[j] != mjJNT_SLIDE) continue;
    joints.slide_qpos.push_back(model_->jnt_qposadr[j]);
    joints.slide_axis.push_back(
        {data_->xaxis[3 * j], data_->xaxis[3 * j + 1], data_->xaxis[3 * j + 2]});
  }
  for (int k = 0; k < 3; ++k) joints.rest[k] = data_->site_xpos[3 * site + k];
  return joints;
}

ReplayScene::~ReplayScene() { Free(); }

void ReplayScene::Free() {
  if (data_) mj_deleteData(data_);
  if (model_) mj_deleteModel(model_);
  data_ = nullptr;
  model_ = nullptr;
}

void ReplayScene::Pose(int frame) {
  for (int i = 0; i < rec_.n_vehicles; ++i) {
    const Vec3& p = rec_.pos[frame][i];
    const Vec3& e = rec_.rpy[frame][i];
    // q = qz(yaw) qy(pitch) qx(roll): the ZYX Euler angles of timeseries.csv back to a quaternion.
    double qx[4], qy[4], qz[4], qzy[4], q[4];
    const double ax[3] = {1, 0, 0}, ay[3] = {0, 1, 0}, az[3] = {0, 0, 1};
    mju_axisAngle2Quat(qx, ax, e[0]);
    mju_axisAngle2Quat(qy, ay, e[1]);
    mju_axisAngle2Quat(qz, az, e[2]);
    mju_mulQuat(qzy, qz, qy);
    mju_mulQuat(q, qzy, qx);
    const VehicleJoints& joints = joints_[i];
    if (joints.free_qpos < 0) {
      // Slides (the point mass, orthogonal axes): the imu site moves with the body,
      // q_j = q0_j + a_j . (p - rest), rest being the site at q0.
      for (size_t j = 0; j < joints.slide_qpos.size(); ++j) {
        double q_j = model_->qpos0[joints.slide_qpos[j]];
        for (int k = 0; k < 3; ++k) q_j += joints.slide_axis[j][k] * (p[k] - joints.rest[k]);
        data_->qpos[joints.slide_qpos[j]] = q_j;
      }
      continue;
    }
    // The record is the imu site's pose; the body origin is p - R imu_offset.
    double offset[3];
    mju_rotVecQuat(offset, imu_offset_[i].data(), q);
    double* qpos = data_->qpos + joints.free_qpos;
    for (int k = 0; k < 3; ++k) qpos[k] = p[k] - offset[k];
    mju_copy4(qpos + 3, q);
  }
  data_->time = rec_.t[frame];
  mj_kinematics(model_, data_);
  mj_camlight(model_, data_);
}

void CheckReplayTimes(const Recording& rec, const std::vector<double>& times) {
  const double first = rec.t.front(), last = rec.t.back();
  for (double t : times) {
    if (!(std::isfinite(t) && t >= first - 1e-9 && t <= last + 1e-9)) {
      throw ConfigError(fmt::format("--snapshots {}: outside the recorded run [{}, {}] s ({})", t,
                                    first, last, rec.dir + "/timeseries.csv"));
    }
  }
}

std::string SnapshotPath(const std::string& out_dir, const Recording& rec, double time) {
  return fmt::format("{}/replay_t{:06.2f}.png", out_dir, rec.t[rec.Frame(time)]);
}

std::vector<std::string> ReplayOutputs(const Recording& rec, const std::vector<double>& times,
                                       const std::string& out_dir, const std::string& video) {
  std::vector<std::string> paths;
  for (double time : times) {
    const std::string path = SnapshotPath(out_dir, rec, time);
    if (std::find(paths.begin(), paths.end(), path) == paths.end()) paths.push_back(path);
  }
  if (!video.empty()) paths.push_back(video);
  return paths;
}

std::array<int, 2> ParseVideoSize(const std::string& text) {
  const size_t x = text.find('x');
  auto number = [&](const std::string& part, const char* what, int max) {
    // Digits only: std::stoi would take "+5", " 5" and "5abc". A negative number is a number,
    // out of range.
    const bool negative = part.size() > 1 && part[0] == '-' &&
                          part.find_first_not_of("0123456789", 1) == std::string::npos;
    if (negative) {
      throw std::invalid_argument(fmt::format("'{}': the {} must be in [1, {}] (at most {}x{})",
                                              text, what, max, kMaxVideoWidth, kMaxVideoHeight));
    }
    if (part.empty() || part.size() > 6 ||
        part.find_first_not_of("0123456789") != std::string::npos) {
      throw std::invalid_argument("'" + text + "': the " + what +
                                  " is not a number (expected WIDTHxHEIGHT, e.g. 1920x1080)");
    }
    const int v = std::stoi(part);
    if (v <= 0 || v > max) {
      throw std::invalid_argument(fmt::format("'{}': the {} must be in [1, {}] (at most {}x{})",
                                              text, what, max, kMaxVideoWidth, kMaxVideoHeight));
    }
    return v;
  };
  if (x == std::string::npos) {
    throw std::invalid_argument("'" + text + "': expected WIDTHxHEIGHT, e.g. 1920x1080");
  }
  return {number(text.substr(0, x), "width", kMaxVideoWidth),
          number(text.substr(x + 1), "height", kMaxVideoHeight)};
}

void ReplayScene::AllowOffscreen(int width, int height) {
  model_->vis.global.offwidth = std::max(model_->vis.global.offwidth, width);
  model_->vis.global.offheight = std::max(model_->vis.global.offheight, height);
}

TrailBuffer TrailsAt(const Recording& rec, int frame) {
  TrailBuffer trails(rec.n_vehicles, rec.render.trail_seconds, kTrailPeriod);
  const double from = rec.t[frame] - rec.render.trail_seconds - kTrailPeriod;
  for (int k = 0; k <= frame; ++k) {
    if (rec.t[k] < from) continue;
    // Rows on the 0.1 s grid, as run.cc samples them (every row if recorded more sparsely).
    const double cells = rec.t[k] / kTrailPeriod;
    const bool on_grid = std::abs(cells - std::round(cells)) < 1e-6;
    const bool sparse = k > 0 && rec.t[k] - rec.t[k - 1] > kTrailPeriod + 1e-9;
    if (on_grid || sparse) trails.Add(rec.pos[k]);
  }
  return trails;
}

render::Overlay ReplayOverlay(const Recording& rec, const mjModel* model, const TrailBuffer& trails,
                              int frame) {
  render::Overlay o = FrameOverlay(trails, rec.pos[frame], rec.slot[frame], rec.altitude,
                                   rec.ring_radius, FrameLabel(rec.name, rec.t[frame]));
  o.vehicle_bodies = VehicleBodies(model, rec.n_vehicles);
  for (const auto& e : rec.events) {
    if (o.events.size() >= kMaxEventMarks) break;
    if (e.time_s > rec.t[frame] + 1e-9 || !MarkedEventKind(e.kind)) continue;
    const int at = rec.Frame(e.time_s);
    Vec3 pos = {0, 0, 0};
    bool known = !e.vehicles.empty();
    for (int v : e.vehicles) {
      if (v < 0 || v >= rec.n_vehicles) {
        known = false;
        break;
      }
      for (int k = 0; k < 3; ++k) pos[k] += rec.pos[at][v][k] / e.vehicles.size();
    }
    if (known) o.events.push_back(MakeEventMark(e.kind, e.time_s, e.vehicles, pos));
  }
  return o;
}

}  // namespace mjf::runner
