// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// `mjformation bench`: in one command, times (a) bare MuJoCo stepping of the composed scene with
// fixed controls and (b) the full pipeline (plugins, recording, metrics; no rendering) for the
// same scene and step count, and prints both and their ratio; repeats for several swarm sizes;
// reports peak memory per point (each point runs in its own child process so its peak RSS is
// its own) and, on request, offscreen rendering cost.
#include <fcntl.h>
#include <fmt/format.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>

#include "mjformation/app/cli.hpp"
#include "mjformation/config/config.hpp"
#include "mjformation/record/output.hpp"
#include "mjformation/render.hpp"
#include "mjformation/run/run.hpp"
#include "mjformation/scene/scene.hpp"
#include "mjformation/sim/simulation.hpp"

namespace mjf::runner {
namespace {

// A fresh folder under /tmp (mkdtemp), removed with everything in it when the bench ends: it
// holds only the scratch run directories the bench itself wrote.
class ScratchFolder {
 public:
  ScratchFolder() {
    char name[] = "/tmp/mjformation_bench_XXXXXX";
    if (!mkdtemp(name)) throw OutputError(std::string("/tmp: cannot create ") + name);
    path_ = name;
  }
  ~ScratchFolder() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point since) {
  return std::chrono::duration<double>(Clock::now() - since).count();
}

double PeakRssMiB() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;  // ru_maxrss is in KiB on Linux
}

// Runs `work` in a child process and returns what it printed as JSON (its peak RSS included).
nlohmann::json InChild(const std::function<nlohmann::json()>& work) {
  int fds[2];
  if (pipe(fds) != 0) throw std::runtime_error("bench: pipe failed");
  std::fflush(stdout);
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("bench: fork failed");
  if (pid == 0) {
    close(fds[0]);
    nlohmann::json out;
    try {
      out = work();
      out["peak_rss_mib"] = PeakRssMiB();
    } catch (const std::exception& e) {
      out = {{"error", e.what()}};
    }
    const std::string text = out.dump();
    ssize_t written = write(fds[1], text.data(), text.size());
    (void)written;
    close(fds[1]);
    _exit(0);
  }
  close(fds[1]);
  std::string text;
  char buf[4096];
  for (ssize_t n; (n = read(fds[0], buf, sizeof(buf))) > 0;) text.append(buf, n);
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (text.empty()) throw std::runtime_error("bench: the measuring child process died");
  nlohmann::json out = nlohmann::json::parse(text);
  if (out.contains("error")) throw std::runtime_error(out["error"].get<std::string>());
  return out;
}

// The experiment resized to n followers: generated ring topology (leader -> follower 1), the
// default start ring, circle shape phases spread over 2 pi, and the circle widened when needed
// (at the file's slot speed) so neighbouring slots stay at least kSlotSpacing apart, like the
// start ring. Vehicles never
// collide with each other (contype/conaffinity), but a crowd still costs MuJoCo 2.2.2: its
// collision phase (broadphase and the per-geom contype checks of every overlapping body pair)
// grows with the number of vehicles within a vehicle's size of each other. 1000 slots on the
// file's 10 m circle (6 cm apart) made a step cost 2.3x that of the same vehicles flying apart
// (docs/PERFORMANCE.md), which measures crowding, not the pipeline.
constexpr double kSlotSpacing = 1.5;  // m, as the default start ring
ExperimentConfig Resized(ExperimentConfig c, int n) {
  if (n == c.followers) return c;
  c.followers = n;
  const double radius = std::max(c.shape.radius, kSlotSpacing * n / (2 * M_PI));
  if (radius > c.shape.radius) {
    c.shape.omega *= c.shape.radius / radius;  // the slots keep the file's speed
    c.shape.radius = radius;
  }
  c.follower_start.clear();
  c.leader_weight.assign(n, 0.0);
  c.leader_weight[0] = 1.0;
  c.edges = GeneratedEdges(n, true);
  c.shape.phase_step = -1;
  return c;
}

// (a) bare MuJoCo: the same composed model stepped with mj_step and constant controls, from a
// flying state. A swarm at rest and level is not what MuJoCo steps during a run: with every
// quaternion exactly (1, 0, 0, 0) and every rotor wrench along a world axis, MuJoCo 2.2.2 takes
// shortcuts (mju_quat2Mat's identity case, mju_mulMatTVec skipping zero entries of the rotated
// rotor wrenches) and a step costs about 10% less than the same step in flight (perf, see
// docs/PERFORMANCE.md). So each free-flying vehicle starts tilted by kTilt about a horizontal axis
// of its own, spinning about its body z axis (a principal axis: the attitude stays put) with
// thrust / cos(kTilt) = weight: it holds its altitude and accelerates sideways, its attitude never
// level, for the whole run, with fixed controls.
constexpr double kTilt = 0.1;  // rad
constexpr double kSpin = 0.3;  // rad/s about body z
nlohmann::json BareMujoco(const ExperimentConfig& config) {
  Simulation sim(config);  // composes the scene exactly as a run does
  // A copy of the run's model (its text compiles to the same bytes, SceneTest; reading 10,000
  // vehicles' text back costs MuJoCo's reader minutes: each element it adds rebuilds its lists).
  mjModel* m = mj_copyModel(nullptr, sim.model());
  mjData* d = mj_makeData(m);
  const int per_vehicle = std::max(1, sim.actuators_per_vehicle());
  const double hover = sim.binding(0).info.mass * sim.binding(0).info.gravity / per_vehicle;
  double thrust = hover;
  for (int i = 0; i < sim.n_vehicles(); ++i) {
    const int body = sim.binding(i).body;
    const int joint = m->body_jntadr[body];
    if (m->body_jntnum[body] != 1 || m->jnt_type[joint] != mjJNT_FREE) continue;
    const double axis_angle = 2 * M_PI * i / sim.n_vehicles();
    mjtNum* q = d->qpos + m->jnt_qposadr[joint] + 3;
    q[0] = std::cos(kTilt / 2);
    q[1] = std::sin(kTilt / 2) * std::cos(axis_angle);
    q[2] = std::sin(kTilt / 2) * std::sin(axis_angle);
    q[3] = 0;
    d->qvel[m->jnt_dofadr[joint] + 5] = kSpin;  // free joint: angular velocity in body axes
    thrust = hover / std::cos(kTilt);
  }
  for (int i = 0; i < m->nu; ++i) d->ctrl[i] = thrust;
  for (int i = 0; i < m->na; ++i) d->act[i] = thrust;  // motor lag already settled
  mj_forward(m, d);
  if (m->nu == 0) {
    // Wrench rotor model: the same constant wrench every step, thrust along the body z axis
    // (which the spin about it leaves fixed in the world), handed to MuJoCo as the constant
    // generalized force qfrc_applied: the runner adds it into qfrc_passive after mj_step1
    // (AddWrenchAtCentreOfMass), which mj_step below would clear every step.
    for (int i = 0; i < sim.n_vehicles(); ++i) {
      const int body = sim.binding(i).body;
      mjtNum force[3];
      for (int k = 0; k < 3; ++k) force[k] = thrust * per_vehicle * d->xmat[9 * body + 3 * k + 2];
      mj_applyFT(m, d, force, nullptr, d->xipos + 3 * body, body, d->qfrc_applied);
    }
  }
  const int64_t steps = sim.total_steps();
  const auto start = Clock::now();
  for (int64_t k = 0; k < steps; ++k) mj_step(m, d);
  const double wall = Seconds(start);
  // The state stayed a flight: every vehicle still airborne and tilted (a landed or level swarm
  // would time something else).
  double min_z = INFINITY, min_tilt = INFINITY;
  for (int i = 0; i < sim.n_vehicles(); ++i) {
    const int body = sim.binding(i).body;
    min_z = std::min(min_z, d->xpos[3 * body + 2]);
    min_tilt = std::min(min_tilt, std::acos(std::clamp(d->xmat[9 * body + 8], -1.0, 1.0)));
  }
  mj_deleteData(d);
  mj_deleteModel(m);
  return {{"steps", steps},
          {"wall_s", wall},
          {"compose_s", sim.compose_seconds()},
          {"final_min_z_m", min_z},
          {"final_min_tilt_rad", min_tilt}};
}

// (b) the full pipeline, recording to a scratch run directory, no rendering.
nlohmann::json Pipeline(const ExperimentConfig& config, const std::string& scratch) {
  RunOptions options;
  options.out_dir = scratch;
  options.overwrite = true;
  options.render = false;
  const RunResult r = RunExperiment(config, options);
  if (!r.complete) throw std::runtime_error("bench run stopped early: " + r.error);
  nlohmann::json out = {{"steps", r.steps},
                        {"wall_s", r.wall_time_s},
                        {"sigma_f_mean", r.summary["metrics"]["sigma_f_mean"]}};
  const auto& timing = r.summary["timing"];
  for (const char* key : {"estimator_wall_s", "sensor_models_wall_s", "estimator_plugins_wall_s"}) {
    if (timing.contains(key)) out[key] = timing[key];
  }
  // Per-agent runs: the broadcasts every link carried (sent; delivered, neither lost nor late).
  if (r.summary.contains("network")) {
    int64_t sent = 0, delivered = 0;
    for (const auto& link : r.summary["network"]["links"]) {
      sent += link.value("sent", int64_t{0});
      delivered += link.value("delivered", int64_t{0});
    }
    out["messages_sent"] = sent;
    out["messages_delivered"] = delivered;
  }
  return out;
}

nlohmann::json RenderCost(const ExperimentConfig& config) {
  Simulation sim(config);
  for (int k = 0; k < 100; ++k) {
    sim.ComputeControls();
    sim.Integrate();
  }
  sim.ComputeControls();
  const auto& leader = sim.states()[0].pos;
  const double target[3] = {leader[0], leader[1], leader[2]};
  render::CameraSpec camera;
  camera.distance = config.render.distance;
  render::Overlay overlay;
  nlohmann::json out;
  auto time_frames = [&](int w, int h, bool shadows, int frames) {
    render::OffscreenRenderer renderer(sim.model(), w, h, shadows);
    renderer.Render(sim.data(), camera, overlay, target);  // warm-up
    const auto start = Clock::now();
    for (int k = 0; k < frames; ++k) renderer.Render(sim.data(), camera, overlay, target);
    return Seconds(start) / frames;
  };
  out["snapshot_1280x720_shadows_ms"] = 1e3 * time_frames(1280, 720, true, 10);
  out["snapshot_1280x720_noshadows_ms"] = 1e3 * time_frames(1280, 720, false, 10);
  out["video_640x480_shadows_fps"] = 1.0 / time_frames(640, 480, true, 30);
  out["video_640x480_noshadows_fps"] = 1.0 / time_frames(640, 480, false, 30);
  return out;
}

constexpr int kRepeats = 3;
constexpr double kRepeatBelowS = 5.0;  // s of pipeline wall time

}  // namespace

