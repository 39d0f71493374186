// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
// Offscreen rendering of a MuJoCo state (OSMesa, no display needed), PNG snapshots and H.264
// video through an ffmpeg pipe.
//
// Threading: each OffscreenRenderer owns its OSMesa context, MuJoCo render context, scene,
// options and output buffers; nothing is global. Several renderers may live on one thread (each
// Render makes its own context current) or on several threads, as long as one renderer is used by
// one thread at a time.
#ifndef MJFORMATION_RENDER_HPP_
#define MJFORMATION_RENDER_HPP_

#include <mujoco/mujoco.h>
#include <sys/types.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace mjf::render {

struct CameraSpec {
  // "follow": look at the `target` point given per frame (e.g. the leader or the formation
  //           centroid; falls back to `lookat` when no target is given) from
  //           distance/azimuth/elevation;
  // "fixed":  lookat/distance/azimuth/elevation as given;
  // "model":  the model's <camera> named `model_camera`.
  std::string mode = "follow";
  double distance = 40, azimuth = 90, elevation = -60;  // m, deg, deg (MuJoCo free camera)
  double lookat[3] = {0, 0, 0};
  std::string model_camera;  // for mode "model"
};

// The one palette of the pictures: vehicle i's colour (0 = the leader, gold; followers 1..N each
// their own hue, never red, which marks safety events). Trails, vehicle markers, the vehicles'
// bodies (TintVehicleGeoms) and the legend all take it from here. Distinct for every i: a fixed
// list of well separated colours, then hues spread by the golden angle.
std::array<float, 4> VehicleColour(int vehicle);
// "leader", "follower 3": the legend's names.
std::string VehicleName(int vehicle);
// The colour of safety-event marks (and nothing else).
constexpr std::array<float, 4> kEventColour = {0.95f, 0.05f, 0.05f, 0.8f};

// A safety event drawn into a picture: a red sphere at `pos` with a short label beside it.
struct EventMark {
  std::array<double, 3> pos;
  std::string label;  // e.g. "F6 flip 34.19 s"
};

// Drawn into the scene after mjv_updateScene, as extra decor geoms. Geoms beyond the scene's
// capacity are skipped (trails first, then slots, then the ring get a place). Trail i, disc i
// and vehicle i take VehicleColour(i): there are no per-overlay colours, so that they always
// agree with the legend.
struct Overlay {
  std::vector<std::vector<std::array<double, 3>>> trails;  // per vehicle polyline (m)
  std::vector<std::array<double, 3>> slots;                // desired slots: translucent spheres
  std::vector<std::array<double, 3>> ring_points;          // optional polyline (e.g. 10 m circle)
  // Vehicle positions: a translucent disc under each one in its trail's colour, sized with the
  // camera distance, so vehicles half a metre wide stay visible in a 60 m wide view.
  std::vector<std::array<double, 3>> markers;
  std::string label;  // optional text in the top-left corner (e.g. "t = 10.0 s")
  // Each vehicle's root body in the model (-1: unknown): its geoms are recoloured in the
  // vehicle's palette colour at render time (the model is not changed). Empty: model colours.
  std::vector<int> vehicle_bodies;
  int legend_vehicles = 0;        // > 0: a legend (leader, follower 1..N) in the top-right corner
  std::vector<EventMark> events;  // safety events seen so far
};

// Recolours, in a scene filled by mjv_updateScene, every geom of each vehicle's body subtree
// (overlay.vehicle_bodies) to the vehicle's palette colour, keeping each geom's transparency;
// invisible geoms (alpha 0, e.g. collision hulls) stay invisible. The leader is drawn a little
// brighter (emission). Returns how many scene geoms were recoloured. Needs no GL context.
int TintVehicleGeoms(const mjModel* m, mjvScene* scene, const std::vector<int>& vehicle_bodies);

