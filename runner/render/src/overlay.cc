// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "mjformation/render.hpp"

namespace mjf::render {
namespace {

// Well separated colours on the grey floor and the sky: Tableau 10 without red (safety events)
// and with gold for the leader. Beyond these, hues by the golden angle (VehicleColour).
constexpr float kPalette[][3] = {
    {1.00f, 0.78f, 0.05f},  // leader: gold
    {0.12f, 0.47f, 0.95f},  // blue
    {1.00f, 0.45f, 0.00f},  // orange
    {0.17f, 0.70f, 0.17f},  // green
    {0.62f, 0.35f, 0.85f},  // purple
    {0.10f, 0.85f, 0.90f},  // cyan
    {0.95f, 0.40f, 0.80f},  // pink
    {0.55f, 0.34f, 0.20f},  // brown
    {0.60f, 0.75f, 0.10f},  // olive
    {0.98f, 0.98f, 0.98f},  // white
    {0.20f, 0.20f, 0.55f},  // navy
    {0.50f, 0.50f, 0.50f},  // grey
};
constexpr int kPaletteSize = sizeof(kPalette) / sizeof(kPalette[0]);

// HSV (h in turns) to RGB at full value: the generated colours beyond the fixed list.
std::array<float, 4> Hue(double h, double s, double v) {
  h -= std::floor(h);
  const double f = h * 6 - std::floor(h * 6);
  const double p = v * (1 - s), q = v * (1 - f * s), t = v * (1 - (1 - f) * s);
  double r = v, g = t, b = p;
  switch (static_cast<int>(h * 6) % 6) {
    case 1:
      r = q, g = v, b = p;
      break;
    case 2:
      r = p, g = v, b = t;
      break;
    case 3:
      r = p, g = q, b = v;
      break;
    case 4:
      r = t, g = p, b = v;
      break;
    case 5:
      r = v, g = p, b = q;
      break;
    default:
      break;
  }
  return {static_cast<float>(r), static_cast<float>(g), static_cast<float>(b), 1.0f};
}

// The scene's lights (headlight ambient 0.35 + diffuse 0.5, the sun 0.7) add up to about 1.6
// times a geom's colour where it faces them, which clamps a saturated colour towards white or
// its neighbour (blue drawn as cyan, orange as yellow: two followers looked alike). Geoms drawn
// in a palette colour are given this fraction of it, so they look like the legend's swatches.
constexpr float kLitScale = 0.62f;
std::array<float, 4> Lit(const std::array<float, 4>& c, float alpha) {
  return {kLitScale * c[0], kLitScale * c[1], kLitScale * c[2], alpha};
}

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
    g->emission = 0.0f;
    g->specular = 0.1f;
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
    mjv_connector(g, mjGEOM_LINE, pixels, a.data(), b.data());
  }

 private:
  mjvScene* scn_;
  int skipped_ = 0;
};

// Safety events: a red sphere where each happened, with its label beside it (MuJoCo draws the
// label of any scene geom that has one). Marks closer than eight radii (the radius grows with
// the camera distance: about a label's height on screen, a third of its width) to an earlier
// labelled one keep their sphere but not their label, which would be drawn over the other:
// that label says "(+K here)" instead.
void AddEventMarks(GeomAppender* r, const std::vector<EventMark>& events, double radius) {
  std::vector<std::pair<mjvGeom*, int>> labelled;  // geom, marks merged into it
  for (const EventMark& e : events) {
    mjvGeom* g = r->NewGeom(kEventColour.data());
    if (!g) continue;
    for (int k = 0; k < 3; ++k) {
      g->size[k] = static_cast<float>(radius);
      g->pos[k] = static_cast<float>(e.pos[k]);
    }
    g->emission = 0.6f;
    auto near = std::find_if(labelled.begin(), labelled.end(), [&](const auto& l) {
      double d2 = 0;
      for (int k = 0; k < 3; ++k)
        d2 += (l.first->pos[k] - g->pos[k]) * (l.first->pos[k] - g->pos[k]);
      return d2 < 64 * radius * radius;
    });
    if (near != labelled.end()) {
      ++near->second;
      continue;
    }
    std::snprintf(g->label, sizeof(g->label), "%s", e.label.c_str());
    labelled.push_back({g, 0});
  }
  for (const auto& [g, more] : labelled) {
    if (more == 0) continue;
    const std::string text = std::string(g->label) + " (+" + std::to_string(more) + " here)";
    std::snprintf(g->label, sizeof(g->label), "%s", text.c_str());
  }
}

}  // namespace

std::array<float, 4> VehicleColour(int vehicle) {
  if (vehicle >= 0 && vehicle < kPaletteSize) {
    const float* c = kPalette[vehicle];
    return {c[0], c[1], c[2], 1.0f};
  }
  // Golden-angle hues never repeat; saturation and value alternate over three levels so that
  // neighbours in index differ in more than hue. Hues below 0.09 and above 0.88 (red) are not
  // used: red is the events' colour. Distinct from each other up to float rounding (tested to
  // 1000 followers); at that size "told apart" is all a colour can do.
  const int k = std::max(0, vehicle - kPaletteSize);
  const double h = 0.09 + 0.79 * std::fmod(0.1 + k * 0.618033988749895, 1.0);
  return Hue(h, 0.55 + 0.2 * (k % 3), 0.95 - 0.15 * ((k / 3) % 3));
}

std::string VehicleName(int vehicle) {
  return vehicle == 0 ? std::string("leader") : "follower " + std::to_string(vehicle);
}