namespace {

// A finite number > 0: CLI::PositiveNumber lets NaN through.
const CLI::Validator kPositiveFinite(
    [](std::string& text) {
      double v = 0;
      try {
        size_t used = 0;
        v = std::stod(text, &used);
        if (used != text.size()) return std::string("expected a number, got ") + text;
      } catch (const std::exception&) {
        return std::string("expected a number, got ") + text;
      }
      return std::isfinite(v) && v > 0 && v <= 1e6
                 ? std::string()
                 : "must be a finite number in (0, 1e6], got " + text;
    },
    "POSITIVE");

}  // namespace

void AddBenchCommand(CLI::App& app, CliCommands* c) {
  c->bench = app.add_subcommand(
      "bench",
      "Time bare MuJoCo against the full pipeline on the same composed scene; scale the swarm");
  c->bench->add_option("experiment", c->experiment, "experiment file (TOML)")->required();
  AddIntegerListOption(c->bench, "--followers", &c->bench_followers,
                       "swarm sizes to measure (default: the file's); other sizes use a "
                       "generated ring topology",
                       1, 100000);  // [vehicles] followers' bound, before any vector
  c->bench->add_option("--duration", c->bench_duration, "simulated seconds (default: the file's)")
      ->check(kPositiveFinite);
  c->bench->add_option("--set", c->overrides, "override a value: section.key=value");
  c->bench->add_option("--json", c->bench_json, "also write the figures to this JSON file");
  c->bench->add_flag("--render", c->bench_render, "also time offscreen rendering");
  AddIntegerListOption(c->bench, "--threads", &c->bench_threads,
                       "physics partitions to time the full pipeline with, e.g. 1,2 (prints the "
                       "speed-up over the first)",
                       1, kMaxThreads);
  c->bench->add_flag("--memory", c->bench_memory,
                     "also run the first size 10x longer and compare peak memory");
}

