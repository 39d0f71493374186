// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// mjformation-view: the window behind `mjformation view EXPERIMENT.toml` (a live simulation
// driven through the Simulation class's public API, the same plugins as `run`) and
// `mjformation replay RUN_DIR` (a finished run from its recorded states). GLFW window and MuJoCo's
// mjv/mjr, as MuJoCo's own `simulate` sample does; the overlay (trails, slots, the desired circle,
// vehicle markers) and the following camera are those of the snapshots (frame_view.hpp).
//
// Keys: space pause/run, right arrow one step while paused, + / - speed x2 / /2, backspace
// reset, c following / free camera, esc or q quit. Mouse: left drag rotates, right drag moves
// (and frees the camera), wheel zooms.
#include <GLFW/glfw3.h>
#include <fmt/format.h>
#include <mujoco/mujoco.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mjformation/app/cli.hpp"
#include "mjformation/app/replay.hpp"
#include "mjformation/config/config.hpp"
#include "mjformation/record/frame_view.hpp"
#include "mjformation/record/metrics.hpp"
#include "mjformation/record/recorders.hpp"
#include "mjformation/record/safety_events.hpp"
#include "mjformation/render.hpp"
#include "mjformation/sim/simulation.hpp"
#include "mjformation/time_steps.hpp"

namespace mjf::runner {
namespace {

constexpr double kTrailPeriod = 0.1;  // s, as run.cc

// What the window shows: a live simulation or a recorded run, advanced in simulated time.
class Source {
 public:
  virtual ~Source() = default;
  virtual const mjModel* model() const = 0;
  virtual mjData* data() = 0;
  virtual double time() const = 0;
  virtual double duration() const = 0;
  virtual bool finished() const = 0;
  virtual void AdvanceTo(double t) = 0;  // up to simulated time t (not past the end)
  virtual void StepOnce() = 0;           // one physics step, or one recorded row
  virtual void Reset() = 0;
  virtual const std::vector<Vec3>& positions() const = 0;
  virtual const std::vector<std::array<double, 2>>& slots() const = 0;
  virtual double sigma_f() const = 0;
  virtual const TrailBuffer& trails() const = 0;
  virtual const RenderConfig& render() const = 0;
  virtual double altitude() const = 0;
  virtual double ring_radius() const = 0;
  virtual const std::string& name() const = 0;
  virtual std::string error() const { return ""; }
  // Safety events to mark (a replay's, from summary.json; the live view has none).
  virtual std::vector<render::EventMark> events() const { return {}; }
};

// A live simulation: ComputeControls() / Integrate(), exactly the loop of `run`.
class LiveSource : public Source {
 public:
  explicit LiveSource(const ExperimentConfig& config) : config_(config) { Reset(); }

  const mjModel* model() const override { return sim_->model(); }
  mjData* data() override { return sim_->data(); }
  double time() const override { return sim_->time(); }
  double duration() const override { return config_.duration; }
  bool finished() const override { return done_ || !error_.empty(); }
  void AdvanceTo(double t) override {
    while (!finished() && sim_->time() + 0.5 * config_.timestep < t) StepOnce();
  }
  void StepOnce() override {
    if (finished()) return;
    try {
      if (sim_->step_index() >= sim_->total_steps()) {
        done_ = true;
        return;
      }
      sim_->Integrate();
      Observe();
    } catch (const SimulationError& e) {
      error_ = e.what();
      std::fprintf(stderr, "mjformation view: the run stopped: %s\n", e.what());
    }
  }
  void Reset() override {
    metrics_.reset();
    sim_.reset();  // plugins and model of the old run go before the new ones are made
    sim_ = std::make_unique<Simulation>(config_);
    metrics_ = std::make_unique<OnlineMetrics>(*sim_);
    safety_ = std::make_unique<SafetyMonitor>(config_.safety, VehicleRadii(*sim_));
    marks_.clear();
    trails_ = TrailBuffer(sim_->n_vehicles(), config_.render.trail_seconds, kTrailPeriod);
    slot_buffer_.assign(2 * static_cast<size_t>(sim_->n_vehicles()), 0.0);
    done_ = false;
    error_.clear();
    Observe();
  }
  const std::vector<Vec3>& positions() const override { return positions_; }
  const std::vector<std::array<double, 2>>& slots() const override { return slots_; }
  double sigma_f() const override { return sigma_f_; }
  const TrailBuffer& trails() const override { return trails_; }
  const RenderConfig& render() const override { return config_.render; }
  double altitude() const override { return config_.altitude; }
  double ring_radius() const override {
    return sim_->shape() && config_.shape.type == ShapeType::kCircle ? config_.shape.radius : 0.0;
  }
  const std::string& name() const override { return config_.name; }
  std::string error() const override { return error_; }
  std::vector<render::EventMark> events() const override { return marks_; }