// Draws the legend of `n_vehicles` (a swatch in each vehicle's colour and its name; beyond
// kLegendRows, "... and K more") in the top-right corner of `viewport`, after mjr_render, in
// the current GL context of `con`. Returns the legend's rectangle (pixels, origin bottom-left).
mjrRect DrawLegend(const mjrRect& viewport, int n_vehicles, const mjrContext* con);
constexpr int kLegendRows = 16;

// Everything of `overlay` that is drawn after mjr_render (the legend, then the label top-left),
// shared by the offscreen renderer and the live viewer.
void DrawOverlayText(const mjrRect& viewport, const Overlay& overlay, const mjrContext* con);

// Appends the overlay to a scene already filled by mjv_updateScene, as decor geoms (lines a few
// pixels wide for an image `viewport_height` pixels high, slot spheres and vehicle discs sized
// with the camera distance). Returns the number of geoms skipped because the scene was full.
// Needs no GL context: the offscreen renderer and the live viewer share it.
int AddOverlayGeoms(mjvScene* scene, const Overlay& overlay, double cam_distance,
                    int viewport_height);

class OffscreenRenderer {
 public:
  // Creates its own OSMesa context and MuJoCo render context for m (m must outlive the
  // renderer). Throws std::runtime_error with a clear message when width/height are not positive
  // or exceed the model's <visual><global offwidth offheight>, or when OSMesa fails.
  OffscreenRenderer(const mjModel* m, int width, int height, bool shadows = true);
  ~OffscreenRenderer();
  OffscreenRenderer(const OffscreenRenderer&) = delete;
  OffscreenRenderer& operator=(const OffscreenRenderer&) = delete;

  // Renders d (only read, except that MuJoCo counts mjWARN_VGEOMFULL in d->warning when the
  // model alone overflows the scene); `target` is the follow point for mode "follow". Returns
  // RGB, rows top-down, width*height*3 bytes; valid until the next Render of this renderer.
  // Throws std::runtime_error for an unknown camera mode or model camera name.
  const std::vector<unsigned char>& Render(const mjData* d, const CameraSpec& camera,
                                           const Overlay& overlay,
                                           const double target[3] = nullptr);
  int width() const;
  int height() const;
  // Overlay geoms dropped by the last Render because the scene was full.
  int skipped_overlay_geoms() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Writes an 8-bit RGB PNG (rows top-down) through path + ".tmp" and a rename, so a PNG at `path`
// is never half-written. Throws std::runtime_error naming the path.
void WritePng(const std::string& path, const unsigned char* rgb, int width, int height);

// The absolute path of the ffmpeg a VideoWriter starts, or "" when PATH holds none. Callers
// that write files before their first video frame check it first.
std::string FfmpegPath();
// Why a video cannot be made without ffmpeg and what to install, for an error message.
std::string FfmpegMissing();

// Pipes raw RGB frames into ffmpeg (H.264 in mp4, yuv420p, -loglevel error). ffmpeg writes to
// path + ".tmp", renamed to `path` when ffmpeg finishes successfully. Odd sizes are padded by one
// pixel (yuv420p needs even sizes).
class VideoWriter {
 public:
  // Throws std::runtime_error when ffmpeg is not on PATH, the output directory does not exist or
  // is not writable, or ffmpeg cannot be started.
  VideoWriter(const std::string& path, int width, int height, double fps);
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;
  // One frame, width*height*3 bytes, rows top-down. Throws if ffmpeg died (with its message).
  void AddFrame(const unsigned char* rgb_top_down);
  // Waits for ffmpeg; throws if it failed. Idempotent; also called by the destructor (which
  // swallows errors).
  void Close();
  ~VideoWriter();
  int frames() const { return frames_; }

 private:
  std::string path_, tmp_path_, err_path_;
  int width_, height_;
  int fd_ = -1;
  int err_fd_ = -1;
  pid_t pid_ = -1;
  int frames_ = 0;
  bool closed_ = false;
  std::string FfmpegMessage() const;
};

}  // namespace mjf::render

#endif  // MJFORMATION_RENDER_HPP_
