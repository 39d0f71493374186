// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include <GL/osmesa.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <string>

#include "mjformation/render.hpp"

namespace mjf::render {
namespace {

// mjr_makeContext loads the GL entry points into MuJoCo's process-wide table (glad) every time it
// is called, and OSMesa context creation touches Mesa's global state: serialise creation and
// destruction. Rendering itself needs no lock.
std::mutex& ContextMutex() {
  static std::mutex mutex;
  return mutex;
}

constexpr int kOverlayCapacity = 10000;

}  // namespace

struct OffscreenRenderer::Impl {
  const mjModel* m = nullptr;
  int width = 0, height = 0;
  bool shadows = true;
  OSMesaContext osmesa = nullptr;
  std::vector<unsigned char> osmesa_buffer;  // OSMesa's default framebuffer (RGBA)
  mjvScene scn;
  mjvOption opt;
  mjvPerturb pert;
  mjvCamera cam;
  mjrContext con;
  bool scene_made = false, context_made = false;
  std::vector<unsigned char> bottom_up, rgb;
  int skipped = 0;

  ~Impl() { Free(); }

  void MakeCurrent() {
    if (!OSMesaMakeCurrent(osmesa, osmesa_buffer.data(), GL_UNSIGNED_BYTE, width, height)) {
      throw std::runtime_error("OffscreenRenderer: OSMesaMakeCurrent failed");
    }
  }