 private:
  // Sensors and plugins for the current state (the controls the next Integrate applies), then
  // what is drawn, as `run` samples it.
  void Observe() {
    sim_->ComputeControls();
    sigma_f_ = metrics_->Sample(*sim_, &slot_buffer_, false);
    const int n = sim_->n_vehicles();
    positions_.resize(n);
    slots_.resize(n);
    for (int i = 0; i < n; ++i) {
      const auto& p = sim_->states()[i].pos;
      positions_[i] = {p[0], p[1], p[2]};
      slots_[i] = {i == 0 ? NAN : slot_buffer_[2 * i], i == 0 ? NAN : slot_buffer_[2 * i + 1]};
    }
    // Safety events as `run` sees them (recorders.cc), marked where they happened.
    const size_t fresh = safety_->Check(sim_->time(), sim_->states());
    const auto& events = safety_->events();
    for (size_t k = events.size() - fresh; k < events.size(); ++k) {
      const SafetyEvent& e = events[k];
      if (marks_.size() >= kMaxEventMarks || !MarkedEventKind(e.kind)) continue;
      Vec3 at = {0, 0, 0};
      for (int v : e.vehicles) {
        for (int a = 0; a < 3; ++a) at[a] += positions_[v][a] / e.vehicles.size();
      }
      marks_.push_back(MakeEventMark(e.kind, e.time_s, e.vehicles, at));
    }
    const int64_t trail_every = NearestSteps(kTrailPeriod, config_.timestep);
    if (sim_->step_index() % trail_every == 0) trails_.Add(positions_);
  }

  ExperimentConfig config_;
  std::unique_ptr<Simulation> sim_;
  std::unique_ptr<OnlineMetrics> metrics_;
  std::unique_ptr<SafetyMonitor> safety_;
  std::vector<render::EventMark> marks_;
  TrailBuffer trails_{0, 1, 1};
  std::vector<double> slot_buffer_;
  std::vector<Vec3> positions_;
  std::vector<std::array<double, 2>> slots_;
  double sigma_f_ = NAN;
  bool done_ = false;
  std::string error_;
};

// A finished run, frame by frame from timeseries.csv.
class ReplaySource : public Source {
 public:
  explicit ReplaySource(const std::string& dir)
      : rec_(LoadRecording(dir)), scene_(rec_), trails_(TrailsAt(rec_, 0)) {
    Show(0);
  }
  const mjModel* model() const override { return scene_.model(); }
  mjData* data() override { return scene_.data(); }
  double time() const override { return rec_.t[frame_]; }
  double duration() const override { return rec_.t.back(); }
  bool finished() const override { return frame_ + 1 >= static_cast<int>(rec_.t.size()); }
  void AdvanceTo(double t) override {
    int f = frame_;
    while (f + 1 < static_cast<int>(rec_.t.size()) && rec_.t[f + 1] <= t + 1e-9) ++f;
    if (f != frame_) Show(f);
  }
  void StepOnce() override {
    if (!finished()) Show(frame_ + 1);
  }
  void Reset() override { Show(0); }
  const std::vector<Vec3>& positions() const override { return rec_.pos[frame_]; }
  const std::vector<std::array<double, 2>>& slots() const override { return rec_.slot[frame_]; }
  double sigma_f() const override { return rec_.sigma_f[frame_]; }
  const TrailBuffer& trails() const override { return trails_; }
  const RenderConfig& render() const override { return rec_.render; }
  double altitude() const override { return rec_.altitude; }
  double ring_radius() const override { return rec_.ring_radius; }
  const std::string& name() const override { return rec_.name; }
  std::vector<render::EventMark> events() const override {
    return ReplayOverlay(rec_, scene_.model(), trails_, frame_).events;
  }

