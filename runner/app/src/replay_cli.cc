// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// `mjformation replay` and `mjformation view`. Windows are drawn by mjformation-view (GLFW, GLX),
// a separate executable next to this one: the runner itself renders offscreen with OSMesa, and
// one process should not load two GL implementations.
#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "mjformation/app/cli.hpp"
#include "mjformation/app/replay.hpp"
#include "mjformation/config/paths.hpp"
#include "mjformation/render.hpp"

namespace mjf::runner {
namespace {

int ExecViewer(const std::vector<std::string>& args) {
  const std::string viewer = ExecutableDir() + "/mjformation-view";
  if (!IsFile(viewer)) {
    std::fprintf(stderr,
                 "mjformation: error: the window needs %s, which is not installed (it is built "
                 "when GLFW is found: Debian package libglfw3-dev)\n",
                 viewer.c_str());
    return 1;
  }
  // The name its usage and --help show: the command the user typed, not the helper's path.
  std::string name = "mjformation view";
  std::vector<char*> argv;
  argv.push_back(name.data());
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  execv(viewer.c_str(), argv.data());
  std::perror(("mjformation: cannot start " + viewer).c_str());
  return 1;
}

constexpr double kTrailPeriod = 0.1;  // s, as run.cc and TrailsAt

// Creates `path` for the renderer, refusing one that exists: O_EXCL makes the check and the
// creation one step, so a file that appears after ReplayOutputs looked is not replaced either.
void ClaimNewFile(const std::string& path) {
  const int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
  if (fd < 0) {
    throw ReplayError(path + ": cannot create it (" + std::strerror(errno) +
                      "); replay never replaces a file");
  }
  close(fd);
}

}  // namespace

namespace {

// "replay: video 120/600 frames (20 %), ETA 35 s" on stderr: rewritten in place on a terminal,
// else a line every 10 %, so a log is not flooded.
class VideoProgress {
 public:
  VideoProgress(int64_t total, bool enabled)
      : total_(std::max<int64_t>(1, total)),
        enabled_(enabled),
        tty_(isatty(2) != 0),
        start_(std::chrono::steady_clock::now()) {}
  void Done(int64_t frames) {
    if (!enabled_) return;
    const int percent = static_cast<int>(100 * frames / total_);
    if (percent == last_percent_ ||
        (!tty_ && percent / 10 == last_percent_ / 10 && frames < total_))
      return;
    last_percent_ = percent;
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double eta = frames > 0 ? elapsed * static_cast<double>(total_ - frames) / frames : 0;
    std::fprintf(stderr, "%sreplay: video %lld/%lld frames (%d %%), ETA %.0f s%s", tty_ ? "\r" : "",
                 static_cast<long long>(frames), static_cast<long long>(total_), percent, eta,
                 tty_ && frames < total_ ? "" : "\n");
    std::fflush(stderr);
  }