namespace {

using Json = nlohmann::ordered_json;

// One row: bare MuJoCo against the full pipeline at one thread count (`speed_up`: over the
// first thread count measured; printed only with --threads).
Json PointRow(const ExperimentConfig& config, int n, const nlohmann::json& bare,
              const nlohmann::json& full, int repeats, int threads, double speed_up,
              bool with_threads) {
  const double steps = full["steps"].get<double>();
  const double bare_wall = bare["wall_s"].get<double>(), full_wall = full["wall_s"].get<double>();
  const double ratio = full_wall / bare_wall;
  // What the pipeline (sensors, network, controllers, recording) adds to a bare step, per
  // follower: constant in n when its cost is linear in the number of followers.
  const double per_follower_us = (full_wall - bare_wall) / steps / n * 1e6;
  std::printf("%9d %9.0f %14.0f %14.0f %15.3f %9.2f %9.2f %10.1f %7d %21.3f %10.2f", n, steps,
              steps / bare_wall, steps / full_wall, ratio, config.duration / bare_wall,
              config.duration / full_wall, full["peak_rss_mib"].get<double>(), repeats,
              per_follower_us, bare["compose_s"].get<double>());
  if (with_threads) std::printf(" %7d %8.2f", threads, speed_up);
  std::printf("\n");
  std::fflush(stdout);
  Json row = {
      {"followers", n},
      {"steps", steps},
      {"best_of", repeats},
      {"bare_wall_s", bare_wall},
      {"full_wall_s", full_wall},
      {"ratio_full_over_bare", ratio},
      {"pipeline_us_per_follower_step", per_follower_us},
      {"real_time_factor_bare", config.duration / bare_wall},
      {"real_time_factor_full", config.duration / full_wall},
      {"peak_rss_mib_full", full["peak_rss_mib"]},
      {"peak_rss_mib_bare", bare["peak_rss_mib"]},
      {"compose_s", bare["compose_s"]},
      {"peak_rss_kib_full_per_vehicle", full["peak_rss_mib"].get<double>() * 1024.0 / (n + 1)},
      {"bare_final_min_z_m", bare["final_min_z_m"]},
      {"bare_final_min_tilt_rad", bare["final_min_tilt_rad"]}};
  if (with_threads) {
    row["threads"] = threads;
    row["speed_up"] = speed_up;
  }
  return row;
}

// One size: bare MuJoCo (one model, one thread) against the full pipeline at each thread
// count, printed as table rows.
std::vector<Json> BenchPoint(const ExperimentConfig& base, int n, const std::vector<int>& threads,
                             const std::string& scratch) {
  const ExperimentConfig config = Resized(base, n);
  std::vector<ExperimentConfig> configs(threads.size(), config);
  for (size_t t = 0; t < threads.size(); ++t) configs[t].threads = threads[t];
  // Other processes share the machine: short points are measured kRepeats times, bare and full
  // alternating, and the fastest of each is kept (the least disturbed run).
  nlohmann::json bare = InChild([&] { return BareMujoco(config); });
  std::vector<nlohmann::json> full;
  for (const auto& c : configs) full.push_back(InChild([&] { return Pipeline(c, scratch); }));
  int repeats = 1;
  for (; repeats < kRepeats && full[0]["wall_s"].get<double>() < kRepeatBelowS; ++repeats) {
    const nlohmann::json b = InChild([&] { return BareMujoco(config); });
    if (b["wall_s"].get<double>() < bare["wall_s"].get<double>()) bare = b;
    for (size_t t = 0; t < configs.size(); ++t) {
      const nlohmann::json f = InChild([&] { return Pipeline(configs[t], scratch); });
      if (f["wall_s"].get<double>() < full[t]["wall_s"].get<double>()) full[t] = f;
    }
  }
  std::vector<Json> rows;
  for (size_t t = 0; t < configs.size(); ++t) {
    const double speed_up = full[0]["wall_s"].get<double>() / full[t]["wall_s"].get<double>();
    rows.push_back(PointRow(config, n, bare, full[t], repeats, threads[t], speed_up,
                            threads.size() > 1 || threads[0] != base.threads));
  }
  return rows;
}

// Peak memory of a run ten times longer: nothing may grow with run length.
Json BenchMemory(const ExperimentConfig& base, int n, const std::string& scratch) {
  ExperimentConfig shorter = Resized(base, n);
  ExperimentConfig longer = shorter;
  longer.duration *= 10;
  longer.metric_window = {0.625 * longer.duration, longer.duration};
  const nlohmann::json a = InChild([&] { return Pipeline(shorter, scratch); });
  const nlohmann::json b = InChild([&] { return Pipeline(longer, scratch); });
  const double ra = a["peak_rss_mib"].get<double>(), rb = b["peak_rss_mib"].get<double>();
  std::printf(
      "memory: %d followers, %.0f s run: peak %.1f MiB; %.0f s run: peak %.1f MiB; "
      "ratio %.3f (target < 1.2)\n",
      n, shorter.duration, ra, longer.duration, rb, rb / ra);
  return {{"followers", n},
          {"short_duration_s", shorter.duration},
          {"long_duration_s", longer.duration},
          {"short_peak_rss_mib", ra},
          {"long_peak_rss_mib", rb},
          {"ratio", rb / ra}};
}

// The estimator's cost, two ways. (1) The same run with the configured estimator and
// with passthrough (the same sensor suite), each the best of up to kRepeats, alternating: ratio
// = steps/s with the estimator / steps/s with passthrough. The two fly different trajectories
// (passthrough hands the controllers the raw samples), so the ratio also holds what the flights
// cost MuJoCo and the controllers differently. (2) Within the estimator's own run, the wall
// time of the estimator plugins over the run's (the target's figure: what the estimator costs
// that very flight), and of the sensor models (noise, latency, accelerometer), which a
// passthrough run with the same suite pays as well.
Json BenchEstimator(const ExperimentConfig& base, int n, const std::string& scratch) {
  const ExperimentConfig with = Resized(base, n);
  ExperimentConfig without = with;
  without.estimator.plugin = "passthrough";  // it declares no attributes
  without.estimator.attributes.clear();
  without.estimator.derived.clear();
  nlohmann::json a = InChild([&] { return Pipeline(with, scratch); });
  nlohmann::json b = InChild([&] { return Pipeline(without, scratch); });
  for (int k = 1; k < kRepeats && a["wall_s"].get<double>() < kRepeatBelowS; ++k) {
    const nlohmann::json a2 = InChild([&] { return Pipeline(with, scratch); });
    const nlohmann::json b2 = InChild([&] { return Pipeline(without, scratch); });
    if (a2["wall_s"].get<double>() < a["wall_s"].get<double>()) a = a2;
    if (b2["wall_s"].get<double>() < b["wall_s"].get<double>()) b = b2;
  }
  const double rate_with = a["steps"].get<double>() / a["wall_s"].get<double>();
  const double rate_without = b["steps"].get<double>() / b["wall_s"].get<double>();
  const double ratio = rate_with / rate_without;
  const double wall = a["wall_s"].get<double>();
  const double share = a.value("estimator_plugins_wall_s", 0.0) / wall;
  const double models_share = a.value("sensor_models_wall_s", 0.0) / wall;
  const std::string& name = with.estimator.plugin;
  std::printf(
      "estimator: %d followers, %s %.0f steps/s, passthrough %.0f steps/s, ratio "
      "%s/passthrough %.3f; in the %s run the estimator plugins took %.1f %% of the wall time "
      "(target <= 10 %%), the sensor models %.1f %%\n",
      n, name.c_str(), rate_with, rate_without, name.c_str(), ratio, name.c_str(), 100.0 * share,
      100.0 * models_share);
  return {{"followers", n},
          {"estimator", name},
          {"steps_per_s_estimator", rate_with},
          {"steps_per_s_passthrough", rate_without},
          {"ratio_estimator_over_passthrough", ratio},
          {"estimator_share_of_run", share},
          {"sensor_models_share_of_run", models_share}};
}

// Per-agent execution's cost: the same run with the configured per-agent execution
// (its coupling, prediction, clocks and network) and in central mode (one formation plugin that
// sees every state, no network), each the best of up to kRepeats, alternating: ratio = wall
// time per step per-agent / central. The two fly slightly different trajectories unless the
// network is ideal, so the ratio also holds what the flights cost MuJoCo differently.
Json BenchExecution(const ExperimentConfig& base, int n, const std::string& scratch) {
  const ExperimentConfig per_agent = Resized(base, n);
  ExperimentConfig central = per_agent;
  central.network = NetworkConfig{};  // mode "central", no [network]: the reference
  nlohmann::json a = InChild([&] { return Pipeline(per_agent, scratch); });
  nlohmann::json b = InChild([&] { return Pipeline(central, scratch); });
  for (int k = 1; k < kRepeats && a["wall_s"].get<double>() < kRepeatBelowS; ++k) {
    const nlohmann::json a2 = InChild([&] { return Pipeline(per_agent, scratch); });
    const nlohmann::json b2 = InChild([&] { return Pipeline(central, scratch); });
    if (a2["wall_s"].get<double>() < a["wall_s"].get<double>()) a = a2;
    if (b2["wall_s"].get<double>() < b["wall_s"].get<double>()) b = b2;
  }
  const double rate_agent = a["steps"].get<double>() / a["wall_s"].get<double>();
  const double rate_central = b["steps"].get<double>() / b["wall_s"].get<double>();
  const double ratio = rate_central / rate_agent;  // cost per step, per-agent over central
  const NetworkConfig& net = per_agent.network;
  // What a message costs: the per-agent run's extra wall time over central mode, per message
  // sent (a message is one broadcast on one link: sending, queueing, losing or delivering it, and
  // the per-agent law's reading of it).
  const int64_t sent = a.value("messages_sent", int64_t{0});
  const double extra_s = a["wall_s"].get<double>() - b["wall_s"].get<double>() *
                                                         a["steps"].get<double>() /
                                                         b["steps"].get<double>();
  const double us_per_message = sent > 0 ? 1e6 * extra_s / static_cast<double>(sent) : 0.0;
  std::printf(
      "execution: %d followers, per_agent (coupling %s, predict %s) %.0f steps/s, central %.0f "
      "steps/s; cost per step per_agent/central %.3f (target <= 1.3); %.0f messages sent per "
      "step, %.3f us of extra wall time per message\n",
      n, ToString(net.coupling), ToString(net.predict), rate_agent, rate_central, ratio,
      static_cast<double>(sent) / a["steps"].get<double>(), us_per_message);
  return {{"followers", n},
          {"messages_sent", sent},
          {"messages_delivered", a.value("messages_delivered", int64_t{0})},
          {"extra_us_per_message", us_per_message},
          {"coupling", ToString(net.coupling)},
          {"predict", ToString(net.predict)},
          {"steps_per_s_per_agent", rate_agent},
          {"steps_per_s_central", rate_central},
          {"cost_ratio_per_agent_over_central", ratio},
          {"sigma_f_mean_per_agent", a["sigma_f_mean"]},
          {"sigma_f_mean_central", b["sigma_f_mean"]}};
}

Json BenchRender(const ExperimentConfig& config) {
  const nlohmann::json r = InChild([&] { return RenderCost(config); });
  std::printf(
      "render: snapshot 1280x720 %.1f ms with shadows, %.1f ms without; video 640x480 "
      "%.1f fps with shadows, %.1f fps without\n",
      r["snapshot_1280x720_shadows_ms"].get<double>(),
      r["snapshot_1280x720_noshadows_ms"].get<double>(),
      r["video_640x480_shadows_fps"].get<double>(), r["video_640x480_noshadows_fps"].get<double>());
  return r;
}

void WriteJson(const std::string& path, const Json& report) {
  // Created, never replaced (RefuseExistingFiles looked before the bench began).
  const int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
  std::FILE* f = fd >= 0 ? fdopen(fd, "wb") : nullptr;
  if (!f) throw OutputError(path + ": cannot write: " + std::strerror(errno));
  const std::string text = report.dump(2) + "\n";
  const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  if (std::fclose(f) != 0 || !ok)
    throw OutputError(path + ": write failed: " + std::strerror(errno));
}

// The experiment as benched: shortened by --duration, without snapshots or video.
ExperimentConfig BenchedExperiment(const CliCommands& c) {
  ExperimentConfig base = LoadExperiment(c.experiment, c.overrides);
  if (c.bench_duration > 0) {
    base.duration = c.bench_duration;
    base.metric_window = {0.625 * base.duration, base.duration};
  }
  base.render.snapshots.clear();
  base.render.video = false;
  return base;
}

// The settings that change the cost, echoed so that two tables can be told apart, and a legend
// of the columns.
Json EchoSettings(const CliCommands& c, const ExperimentConfig& base) {
  Json report;
  report["experiment"] = c.experiment;
  report["duration_s"] = base.duration;
  report["timestep_s"] = base.timestep;
  report["record_rate_hz"] = base.record_rate;
  report["rotor_model"] = ToString(base.rotor_model);
  report["version"] = VersionString();
  report["contacts"] = base.contacts;
  std::printf(
      "%s: %g s at %g s steps, rotor model %s, recording at %g Hz, contacts=%s, sensors=%s, "
      "wind=%s, estimator=%s, execution=%s\n",
      c.experiment.c_str(), base.duration, base.timestep, ToString(base.rotor_model),
      base.record_rate, base.contacts ? "true" : "false", base.sensors.enabled() ? "on" : "ideal",
      base.wind.enabled() ? "on" : "calm", base.estimator.plugin.c_str(),
      base.network.execution == Execution::kPerAgent ? "per_agent" : "central");
  std::printf(
      "  bare: MuJoCo alone stepping the composed scene; full: the whole pipeline (plugins, "
      "sensors, wind, recording)\n"
      "  steps/s: physics steps per wall second; wall full/bare: full's wall time over bare's "
      "(1: no overhead)\n"
      "  RTF: real-time factor, simulated s per wall s; peak MiB: the full run's peak memory; "
      "best of: runs per point, fastest kept\n"
      "  overhead us/foll/step: (full - bare wall time) / steps / followers, what the pipeline "
      "adds per follower and step\n"
      "  compose s: wall time of composing and compiling the scene (the bare run's)\n");
  return report;
}

void PrintTableHeader(bool with_threads) {
  std::printf("%9s %9s %14s %14s %15s %9s %9s %10s %7s %21s %10s", "followers", "steps",
              "bare steps/s", "full steps/s", "wall full/bare", "RTF bare", "RTF full", "peak MiB",
              "best of", "overhead us/foll/step", "compose s");
  if (with_threads) std::printf(" %7s %8s", "threads", "speed-up");
  std::printf("\n");
}

// Linear scaling: the largest size's per-follower pipeline cost against the smallest's, at the
// first thread count (the rows of one size follow each other).
double PrintScaling(const Json& points, size_t sizes, size_t threads) {
  const Json& first = points.front();
  const Json& last = points[(sizes - 1) * threads];
  const double growth = last["pipeline_us_per_follower_step"].get<double>() /
                        first["pipeline_us_per_follower_step"].get<double>();
  std::printf(
      "scaling: pipeline cost per follower and step at %d followers / at %d followers = %.2f "
      "(1: linear in N; %d: quadratic)\n",
      last["followers"].get<int>(), first["followers"].get<int>(), growth,
      last["followers"].get<int>() / first["followers"].get<int>());
  return growth;
}

}  // namespace