 private:
  void Show(int frame) {
    frame_ = frame;
    scene_.Pose(frame);
    trails_ = TrailsAt(rec_, frame);
  }
  Recording rec_;
  ReplayScene scene_;
  TrailBuffer trails_;
  int frame_ = 0;
};

struct Options {
  std::string experiment, replay_dir;
  std::vector<std::string> overrides, plugin_path;
  std::string screenshot;     // test hook: PNG of the window at --screenshot-at
  double screenshot_at = -1;  // s of simulated time
  double speed = 1.0;         // simulated seconds per wall second
  bool keep_open = false;     // after --screenshot: keep the window open (else it closes)
  int width = 1280, height = 720;
};

class Viewer {
 public:
  Viewer(Source* source, const Options& options) : src_(source), opt_(options) {
    // The README's name for the window, so that a user (and xdotool) finds it by that name.
    window_ = glfwCreateWindow(opt_.width, opt_.height,
                               ("mjformation-view: " + src_->name()).c_str(), nullptr, nullptr);
    if (!window_) throw std::runtime_error("cannot create a window (GLFW/OpenGL)");
    glfwMakeContextCurrent(window_);
    glfwSwapInterval(1);
    glfwSetWindowUserPointer(window_, this);
    glfwSetKeyCallback(window_, [](GLFWwindow* w, int key, int, int act, int) {
      static_cast<Viewer*>(glfwGetWindowUserPointer(w))->Key(key, act);
    });
    glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int, int, int) {
      static_cast<Viewer*>(glfwGetWindowUserPointer(w))->Button();
    });
    glfwSetCursorPosCallback(window_, [](GLFWwindow* w, double x, double y) {
      static_cast<Viewer*>(glfwGetWindowUserPointer(w))->Move(x, y);
    });
    glfwSetScrollCallback(window_, [](GLFWwindow* w, double, double dy) {
      static_cast<Viewer*>(glfwGetWindowUserPointer(w))->Scroll(dy);
    });
    mjv_defaultOption(&vopt_);
    mjv_defaultPerturb(&pert_);
    mjv_defaultScene(&scn_);
    mjr_defaultContext(&con_);
    MakeScene();
    speed_ = opt_.speed;
    ResetCamera();
  }
  ~Viewer() {
    mjr_freeContext(&con_);
    mjv_freeScene(&scn_);
    if (window_) glfwDestroyWindow(window_);
  }

  // Runs until the window closes or a quit key; returns 0, or 1 when the screenshot failed.
  int Loop() {
    double last = glfwGetTime();
    while (!glfwWindowShouldClose(window_)) {
      const double now = glfwGetTime();
      // At most 0.1 s of wall time per frame, so a slow frame does not snowball.
      const double wall = std::min(0.1, now - last);
      last = now;
      if (!paused_ && !src_->finished()) {
        double target = src_->time() + speed_ * wall;
        if (opt_.screenshot_at >= 0 && !shot_taken_) target = std::min(target, opt_.screenshot_at);
        src_->AdvanceTo(target);
      }
      Draw();
      if (opt_.screenshot_at >= 0 && !shot_taken_ &&
          (src_->time() >= opt_.screenshot_at - 1e-9 || src_->finished())) {
        if (!Screenshot()) return 1;
        shot_taken_ = true;
        // A screenshot is the job of a script: the window closes once it is saved, unless the
        // user asked to keep it (--keep-open, e.g. to send it keys afterwards).
        if (!opt_.keep_open) return 0;
      }
      glfwSwapBuffers(window_);
      glfwPollEvents();
    }
    return 0;
  }

 private:
  void MakeScene() {
    // Model geoms and decor, plus room for the overlay (trails are many segments).
    mjv_makeScene(src_->model(), &scn_, 10000 + 2 * (src_->model()->ngeom + src_->model()->nsite));
    mjr_makeContext(src_->model(), &con_, mjFONTSCALE_150);
  }