  void Free() {
    if (osmesa) {
      std::lock_guard<std::mutex> lock(ContextMutex());
      if (OSMesaMakeCurrent(osmesa, osmesa_buffer.data(), GL_UNSIGNED_BYTE, width, height)) {
        if (context_made) mjr_freeContext(&con);
      }
      context_made = false;
      OSMesaMakeCurrent(nullptr, nullptr, GL_UNSIGNED_BYTE, 0, 0);
      OSMesaDestroyContext(osmesa);
      osmesa = nullptr;
    }
    if (scene_made) mjv_freeScene(&scn);
    scene_made = false;
  }
};

OffscreenRenderer::OffscreenRenderer(const mjModel* m, int width, int height, bool shadows)
    : impl_(std::make_unique<Impl>()) {
  if (!m) throw std::runtime_error("OffscreenRenderer: no model");
  if (width <= 0 || height <= 0) {
    throw std::runtime_error("OffscreenRenderer: invalid image size " + std::to_string(width) +
                             "x" + std::to_string(height));
  }
  const int offw = m->vis.global.offwidth, offh = m->vis.global.offheight;
  if (width > offw || height > offh) {
    throw std::runtime_error("OffscreenRenderer: requested " + std::to_string(width) + "x" +
                             std::to_string(height) + " exceeds the model's offscreen buffer " +
                             std::to_string(offw) + "x" + std::to_string(offh) +
                             "; raise <visual><global offwidth=\"" +
                             std::to_string(std::max(width, offw)) + "\" offheight=\"" +
                             std::to_string(std::max(height, offh)) + "\"/> in the MJCF");
  }
  Impl& r = *impl_;
  r.m = m;
  r.width = width;
  r.height = height;
  r.shadows = shadows;
  r.osmesa_buffer.resize(static_cast<size_t>(width) * height * 4);
  r.bottom_up.resize(static_cast<size_t>(width) * height * 3);
  r.rgb.resize(r.bottom_up.size());

  mjv_defaultScene(&r.scn);
  mjv_defaultOption(&r.opt);
  mjv_defaultPerturb(&r.pert);
  mjv_defaultCamera(&r.cam);
  mjr_defaultContext(&r.con);
  bool offscreen = false;
  {
    std::lock_guard<std::mutex> lock(ContextMutex());
    r.osmesa = OSMesaCreateContextExt(OSMESA_RGBA, 24, 8, 8, nullptr);
    if (!r.osmesa) throw std::runtime_error("OffscreenRenderer: OSMesaCreateContextExt failed");
    if (!OSMesaMakeCurrent(r.osmesa, r.osmesa_buffer.data(), GL_UNSIGNED_BYTE, width, height)) {
      OSMesaDestroyContext(r.osmesa);
      r.osmesa = nullptr;
      throw std::runtime_error("OffscreenRenderer: OSMesaMakeCurrent failed for " +
                               std::to_string(width) + "x" + std::to_string(height));
    }
    // Model geoms and their decorations, plus room for the overlay.
    mjv_makeScene(m, &r.scn, kOverlayCapacity + 2 * (m->ngeom + m->nsite) + 100);
    r.scene_made = true;
    mjr_makeContext(m, &r.con, mjFONTSCALE_150);
    r.context_made = true;
    mjr_setBuffer(mjFB_OFFSCREEN, &r.con);
    offscreen = r.con.currentBuffer == mjFB_OFFSCREEN;
    OSMesaMakeCurrent(nullptr, nullptr, GL_UNSIGNED_BYTE, 0, 0);
  }
  if (!offscreen) {
    r.Free();
    throw std::runtime_error(
        "OffscreenRenderer: MuJoCo could not create its offscreen framebuffer (OSMesa)");
  }
}

OffscreenRenderer::~OffscreenRenderer() = default;

int OffscreenRenderer::width() const { return impl_->width; }
int OffscreenRenderer::height() const { return impl_->height; }
int OffscreenRenderer::skipped_overlay_geoms() const { return impl_->skipped; }

const std::vector<unsigned char>& OffscreenRenderer::Render(const mjData* d,
                                                            const CameraSpec& camera,
                                                            const Overlay& overlay,
                                                            const double target[3]) {
  if (!d) throw std::runtime_error("OffscreenRenderer::Render: no mjData");
  Impl& r = *impl_;
  const mjModel* m = r.m;
  mjvCamera& cam = r.cam;
  mjv_defaultCamera(&cam);
  if (camera.mode == "follow" || camera.mode == "fixed") {
    cam.type = mjCAMERA_FREE;
    const double* look = camera.mode == "follow" && target ? target : camera.lookat;
    for (int k = 0; k < 3; ++k) cam.lookat[k] = look[k];
    cam.distance = camera.distance;
    cam.azimuth = camera.azimuth;
    cam.elevation = camera.elevation;
  } else if (camera.mode == "model") {
    const int id = mj_name2id(m, mjOBJ_CAMERA, camera.model_camera.c_str());
    if (id < 0) {
      throw std::runtime_error("OffscreenRenderer: the model has no camera named '" +
                               camera.model_camera + "'");
    }
    cam.type = mjCAMERA_FIXED;
    cam.fixedcamid = id;
  } else {
    throw std::runtime_error("OffscreenRenderer: unknown camera mode '" + camera.mode +
                             "' (follow, fixed or model)");
  }

  r.MakeCurrent();
  mjr_setBuffer(mjFB_OFFSCREEN, &r.con);
  // mjv_updateScene only reads d (it takes a non-const pointer; see the header's note).
  mjv_updateScene(m, const_cast<mjData*>(d), &r.opt, &r.pert, &cam, mjCAT_ALL, &r.scn);
  r.skipped = 0;
  double cam_distance = camera.distance;
  if (camera.mode == "model") {
    cam_distance = 0;
    for (int k = 0; k < 3; ++k) {
      const double c = 0.5 * (r.scn.camera[0].pos[k] + r.scn.camera[1].pos[k]);
      cam_distance += c * c;
    }
    cam_distance = std::sqrt(cam_distance);
  }
  TintVehicleGeoms(m, &r.scn, overlay.vehicle_bodies);
  r.skipped = AddOverlayGeoms(&r.scn, overlay, cam_distance, r.height);
  r.scn.flags[mjRND_SHADOW] = r.shadows ? 1 : 0;

  const mjrRect viewport = {0, 0, r.width, r.height};
  mjr_render(viewport, &r.scn, &r.con);
  DrawOverlayText(viewport, overlay, &r.con);
  mjr_readPixels(r.bottom_up.data(), nullptr, viewport, &r.con);
  const size_t row = static_cast<size_t>(r.width) * 3;
  for (int y = 0; y < r.height; ++y) {
    std::memcpy(r.rgb.data() + row * y, r.bottom_up.data() + row * (r.height - 1 - y), row);
  }
  // Release the context so that the renderer may be used from another thread next time.
  OSMesaMakeCurrent(nullptr, nullptr, GL_UNSIGNED_BYTE, 0, 0);
  return r.rgb;
}

}  // namespace mjf::render
