// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// `mjformation replay RUN_DIR`: a finished run shown again from what it recorded (scene.xml,
// timeseries.csv positions and attitudes, config.toml's [render]), with no re-simulation.
#ifndef MJFORMATION_APP_REPLAY_HPP_
#define MJFORMATION_APP_REPLAY_HPP_

#include <mujoco/mujoco.h>

#include <array>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "mjformation/config/config_error.hpp"
#include "mjformation/config/experiment.hpp"
#include "mjformation/record/frame_view.hpp"

namespace mjf::runner {

class ReplayError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The recorded states of a run directory, one frame per timeseries.csv row.
struct Recording {
  std::string dir;
  std::string name;        // summary.json "experiment", else config.toml [run] name
  RenderConfig render;     // config.toml [render] (defaults where absent)
  double altitude = 5;     // [vehicles] altitude: where slots are drawn
  double ring_radius = 0;  // [formation.shape] circle radius; 0: no circle drawn
  int n_vehicles = 0;
  std::vector<double> t, sigma_f;
  std::vector<std::vector<Vec3>> pos, rpy;  // [frame][vehicle]: m; roll, pitch, yaw (rad, ZYX)
  std::vector<std::vector<std::array<double, 2>>> slot;  // [frame][vehicle], NaN: none
  int Frame(double time) const;                          // the row nearest to `time`
  // summary.json "events" "list" (safety events), in the order recorded.
  struct Event {
    std::string kind;
    double time_s = 0;
    std::vector<int> vehicles;
  };
  std::vector<Event> events;
};

// Reads RUN_DIR/timeseries.csv, config.toml and summary.json. Throws ReplayError naming the file
// (and row) when one is missing or malformed.
Recording LoadRecording(const std::string& run_dir);

// The run's scene (scene.xml) posed at recorded frames: each vehicle's joints are set so its
// `imu` site (where the sensors read position and attitude) is at the recorded pose: a free joint
// (quadrotor) takes position and attitude, three slide joints (point mass, which never rotates)
// the position.
class ReplayScene {
 public:
  explicit ReplayScene(const Recording& recording);
  ~ReplayScene();
  ReplayScene(const ReplayScene&) = delete;
  ReplayScene& operator=(const ReplayScene&) = delete;
  void Pose(int frame);  // qpos from the record, then kinematics (all rendering needs)
  // Raises <visual><global offwidth offheight> of the replayed model (render only: the model
  // is never simulated) so that an offscreen renderer of width x height fits.
  void AllowOffscreen(int width, int height);
  const mjModel* model() const { return model_; }
  mjData* data() { return data_; }

 private:
  void Free();
  const Recording& rec_;
  mjModel* model_ = nullptr;
  mjData* data_ = nullptr;
  // How one vehicle is posed: its free joint's qpos address, or its slide joints.
  struct VehicleJoints {
    int free_qpos = -1;
    std::vector<int> slide_qpos;
    std::vector<Vec3> slide_axis;  // world frame
    Vec3 rest{};                   // the imu site's world position with the slides at zero
  };
  VehicleJoints BindJoints(int body, int site) const;
  std::vector<VehicleJoints> joints_;
  std::vector<Vec3> imu_offset_;  // imu site in its body's frame
};

// What is drawn at `frame`, as `run` drew it: FrameOverlay with the vehicles' colours (bodies
// of `model`) and the marks of the safety events seen by then, at the vehicles' recorded
// positions nearest the event's time.
render::Overlay ReplayOverlay(const Recording& recording, const mjModel* model,
                              const TrailBuffer& trails, int frame);

// The trails as `run` had drawn them at `frame`: samples every 0.1 s over trail_seconds.
TrailBuffer TrailsAt(const Recording& recording, int frame);

// The largest --video-size (8K UHD): beyond it, a typo rather than a wish, and several GB of
// frame buffers.
constexpr int kMaxVideoWidth = 7680, kMaxVideoHeight = 4320;
// "1920x1080" -> {1920, 1080}; an empty string: the run's snapshot size ([render] width x
// height). Throws std::invalid_argument with the reason for anything else (non-numeric, not
// positive, beyond kMaxVideoWidth x kMaxVideoHeight).
std::array<int, 2> ParseVideoSize(const std::string& text);

struct ReplayVideo {
  std::string path;           // empty: no video
  int width = 0, height = 0;  // 0: the run's snapshot size ([render] width, height)
  bool progress = true;       // a progress line on stderr while encoding
};

// --snapshots times must lie in the recording itself, [first, last] row of timeseries.csv (a
// killed run has no summary.json; a time beyond the rows would render the last frame under a
// misleading name). Throws ConfigError naming the time and the recorded range.
void CheckReplayTimes(const Recording& recording, const std::vector<double>& times);

// out_dir/replay_t<sss.ss>.png: the PNG of the frame nearest `time`, named by its recorded time.
std::string SnapshotPath(const std::string& out_dir, const Recording& recording, double time);

// Every file a replay would write: the PNGs of `times` (each once) and the video (when named).
std::vector<std::string> ReplayOutputs(const Recording& recording, const std::vector<double>& times,
                                       const std::string& out_dir, const std::string& video);

// `mjformation replay` without a window: PNGs at `times` into out_dir (replay_t<sss.ss>.png)
// and/or a video; returns the paths written.
std::vector<std::string> RenderReplay(const Recording& recording, const std::vector<double>& times,
                                      const std::string& out_dir, const ReplayVideo& video);

}  // namespace mjf::runner

#endif  // MJFORMATION_APP_REPLAY_HPP_