  void ResetCamera() {
    const RenderConfig& r = src_->render();
    const Vec3 target = CameraTarget(r, src_->positions());
    const render::CameraSpec spec = FollowingCamera(r, src_->positions(), target);
    mjv_defaultCamera(&cam_);
    cam_.type = mjCAMERA_FREE;
    cam_.distance = spec.distance;
    cam_.azimuth = spec.azimuth;
    cam_.elevation = spec.elevation;
    const double* look = spec.mode == "follow" ? target.data() : spec.lookat;
    for (int k = 0; k < 3; ++k) cam_.lookat[k] = look[k];
    follow_ = spec.mode == "follow";
  }

  void Draw() {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    const mjrRect viewport = {0, 0, w, h};
    if (follow_) {
      const Vec3 target = CameraTarget(src_->render(), src_->positions());
      for (int k = 0; k < 3; ++k) cam_.lookat[k] = target[k];
    }
    mjv_updateScene(src_->model(), src_->data(), &vopt_, &pert_, &cam_, mjCAT_ALL, &scn_);
    render::Overlay overlay =
        FrameOverlay(src_->trails(), src_->positions(), src_->slots(), src_->altitude(),
                     src_->ring_radius(), FrameLabel(src_->name(), src_->time()));
    // A reset makes a new model: the vehicles' bodies are looked up again then only.
    if (bodies_model_ != src_->model()) {
      bodies_model_ = src_->model();
      bodies_ = VehicleBodies(src_->model(), static_cast<int>(src_->positions().size()));
    }
    overlay.vehicle_bodies = bodies_;
    overlay.events = src_->events();
    render::TintVehicleGeoms(src_->model(), &scn_, overlay.vehicle_bodies);
    render::AddOverlayGeoms(&scn_, overlay, cam_.distance, h);
    scn_.flags[mjRND_SHADOW] = src_->render().shadows ? 1 : 0;
    mjr_render(viewport, &scn_, &con_);

    const std::string status = fmt::format(
        "{}{}", paused_ ? "PAUSED" : fmt::format("speed x{:g}", speed_),
        src_->finished() ? (src_->error().empty() ? "  (end)" : "  (stopped: see terminal)") : "");
    const std::string title = "experiment\nstate\ntime\nsigma_f (68)\ncamera";
    const std::string values = fmt::format(
        "{}\n{}\n{:.2f} / {:.1f} s\n{}\n{}", src_->name(), status, src_->time(), src_->duration(),
        std::isnan(src_->sigma_f()) ? std::string("n/a") : fmt::format("{:.4f} m", src_->sigma_f()),
        follow_ ? "following (c: free)" : "free (c: follow)");
    mjr_overlay(mjFONT_NORMAL, mjGRID_TOPLEFT, viewport, title.c_str(), values.c_str(), &con_);
    render::DrawLegend(viewport, overlay.legend_vehicles, &con_);
    mjr_overlay(mjFONT_NORMAL, mjGRID_BOTTOMLEFT, viewport,
                "space\nright\n+ / -\nbackspace\nc\nesc",
                "pause / run\none step (paused)\nspeed\nreset\ncamera\nquit", &con_);
  }