int TintVehicleGeoms(const mjModel* m, mjvScene* scn, const std::vector<int>& vehicle_bodies) {
  if (!m || vehicle_bodies.empty()) return 0;
  // owner[body]: the vehicle whose subtree holds it; bodies are in depth-first order, so a
  // parent's owner is known before its children's.
  std::vector<int> owner(m->nbody, -1);
  for (size_t v = 0; v < vehicle_bodies.size(); ++v) {
    const int b = vehicle_bodies[v];
    if (b >= 0 && b < m->nbody) owner[b] = static_cast<int>(v);
  }
  for (int b = 1; b < m->nbody; ++b) {
    if (owner[b] < 0) owner[b] = owner[m->body_parentid[b]];
  }
  int tinted = 0;
  for (int k = 0; k < scn->ngeom; ++k) {
    mjvGeom& g = scn->geoms[k];
    if (g.objtype != mjOBJ_GEOM || g.objid < 0 || g.objid >= m->ngeom) continue;
    const int v = owner[m->geom_bodyid[g.objid]];
    if (v < 0 || g.rgba[3] <= 0) continue;
    const std::array<float, 4> c = Lit(VehicleColour(v), g.rgba[3]);
    for (int a = 0; a < 3; ++a) g.rgba[a] = c[a];
    g.texid = -1;  // a textured mesh would otherwise modulate the colour
    g.emission = v == 0 ? 0.3f : 0.1f;
    ++tinted;
  }
  return tinted;
}

int AddOverlayGeoms(mjvScene* scene, const Overlay& o, double cam_distance, int height) {
  GeomAppender r(scene);
  // Lines a few pixels wide whatever the image size; slot markers scale with the distance so
  // that they stay visible from far away.
  const double line_px = std::max(2.0, height / 280.0);
  const double sphere = std::max(0.1, 0.006 * cam_distance);
  for (size_t i = 0; i < o.trails.size(); ++i) {
    const std::array<float, 4> colour = Lit(VehicleColour(static_cast<int>(i)), 1.0f);
    const float* rgba = colour.data();
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
    const std::array<float, 4> base = Lit(VehicleColour(static_cast<int>(i)), 0.6f);
    const float* rgba = base.data();
    // The leader's disc is larger and ringed by a white halo, so it is found at a glance.
    const double radius = i == 0 ? 1.7 * disc : disc;
    for (int halo = i == 0 ? 1 : 0; halo >= 0; --halo) {
      const float white[4] = {1.0f, 1.0f, 1.0f, 0.35f};
      mjvGeom* g = r.NewGeom(halo ? white : rgba);
      if (!g) continue;
      g->type = mjGEOM_CYLINDER;
      g->size[0] = g->size[1] = static_cast<float>(halo ? 1.35 * radius : radius);
      g->size[2] = halo ? 0.01f : 0.02f;
      for (int k = 0; k < 3; ++k) g->pos[k] = static_cast<float>(o.markers[i][k]);
      g->pos[2] -= halo ? 0.17f : 0.15f;  // just under the rotors, the halo under the disc
    }
  }
  AddEventMarks(&r, o.events, 2.0 * sphere);  // larger than a slot: seen first
  const float ring_rgba[4] = {1.0f, 1.0f, 1.0f, 0.7f};
  for (size_t k = 1; k < o.ring_points.size(); ++k) {
    r.Line(o.ring_points[k - 1], o.ring_points[k], std::max(1.0, 0.75 * line_px), ring_rgba);
  }
  return r.skipped();
}

mjrRect DrawLegend(const mjrRect& viewport, int n, const mjrContext* con) {
  if (n <= 0) return {0, 0, 0, 0};
  const int shown = std::min(n, kLegendRows);
  std::vector<std::string> names;
  for (int i = 0; i < shown; ++i) names.push_back(VehicleName(i));
  if (n > shown) names.push_back("... and " + std::to_string(n - shown) + " more");
  int text_w = 0;
  for (const auto& s : names) {
    int w = 0;
    for (unsigned char c : s) w += c < 127 ? con->charWidth[c] : 0;
    text_w = std::max(text_w, w);
  }
  const int pad = std::max(4, con->charHeight / 4);
  const int row = con->charHeight + pad;
  const int swatch = con->charHeight;
  const int w = pad + swatch + pad + text_w + 2 * pad;
  const int h = static_cast<int>(names.size()) * row + pad;
  const mjrRect box = {viewport.left + viewport.width - w - pad,
                       viewport.bottom + viewport.height - h - pad, w, h};
  mjr_rectangle(box, 0.1f, 0.1f, 0.12f, 0.75f);
  for (size_t i = 0; i < names.size(); ++i) {
    const int top = box.bottom + box.height - pad - static_cast<int>(i + 1) * row + pad;
    const mjrRect text = {box.left + pad + swatch + pad, top, text_w + pad, row - pad};
    if (static_cast<int>(i) < shown) {
      const std::array<float, 4> c = VehicleColour(static_cast<int>(i));
      mjr_rectangle({box.left + pad, top, swatch, row - pad}, c[0], c[1], c[2], 1.0f);
    }
    // Left-aligned text: mjr_label centres it, so the label is as wide as the text itself.
    int tw = 0;
    for (unsigned char ch : names[i]) tw += ch < 127 ? con->charWidth[ch] : 0;
    mjr_label({text.left, text.bottom, tw + 2, text.height}, mjFONT_NORMAL, names[i].c_str(), 0.1f,
              0.1f, 0.12f, 0.0f, 1.0f, 1.0f, 1.0f, con);
  }
  return box;
}

void DrawOverlayText(const mjrRect& viewport, const Overlay& overlay, const mjrContext* con) {
  DrawLegend(viewport, overlay.legend_vehicles, con);
  if (!overlay.label.empty()) {
    mjr_overlay(mjFONT_NORMAL, mjGRID_TOPLEFT, viewport, overlay.label.c_str(), nullptr, con);
  }
}

}  // namespace mjf::render