int BenchCommand(const CliCommands& c) {
  if (!c.bench_json.empty()) {
    RefuseExistingFiles({c.bench_json});
    RequireWritableFolderOf(c.bench_json);
  }
  const ExperimentConfig base = BenchedExperiment(c);
  std::vector<int> sizes = c.bench_followers;
  if (sizes.empty()) sizes.push_back(base.followers);
  const ScratchFolder folder;  // removed on return: a bench leaves nothing behind
  const std::string scratch = folder.path() + "/run";
  Json report = EchoSettings(c, base);
  std::vector<int> threads = c.bench_threads;
  if (threads.empty()) threads.push_back(base.threads);
  PrintTableHeader(threads.size() > 1 || threads[0] != base.threads);
  for (int n : sizes) {
    for (Json& row : BenchPoint(base, n, threads, scratch)) report["points"].push_back(row);
  }
  if (sizes.size() > 1) {
    report["per_follower_cost_growth"] =
        PrintScaling(report["points"], sizes.size(), threads.size());
  }
  // With an estimator configured, what it costs against passthrough on the first size.
  if (base.estimator.plugin != "passthrough")
    report["estimator"] = BenchEstimator(base, sizes.front(), scratch);
  // Per-agent execution configured: what it costs against central mode on the first size.
  if (base.network.execution == Execution::kPerAgent)
    report["execution"] = BenchExecution(base, sizes.front(), scratch);
  if (c.bench_memory) report["memory"] = BenchMemory(base, sizes.front(), scratch);
  if (c.bench_render) report["render"] = BenchRender(Resized(base, sizes.front()));
  if (!c.bench_json.empty()) WriteJson(c.bench_json, report);
  return 0;
}

}  // namespace mjf::runner