  // The window's pixels as PNG, and beside it (.json) the camera and the vehicle positions, so a
  // test can project the vehicles on its own and look for them in the picture.
  bool Screenshot() {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    std::vector<unsigned char> bottom_up(static_cast<size_t>(w) * h * 3), rgb(bottom_up.size());
    mjr_readPixels(bottom_up.data(), nullptr, {0, 0, w, h}, &con_);
    const size_t row = static_cast<size_t>(w) * 3;
    for (int y = 0; y < h; ++y) {
      std::copy_n(bottom_up.data() + row * (h - 1 - y), row, rgb.data() + row * y);
    }
    try {
      render::WritePng(opt_.screenshot, rgb.data(), w, h);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "mjformation view: %s\n", e.what());
      return false;
    }
    nlohmann::ordered_json j;
    j["time"] = src_->time();
    j["width"] = w;
    j["height"] = h;
    j["fovy_deg"] = src_->model()->vis.global.fovy;
    j["camera"] = {{"lookat", {cam_.lookat[0], cam_.lookat[1], cam_.lookat[2]}},
                   {"distance", cam_.distance},
                   {"azimuth", cam_.azimuth},
                   {"elevation", cam_.elevation}};
    j["positions"] = src_->positions();
    std::ofstream(opt_.screenshot + ".json") << j.dump(2) << "\n";
    std::printf("screenshot: %s at t = %.3f s\n", opt_.screenshot.c_str(), src_->time());
    std::fflush(stdout);
    return true;
  }

  // One line per key action on stdout: what the user did, and where the run is.
  void Log(const char* what) const {
    std::printf("%s: t = %.3f s, speed x%g\n", what, src_->time(), speed_);
    std::fflush(stdout);
  }

  void Key(int key, int action) {
    if (action == GLFW_RELEASE) return;
    switch (key) {
      case GLFW_KEY_ESCAPE:
      case GLFW_KEY_Q:
        glfwSetWindowShouldClose(window_, 1);
        break;
      case GLFW_KEY_SPACE:
        paused_ = !paused_;
        Log(paused_ ? "paused" : "running");
        break;
      case GLFW_KEY_RIGHT:
        if (paused_) {
          src_->StepOnce();
          Log("step");
        }
        break;
      case GLFW_KEY_EQUAL:
      case GLFW_KEY_KP_ADD:
        speed_ = std::min(64.0, speed_ * 2);
        Log("speed");
        break;
      case GLFW_KEY_MINUS:
      case GLFW_KEY_KP_SUBTRACT:
        speed_ = std::max(1.0 / 64, speed_ / 2);
        Log("speed");
        break;
      case GLFW_KEY_BACKSPACE:
        try {
          src_->Reset();
          // A live reset compiles the model again: the render context follows it.
          mjr_freeContext(&con_);
          mjv_freeScene(&scn_);
          MakeScene();
          Log("reset");
        } catch (const std::exception& e) {
          std::fprintf(stderr, "mjformation view: reset failed: %s\n", e.what());
          glfwSetWindowShouldClose(window_, 1);
        }
        break;
      case GLFW_KEY_C:
        follow_ = !follow_;
        Log(follow_ ? "camera following" : "camera free");
        break;
      default:
        break;
    }
  }

  void Button() {
    left_ = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    right_ = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    glfwGetCursorPos(window_, &x_, &y_);
  }

  void Move(double x, double y) {
    const double dx = x - x_, dy = y - y_;
    x_ = x;
    y_ = y;
    if (!left_ && !right_) return;
    int w = 0, h = 0;
    glfwGetWindowSize(window_, &w, &h);
    const bool shift = glfwGetKey(window_, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ||
                       glfwGetKey(window_, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
    int action = mjMOUSE_ZOOM;
    if (right_) {
      action = shift ? mjMOUSE_MOVE_H : mjMOUSE_MOVE_V;
      follow_ = false;  // moving the look-at point frees the camera
    } else if (left_) {
      action = shift ? mjMOUSE_ROTATE_H : mjMOUSE_ROTATE_V;
    }
    mjv_moveCamera(src_->model(), action, dx / h, dy / h, &cam_);
  }

  void Scroll(double dy) { mjv_moveCamera(src_->model(), mjMOUSE_ZOOM, 0, -0.05 * dy, &cam_); }

  Source* src_;
  Options opt_;
  GLFWwindow* window_ = nullptr;
  mjvCamera cam_;
  mjvOption vopt_;
  mjvPerturb pert_;
  mjvScene scn_;
  mjrContext con_;
  const mjModel* bodies_model_ = nullptr;  // the model bodies_ was looked up in
  std::vector<int> bodies_;                // each vehicle's root body, for its colour
  bool paused_ = false, follow_ = true, shot_taken_ = false;
  bool left_ = false, right_ = false;
  double x_ = 0, y_ = 0;
  double speed_ = 1.0;
};

// The replayed run or the live experiment; null (after the message) on bad input, which is
// reported before a window opens, as by `run`.
std::unique_ptr<Source> MakeSource(const Options& o) {
  try {
    if (!o.replay_dir.empty()) return std::make_unique<ReplaySource>(o.replay_dir);
    ExperimentConfig config = LoadExperiment(o.experiment, o.overrides);
    for (const auto& p : o.plugin_path) config.plugin_path.push_back(p);
    return std::make_unique<LiveSource>(config);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mjformation: error: %s\n", e.what());
    return nullptr;
  }
}

// What is wrong with a parsed command line that CLI11 cannot see; empty when nothing is.
std::string UsageProblem(const Options& o) {
  // NaN passes CLI::Range (every comparison with it is false): said apart.
  if (!std::isfinite(o.speed)) return "--speed must be a finite number";
  if (!std::isfinite(o.screenshot_at)) return "--screenshot-at must be a finite number";
  if (o.experiment.empty() == o.replay_dir.empty()) {
    return "give an experiment file, or --replay RUN_DIR";
  }
  return "";
}

// One rule for every output file, as replay and bench --json: an existing file is never
// replaced. Looked at before the window opens, so nothing runs for a shot that cannot be kept.
// True (after the message) when --screenshot FILE or FILE.json exists.
bool ScreenshotWouldReplace(const Options& o) {
  if (o.screenshot.empty()) return false;
  try {
    RefuseExistingFiles({o.screenshot, o.screenshot + ".json"});
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mjformation view: --screenshot %s\n", e.what());
    return true;
  }
  return false;
}

// Whether neither an X nor a Wayland display is set, said in a message that names the headless
// alternatives (GLFW's own error would only say that it failed).
bool NoDisplay() {
  const char* display = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((display && *display) || (wayland && *wayland)) return false;
  std::fprintf(stderr,
               "mjformation view: no display (DISPLAY is not set). The window needs an X "
               "server; on a headless machine use `mjformation run` (snapshots, video) or "
               "`xvfb-run mjformation view ...`\n");
  return true;
}

int Main(int argc, char** argv) {
  CLI::App app("mjformation-view: fly an experiment live, or replay a run, in a window");
  Options o;
  app.add_option("experiment", o.experiment, "experiment file (TOML)");
  app.add_option("--replay", o.replay_dir, "show this run directory instead");
  app.add_option("--set", o.overrides, "override a value: section.key=value (as `run`)");
  app.add_option("--plugin-path", o.plugin_path, "extra folder to search for plugins")
      ->check(CLI::ExistingDirectory);
  app.add_option("--speed", o.speed, "simulated seconds per second (default 1)")
      ->check(CLI::Range(1e-3, 1e3));
  app.add_option("--screenshot", o.screenshot,
                 "save the window to this new PNG and FILE.json, then close (--keep-open)");
  app.add_option("--screenshot-at", o.screenshot_at, "... at this simulated time, s")
      ->check(CLI::Range(0.0, 1e7));
  app.add_flag("--keep-open", o.keep_open, "after --screenshot, keep the window open");
  app.add_option("--size", o.width, "window width in pixels (height: 9/16 of it)")
      ->check(CLI::Range(160, 7680));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);  // --help: 0; every misuse of the command line: 2
    return code == 0 ? 0 : 2;
  }
  o.height = o.width * 9 / 16;
  if (const std::string bad = UsageProblem(o); !bad.empty()) {
    std::fprintf(stderr, "mjformation view: %s\n", bad.c_str());
    return 2;
  }
  if (!o.screenshot.empty() && o.screenshot_at < 0) o.screenshot_at = 0;

  std::unique_ptr<Source> source = ScreenshotWouldReplace(o) ? nullptr : MakeSource(o);
  if (!source) return 1;
  if (NoDisplay()) return 1;
  const char* display = std::getenv("DISPLAY");
  glfwSetErrorCallback([](int, const char* message) {
    std::fprintf(stderr, "mjformation view: GLFW: %s\n", message);
  });
  if (!glfwInit()) {
    std::fprintf(stderr, "mjformation view: cannot open the display '%s'\n",
                 display ? display : "");
    return 1;
  }
  int rc = 0;
  try {
    Viewer viewer(source.get(), o);
    rc = viewer.Loop();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mjformation view: %s\n", e.what());
    rc = 1;
  }
  source.reset();
  glfwTerminate();
  return rc;
}

}  // namespace
}  // namespace mjf::runner

int main(int argc, char** argv) { return mjf::runner::Main(argc, argv); }
