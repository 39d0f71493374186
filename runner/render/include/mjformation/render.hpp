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

// Drawn into the scene after mjv_updateScene, as extra decor geoms. Geoms beyond the scene's
// capacity are skipped (trails first, then slots, then the ring get a place).
struct Overlay {
  std::vector<std::vector<std::array<double, 3>>> trails;  // per vehicle polyline (m)
  std::vector<std::array<float, 4>> trail_rgba;            // per trail colour; default palette
  std::vector<std::array<double, 3>> slots;                // desired slots: translucent spheres
  std::vector<std::array<double, 3>> ring_points;          // optional polyline (e.g. 10 m circle)
  // Vehicle positions: a translucent disc under each one in its trail's colour, sized with the
  // camera distance, so vehicles half a metre wide stay visible in a 60 m wide view.
  std::vector<std::array<double, 3>> markers;
  std::string label;  // optional text in the top-left corner (e.g. "t = 10.0 s")
};

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