 private:
  int64_t total_;
  bool enabled_, tty_;
  std::chrono::steady_clock::time_point start_;
  int last_percent_ = -1;
};

}  // namespace

namespace {

// The PNGs of `times` into out_dir, each frame once, appended to `written`.
void RenderSnapshots(const Recording& rec, const std::vector<double>& times,
                     const std::string& out_dir, ReplayScene& scene,
                     std::vector<std::string>* written) {
  render::OffscreenRenderer renderer(scene.model(), rec.render.width, rec.render.height,
                                     rec.render.shadows);
  mkdir(out_dir.c_str(), 0755);
  for (double time : times) {
    const int frame = rec.Frame(time);
    const std::string path = SnapshotPath(out_dir, rec, time);
    if (std::find(written->begin(), written->end(), path) != written->end()) continue;
    scene.Pose(frame);
    const Vec3 target = CameraTarget(rec.render, rec.pos[frame]);
    const auto& rgb = renderer.Render(
        scene.data(), FollowingCamera(rec.render, rec.pos[frame], target),
        ReplayOverlay(rec, scene.model(), TrailsAt(rec, frame), frame), target.data());
    ClaimNewFile(path);
    render::WritePng(path, rgb.data(), rec.render.width, rec.render.height);
    written->push_back(path);
  }
}

}  // namespace

// Offscreen (OSMesa), so here and not in replay.cc, which the window executable links.
std::vector<std::string> RenderReplay(const Recording& rec, const std::vector<double>& times,
                                      const std::string& out_dir, const ReplayVideo& v) {
  // Before the snapshots: a video without ffmpeg fails before anything is written.
  if (!v.path.empty() && render::FfmpegPath().empty()) {
    throw std::runtime_error("--video " + v.path + ": " + render::FfmpegMissing());
  }
  ReplayScene scene(rec);
  std::vector<std::string> written;
  auto overlay = [&](const TrailBuffer& trails, int frame) {
    return ReplayOverlay(rec, scene.model(), trails, frame);
  };
  if (!times.empty()) RenderSnapshots(rec, times, out_dir, scene, &written);
  if (!v.path.empty()) {
    // The snapshots' size by default: a video frame then shows what a snapshot shows.
    const int width = v.width > 0 ? v.width : rec.render.width;
    const int height = v.height > 0 ? v.height : rec.render.height;
    scene.AllowOffscreen(width, height);
    render::OffscreenRenderer renderer(scene.model(), width, height, rec.render.video_shadows);
    ClaimNewFile(v.path);
    render::VideoWriter video(v.path, width, height, rec.render.video_fps);
    const int64_t total =
        static_cast<int64_t>(std::floor(rec.t.back() * rec.render.video_fps + 1e-9)) + 1;
    VideoProgress progress(total, v.progress);
    TrailBuffer trails(rec.n_vehicles, rec.render.trail_seconds, kTrailPeriod);
    double next_trail = 0;
    int last = -1;
    for (int64_t k = 0;; ++k) {
      const double time = static_cast<double>(k) / rec.render.video_fps;
      if (time > rec.t.back() + 1e-9) break;
      const int frame = rec.Frame(time);
      for (int j = last + 1; j <= frame; ++j) {
        if (rec.t[j] >= next_trail - 1e-9) {
          trails.Add(rec.pos[j]);
          next_trail = rec.t[j] + kTrailPeriod;
        }
      }
      last = frame;
      scene.Pose(frame);
      const Vec3 target = CameraTarget(rec.render, rec.pos[frame]);
      video.AddFrame(renderer
                         .Render(scene.data(), FollowingCamera(rec.render, rec.pos[frame], target),
                                 overlay(trails, frame), target.data())
                         .data());
      progress.Done(k + 1);
    }
    video.Close();
    written.push_back(v.path);
  }
  return written;
}

void AddReplayCommand(CLI::App& app, CliCommands* c) {
  c->replay = app.add_subcommand(
      "replay",
      "Show a finished run again from its recorded states (no re-simulation): in a window, or "
      "offscreen into a video or PNGs");
  c->replay->add_option("run_dir", c->replay_dir, "run directory written by `mjformation run`")
      ->required();
  CLI::Option* video = c->replay->add_option(
      "--video", c->replay_video,
      "render to this MP4 (at [render] video_fps and the snapshots' size) instead of a window");
  c->replay
      ->add_option("--video-size", c->replay_video_size,
                   "WIDTHxHEIGHT of the --video frames (default: [render] width x height of the "
                   "run; at most 7680x4320)")
      ->needs(video)
      ->check(CLI::Validator(
          [](std::string& text) {
            try {
              ParseVideoSize(text);
            } catch (const std::invalid_argument& e) {
              return std::string(e.what());
            }
            return std::string();
          },
          "WxH", "video size"));
  c->replay
      ->add_option("--snapshots", c->replay_snapshots,
                   "render PNGs at these times (s) instead of a window, e.g. 10 20")
      ->delimiter(',');
  c->replay->add_option("--out,-o", c->replay_out,
                        "folder for --snapshots PNGs (default: RUN_DIR/replay)");
}

int ReplayCommand(const CliCommands& c) {
  if (c.replay_video.empty() && c.replay_snapshots.empty()) {
    return ExecViewer({"--replay", c.replay_dir});
  }
  const Recording rec = LoadRecording(c.replay_dir);
  CheckReplayTimes(rec, c.replay_snapshots);
  const std::string out = c.replay_out.empty() ? c.replay_dir + "/replay" : c.replay_out;
  RefuseExistingFiles(ReplayOutputs(rec, c.replay_snapshots, out, c.replay_video));
  ReplayVideo video;
  video.path = c.replay_video;
  if (!c.replay_video_size.empty()) {
    const auto size = ParseVideoSize(c.replay_video_size);  // checked by the parser already
    video.width = size[0];
    video.height = size[1];
  }
  for (const auto& path : RenderReplay(rec, c.replay_snapshots, out, video)) {
    std::printf("%s\n", path.c_str());
  }
  return 0;
}

void AddViewCommand(CLI::App& app, CliCommands* c) {
  c->view =
      app.add_subcommand("view",
                         "Fly an experiment live in a window (keys: space pause, right arrow step, "
                         "+/- speed, backspace reset, c camera, esc quit)");
  c->view->allow_extras();
  c->view->prefix_command();  // everything after `view` goes to mjformation-view as is
  // --help too: the window's options (--screenshot, --speed, --replay, --size, ...) are
  // mjformation-view's, so its help is the one that lists them.
  c->view->set_help_flag();
}

int ViewCommand(const CliCommands& c) {
  std::vector<std::string> args = c.view->remaining();
  if (args.empty()) {
    std::fprintf(stderr,
                 "mjformation view: usage: mjformation view EXPERIMENT.toml [--set "
                 "section.key=value]... [--plugin-path DIR]...\n");
    return 2;
  }
  return ExecViewer(args);
}

}  // namespace mjf::runner
