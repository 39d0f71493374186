// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/runner/run.hpp"

#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <fstream>
#include <limits>
#include <memory>

#include "mjformation/core/metrics.hpp"
#include "mjformation/core/shape.hpp"
#include "mjformation/render.hpp"
#include "mjformation/runner/metrics.hpp"
#include "mjformation/runner/output.hpp"
#include "mjformation/runner/simulation.hpp"
#include "realism_config.hpp"

#ifndef MJF_VERSION
#define MJF_VERSION "0.0.0"
#endif

namespace mjf::runner {
namespace {

using Clock = std::chrono::steady_clock;

// Step indices at which something happens every `period` seconds.
int64_t StepsPer(double period, double timestep) {
  return std::max<int64_t>(1, std::llround(period / timestep));
}

// What the renderer draws: the vehicles' recent paths and the desired slots.
class TrailKeeper {
 public:
  TrailKeeper(int n_vehicles, double seconds, double sample_period)
      : trails_(n_vehicles), capacity_(static_cast<size_t>(seconds / sample_period) + 1) {}
  void Add(const Simulation& sim) {
    for (int i = 0; i < sim.n_vehicles(); ++i) {
      const auto& p = sim.states()[i].pos;
      trails_[i].push_back({p[0], p[1], p[2]});
      if (trails_[i].size() > capacity_) trails_[i].pop_front();
    }
  }
  render::Overlay Overlay(const Simulation& sim, const std::vector<double>& slots) const {
    render::Overlay o;
    for (const auto& t : trails_) o.trails.emplace_back(t.begin(), t.end());
    for (const auto& s : sim.states()) o.markers.push_back({s.pos[0], s.pos[1], s.pos[2]});
    const double z = sim.config().altitude;
    for (int i = 1; i < sim.n_vehicles(); ++i) {
      if (!std::isnan(slots[2 * i])) o.slots.push_back({slots[2 * i], slots[2 * i + 1], z});
    }
    if (sim.shape() && sim.config().shape.type == "circle") {
      const auto& leader = sim.states()[0].pos;
      const double r = sim.config().shape.radius;
      for (int k = 0; k <= 96; ++k) {
        const double a = 2 * M_PI * k / 96;
        o.ring_points.push_back({leader[0] + r * std::cos(a), leader[1] + r * std::sin(a), z});
      }
    }
    o.label = fmt::format("{}   t = {:.1f} s", sim.config().name, sim.time());
    return o;
  }

 private:
  std::vector<std::deque<std::array<double, 3>>> trails_;
  size_t capacity_;
};

// The configured camera; a following camera ("follow", "leader") backs off so that every
// vehicle stays in the picture: MuJoCo's 45 degree field of view shows about 0.35 x distance
// around the target, hence distance >= 2.8 x the farthest vehicle from it.
render::CameraSpec Camera(const RenderConfig& r, const Simulation& sim,
                          const std::array<double, 3>& target) {
  render::CameraSpec cam;
  cam.mode = r.camera == "fixed" ? "fixed" : "follow";
  cam.distance = r.distance;
  if (cam.mode == "follow") {
    double farthest = 0;
    for (const auto& s : sim.states()) {
      farthest = std::max(farthest, std::hypot(s.pos[0] - target[0], s.pos[1] - target[1]));
    }
    cam.distance = std::max(r.distance, 2.8 * farthest);
  }
  cam.azimuth = r.azimuth;
  cam.elevation = r.elevation;
  for (int k = 0; k < 3; ++k) cam.lookat[k] = r.lookat[k];
  return cam;
}

// Camera target: the formation's centroid ("follow") or the leader ("leader").
std::array<double, 3> CameraTarget(const Simulation& sim) {
  std::array<double, 3> c = {0, 0, 0};
  if (sim.config().render.camera == "leader") {
    for (int k = 0; k < 3; ++k) c[k] = sim.states()[0].pos[k];
    return c;
  }
  for (const auto& s : sim.states()) {
    for (int k = 0; k < 3; ++k) c[k] += s.pos[k];
  }
  for (double& v : c) v /= sim.n_vehicles();
  return c;
}

class ProgressLine {
 public:
  ProgressLine(bool enabled, std::string name, double duration)
      : enabled_(enabled && isatty(STDERR_FILENO)), name_(std::move(name)), duration_(duration) {}
  void Update(double t, double sigma_f, Clock::time_point start) {
    if (!enabled_) return;
    const auto now = Clock::now();
    if (now - last_ < std::chrono::milliseconds(250)) return;
    last_ = now;
    const double wall = std::chrono::duration<double>(now - start).count();
    std::fprintf(stderr, "\r[%s] t = %6.2f / %.2f s (%3.0f%%)  %6.1fx real time  sigma_f = %-9.4g",
                 name_.c_str(), t, duration_, 100.0 * t / duration_, wall > 0 ? t / wall : 0.0,
                 sigma_f);
    std::fflush(stderr);
  }
  void Finish() {
    if (enabled_) std::fprintf(stderr, "\n");
  }

