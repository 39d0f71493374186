// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include <algorithm>
#include <array>

#include "mjformation/render.hpp"

namespace mjf::render {
namespace {

// Trail colours when Overlay::trail_rgba does not give one: the leader first.
constexpr float kPalette[][4] = {
    {1.00f, 0.75f, 0.10f, 1}, {0.15f, 0.55f, 1.00f, 1}, {0.20f, 0.85f, 0.35f, 1},
    {0.85f, 0.30f, 0.90f, 1}, {0.10f, 0.90f, 0.90f, 1}, {1.00f, 0.45f, 0.20f, 1},
    {0.60f, 0.60f, 1.00f, 1}, {0.95f, 0.95f, 0.95f, 1},
};
constexpr int kPaletteSize = sizeof(kPalette) / sizeof(kPalette[0]);

class GeomAppender {
 public:
  explicit GeomAppender(mjvScene* scn) : scn_(scn) {}
  int skipped() const { return skipped_; }

  // A decor geom appended to the scene; nullptr when the scene is full.
  mjvGeom* NewGeom(const float rgba[4]) {
    if (scn_->ngeom >= scn_->maxgeom) {
      ++skipped_;
      return nullptr;
    }
    mjvGeom* g = scn_->geoms + scn_->ngeom;
    mjv_initGeom(g, mjGEOM_SPHERE, nullptr, nullptr, nullptr, rgba);
    g->objtype = mjOBJ_UNKNOWN;
    g->objid = -1;
    g->category = mjCAT_DECOR;
    g->segid = scn_->ngeom;
    g->emission = 0.3f;
    g->specular = 0.2f;
    g->transparent = rgba[3] < 1.0f;
    ++scn_->ngeom;
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

 private:
  mjvScene* scn_;
  int skipped_ = 0;
};

}  // namespace

int AddOverlayGeoms(mjvScene* scene, const Overlay& o, double cam_distance, int height) {
  GeomAppender r(scene);
  // Lines a few pixels wide whatever the image size; slot markers scale with the distance so
  // that they stay visible from far away.
  const double line_px = std::max(2.0, height / 280.0);
  const double sphere = std::max(0.1, 0.006 * cam_distance);
  for (size_t i = 0; i < o.trails.size(); ++i) {
    const float* rgba =
        i < o.trail_rgba.size() ? o.trail_rgba[i].data() : kPalette[i % kPaletteSize];
    const auto& t = o.trails[i];
    for (size_t k = 1; k < t.size(); ++k) r.Line(t[k - 1], t[k], line_px, rgba);
  }
  const float slot_rgba[4] = {0.2f, 1.0f, 0.3f, 0.45f};
  for (const auto& p : o.slots) {
    mjvGeom* g = r.NewGeom(slot_rgba);
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
    mjvGeom* g = r.NewGeom(rgba);
    if (!g) continue;
    g->type = mjGEOM_CYLINDER;
    g->size[0] = g->size[1] = static_cast<float>(disc);
    g->size[2] = 0.02f;
    for (int k = 0; k < 3; ++k) g->pos[k] = static_cast<float>(o.markers[i][k]);
    g->pos[2] -= 0.15f;  // just under the rotors
  }
  const float ring_rgba[4] = {1.0f, 1.0f, 1.0f, 0.7f};
  for (size_t k = 1; k < o.ring_points.size(); ++k) {
    r.Line(o.ring_points[k - 1], o.ring_points[k], std::max(1.0, 0.75 * line_px), ring_rgba);
  }
  return r.skipped();
}

}  // namespace mjf::render
