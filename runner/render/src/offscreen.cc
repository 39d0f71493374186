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

// Trail colours when Overlay::trail_rgba does not give one: the leader first.
constexpr float kPalette[][4] = {
    {1.00f, 0.75f, 0.10f, 1}, {0.15f, 0.55f, 1.00f, 1}, {0.20f, 0.85f, 0.35f, 1},
    {0.85f, 0.30f, 0.90f, 1}, {0.10f, 0.90f, 0.90f, 1}, {1.00f, 0.45f, 0.20f, 1},
    {0.60f, 0.60f, 1.00f, 1}, {0.95f, 0.95f, 0.95f, 1},
};
constexpr int kPaletteSize = sizeof(kPalette) / sizeof(kPalette[0]);
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

  // A decor geom appended to the scene; nullptr when the scene is full.
  mjvGeom* NewGeom(const float rgba[4]) {
    if (scn.ngeom >= scn.maxgeom) {
      ++skipped;
      return nullptr;
    }
    mjvGeom* g = scn.geoms + scn.ngeom;
    mjv_initGeom(g, mjGEOM_SPHERE, nullptr, nullptr, nullptr, rgba);
    g->objtype = mjOBJ_UNKNOWN;
    g->objid = -1;
    g->category = mjCAT_DECOR;
    g->segid = scn.ngeom;
    g->emission = 0.3f;
    g->specular = 0.2f;
    g->transparent = rgba[3] < 1.0f;
    ++scn.ngeom;
    return g;
  }

  // A line segment of `pixels` width: GL lines cost almost nothing in llvmpipe, whereas capsules
  // (hundreds of triangles each, drawn twice with shadows) made a 7-vehicle trail overlay cost
  // several hundred ms per frame.
  void Line(const std::array<double, 3>& a, const std::array<double, 3>& b, double pixels,
            const float rgba[4]) {
    if (a == b) return;
    mjvGeom* g = NewGeom(rgba);
    if (!g) return;
    mjv_makeConnector(g, mjGEOM_LINE, pixels, a[0], a[1], a[2], b[0], b[1], b[2]);
  }

  void AddOverlay(const Overlay& o, double cam_distance) {
    // Lines a few pixels wide whatever the image size; slot markers scale with the distance so
    // that they stay visible from far away.
    const double line_px = std::max(2.0, height / 280.0);
    const double sphere = std::max(0.1, 0.006 * cam_distance);
    for (size_t i = 0; i < o.trails.size(); ++i) {
      const float* rgba =
          i < o.trail_rgba.size() ? o.trail_rgba[i].data() : kPalette[i % kPaletteSize];
      const auto& t = o.trails[i];
      for (size_t k = 1; k < t.size(); ++k) Line(t[k - 1], t[k], line_px, rgba);
    }
    const float slot_rgba[4] = {0.2f, 1.0f, 0.3f, 0.45f};
    for (const auto& p : o.slots) {
      mjvGeom* g = NewGeom(slot_rgba);
      if (!g) continue;
      for (int k = 0; k < 3; ++k) {
        g->size[k] = static_cast<float>(sphere);
        g->pos[k] = static_cast<float>(p[k]);
      }
    }
    const double disc = std::max(0.3, 0.012 * cam_distance);
    for (size_t i = 0; i < o.markers.size(); ++i) {
      const float* base =
          i < o.trail_rgba.size() ? o.trail_rgba[i].data() : kPalette[i % kPaletteSize];
      const float rgba[4] = {base[0], base[1], base[2], 0.55f};
      mjvGeom* g = NewGeom(rgba);
      if (!g) continue;
      g->type = mjGEOM_CYLINDER;
      g->size[0] = g->size[1] = static_cast<float>(disc);
      g->size[2] = 0.02f;
      for (int k = 0; k < 3; ++k) g->pos[k] = static_cast<float>(o.markers[i][k]);
      g->pos[2] -= 0.15f;  // just under the rotors
    }
    const float ring_rgba[4] = {1.0f, 1.0f, 1.0f, 0.7f};
    for (size_t k = 1; k < o.ring_points.size(); ++k) {
      Line(o.ring_points[k - 1], o.ring_points[k], std::max(1.0, 0.75 * line_px), ring_rgba);
    }
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
  r.AddOverlay(overlay, cam_distance);
  r.scn.flags[mjRND_SHADOW] = r.shadows ? 1 : 0;

  const mjrRect viewport = {0, 0, r.width, r.height};
  mjr_render(viewport, &r.scn, &r.con);
  if (!overlay.label.empty()) {
    mjr_overlay(mjFONT_NORMAL, mjGRID_TOPLEFT, viewport, overlay.label.c_str(), nullptr, &r.con);
  }
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