 private:
  bool enabled_;
  std::string name_;
  double duration_;
  Clock::time_point last_{};
};

}  // namespace

std::string VersionString() {
  return fmt::format("mjformation {} (MuJoCo {}, plugin ABI {})", MJF_VERSION, mj_versionString(),
                     MJF_ABI_VERSION);
}

RunResult RunExperiment(const ExperimentConfig& config, const RunOptions& options) {
  // Everything that can be wrong with the input fails here, before a file is written.
  Simulation sim(config);
  const int n = sim.n_vehicles();
  const double dt = config.timestep;

  std::unique_ptr<RunDirectory> dir;
  std::unique_ptr<TimeseriesWriter> csv;
  if (!options.out_dir.empty()) {
    dir = std::make_unique<RunDirectory>(options.out_dir, options.overwrite);
    dir->WriteText("config.toml", ConfigEcho(config));
    dir->WriteText("scene.xml", sim.scene_xml());
    if (options.record) {
      csv = std::make_unique<TimeseriesWriter>(dir->Path("timeseries.csv"), n,
                                               config.sensors.enabled(), config.wind.enabled());
    }
  }

  const bool want_snapshots = dir && options.render && !config.render.snapshots.empty();
  const bool want_video = dir && options.render && config.render.video;
  std::unique_ptr<render::OffscreenRenderer> snapshot_renderer, video_renderer;
  std::unique_ptr<render::VideoWriter> video;
  if (want_snapshots) {
    snapshot_renderer = std::make_unique<render::OffscreenRenderer>(
        sim.model(), config.render.width, config.render.height, config.render.shadows);
  }
  if (want_video) {
    video_renderer = std::make_unique<render::OffscreenRenderer>(
        sim.model(), config.render.video_width, config.render.video_height,
        config.render.video_shadows);
    video =
        std::make_unique<render::VideoWriter>(dir->Path("video.mp4"), config.render.video_width,
                                              config.render.video_height, config.render.video_fps);
  }
  std::vector<int64_t> snapshot_steps;
  for (double t : config.render.snapshots) snapshot_steps.push_back(std::llround(t / dt));
  const int64_t record_every = StepsPer(1.0 / config.record_rate, dt);
  const int64_t trail_every = StepsPer(0.1, dt);
  const int64_t video_every = StepsPer(1.0 / config.render.video_fps, dt);
  TrailKeeper trails(n, config.render.trail_seconds, trail_every * dt);

  OnlineMetrics metrics(sim);
  std::vector<double> slots(2 * static_cast<size_t>(n));
  nlohmann::ordered_json snapshot_files = nlohmann::ordered_json::array();
  ProgressLine progress(options.progress, config.name, config.duration);

  RunResult result;
  const auto start = Clock::now();
  try {
    for (int64_t step = 0; step <= sim.total_steps(); ++step) {
      sim.ComputeControls();
      const bool record_tick = step % record_every == 0 || step == sim.total_steps();
      const bool snapshot_tick =
          want_snapshots &&
          std::find(snapshot_steps.begin(), snapshot_steps.end(), step) != snapshot_steps.end();
      const bool video_tick = want_video && step % video_every == 0;
      if (record_tick || snapshot_tick || video_tick) {
        const double sigma_f = metrics.Sample(sim, &slots, record_tick);
        if (record_tick && csv) csv->Write(sim, sigma_f, slots);
        progress.Update(sim.time(), sigma_f, start);
      }
      metrics.StepControls(sim);
      if ((want_snapshots || want_video) && step % trail_every == 0) trails.Add(sim);
      if (snapshot_tick) {
        const auto target = CameraTarget(sim);
        const auto& rgb = snapshot_renderer->Render(sim.data(), Camera(config.render, sim, target),
                                                    trails.Overlay(sim, slots), target.data());
        const std::string name = fmt::format("snapshots/t{:06.2f}.png", sim.time());
        render::WritePng(dir->Path(name), rgb.data(), config.render.width, config.render.height);
        snapshot_files.push_back(name);
      }
      if (video_tick) {
        const auto target = CameraTarget(sim);
        video->AddFrame(video_renderer
                            ->Render(sim.data(), Camera(config.render, sim, target),
                                     trails.Overlay(sim, slots), target.data())
                            .data());
      }
      if (step < sim.total_steps()) sim.Integrate();
    }
    if (video) video->Close();
    result.complete = true;
  } catch (const SimulationError& e) {
    result.error = e.what();
  }
  progress.Finish();
  result.wall_time_s = std::chrono::duration<double>(Clock::now() - start).count();
  result.sim_time_s = sim.time();
  result.steps = sim.step_index();
  if (csv) csv->Close();

  auto& s = result.summary;
  s["experiment"] = config.name;
  s["complete"] = result.complete;
  s["error"] =
      result.complete ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(result.error);
  s["paper_experiment"] = config.paper_experiment;
  s["sim_time_s"] = result.sim_time_s;
  s["duration_s"] = config.duration;
  s["timestep_s"] = dt;
  s["steps"] = result.steps;
  s["seed"] = config.seed;
  s["config_sha256"] = Sha256Hex(ConfigEcho(config));
  s["versions"] = {{"mjformation", MJF_VERSION},
                   {"mujoco", mj_versionString()},
                   {"plugin_abi", MJF_ABI_VERSION}};
  s["n_followers"] = config.followers;
  s["vehicle_model"] = config.model;
  s["rotor_model"] = config.rotor_model;
  auto plugin_json = [](const PluginInstance& p) {
    nlohmann::ordered_json a = nlohmann::ordered_json::object();
    for (const auto& [k, v] : p.attributes()) a[k] = v;
    return nlohmann::ordered_json{{"name", p.descriptor().name}, {"attributes", a}};
  };
  s["plugins"]["leader"] = plugin_json(sim.leader_plugin());
  s["plugins"]["formation"] =
      sim.formation_plugin()
          ? plugin_json(*sim.formation_plugin())
          : nlohmann::ordered_json{{"name", config.formation.plugin}, {"per_follower", true}};
  s["plugins"]["attitude"] = plugin_json(sim.attitude_plugin(0));
  s["shape"] = {
      {"type", config.shape.type}, {"radius", config.shape.radius}, {"omega", config.shape.omega}};
  AddRealismSummary(config, &s);  // issue 11: "sensors" / "wind", only when switched on
  s["metrics"] = metrics.Summary(sim);
  nlohmann::ordered_json report = nlohmann::ordered_json::object();
  for (const auto& [k, v] : sim.FormationReport()) report[k] = JsonNumber(v);
  s["plugin_report"] = report;
  s["snapshots"] = snapshot_files;
  // Timing varies run to run; it is the only part of the run directory that does.
  s["timing"] = {
      {"wall_time_s", result.wall_time_s},
      {"real_time_factor", result.wall_time_s > 0 ? result.sim_time_s / result.wall_time_s : 0.0},
      {"steps_per_second", result.wall_time_s > 0 ? result.steps / result.wall_time_s : 0.0}};
  if (dir) dir->WriteText("summary.json", s.dump(2) + "\n");
  return result;
}

}  // namespace mjf::runner
