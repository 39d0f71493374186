// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/render.hpp"

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>
#include <png.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace mjf::render {
namespace {

// A checker floor, a light, two red boxes: box A at the origin, box B 3 m along +x.
constexpr char kSceneXml[] = R"(
<mujoco model="render_test">
  <visual>
    <global offwidth="1280" offheight="720"/>
    <quality shadowsize="2048"/>
  </visual>
  <asset>
    <texture name="checker" type="2d" builtin="checker" rgb1="0.2 0.3 0.4" rgb2="0.8 0.8 0.8"
             width="256" height="256"/>
    <material name="floor" texture="checker" texrepeat="8 8"/>
    <material name="red" rgba="0.9 0.05 0.05 1"/>
  </asset>
  <worldbody>
    <light pos="0 0 10" dir="0 0 -1" directional="true" castshadow="true"/>
    <geom name="floor" type="plane" size="20 20 0.1" material="floor"/>
    <body name="a" pos="0 0 0.5">
      <freejoint/>
      <geom type="box" size="0.5 0.5 0.5" material="red"/>
    </body>
    <body name="b" pos="3 0 0.5">
      <geom type="box" size="0.5 0.5 0.5" material="red"/>
    </body>
    <camera name="top" pos="0 0 12" xyaxes="1 0 0 0 1 0"/>
  </worldbody>
</mujoco>
)";

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
using ModelPtr = std::unique_ptr<mjModel, ModelDeleter>;
using DataPtr = std::unique_ptr<mjData, DataDeleter>;

std::string TempPath(const std::string& name) {
  return "/tmp/mjf_render_test_" + std::to_string(::getpid()) + "_" + name;
}

ModelPtr LoadModel(const std::string& xml = kSceneXml) {
  const std::string path = TempPath("scene.xml");
  std::ofstream(path) << xml;
  char error[1000] = "";
  ModelPtr m(mj_loadXML(path.c_str(), nullptr, error, sizeof(error)));
  std::remove(path.c_str());
  if (!m) throw std::runtime_error(std::string("mj_loadXML: ") + error);
  return m;
}

DataPtr MakeData(const mjModel* m) {
  DataPtr d(mj_makeData(m));
  mj_forward(m, d.get());
  return d;
}

const double kBoxA[3] = {0, 0, 0.5};

CameraSpec FollowCamera() {
  CameraSpec cam;
  cam.mode = "follow";
  cam.distance = 8;
  cam.azimuth = 90;
  cam.elevation = -35;
  return cam;
}

// Lit or shaded faces of the red boxes; neither the grey/blue floor nor the overlay colours.
bool IsRed(const unsigned char* p) { return p[0] > 60 && p[0] > 1.8 * p[1] && p[0] > 1.8 * p[2]; }

// Red pixels in the rectangle [x0, x1) x [y0, y1) of a top-down RGB image.
int RedPixels(const std::vector<unsigned char>& rgb, int w, int x0, int x1, int y0, int y1) {
  int n = 0;
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) n += IsRed(&rgb[3 * (static_cast<size_t>(y) * w + x)]);
  }
  return n;
}

double Variance(const std::vector<unsigned char>& rgb) {
  double sum = 0, sum2 = 0;
  for (unsigned char v : rgb) {
    sum += v;
    sum2 += static_cast<double>(v) * v;
  }
  const double n = static_cast<double>(rgb.size());
  return sum2 / n - (sum / n) * (sum / n);
}

int DifferentPixels(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b) {
  int n = 0;
  for (size_t i = 0; i + 2 < a.size(); i += 3) {
    n += a[i] != b[i] || a[i + 1] != b[i + 1] || a[i + 2] != b[i + 2];
  }
  return n;
}

Overlay SampleOverlay() {
  Overlay o;
  // A spiral trail around box A and a straight one towards box B, two slots, a ring.
  std::vector<std::array<double, 3>> spiral, line;
  for (int k = 0; k <= 120; ++k) {
    const double a = 0.1 * k, r = 1.2 + 0.01 * k;
    spiral.push_back({r * std::cos(a), r * std::sin(a), 1.5});
    line.push_back({-3 + 0.05 * k, -2.0, 0.8});
  }
  o.trails = {spiral, line};
  o.slots = {{-2, 1, 1.5}, {2, 1.5, 1.5}};
  for (int k = 0; k <= 64; ++k) {
    const double a = 2 * M_PI * k / 64;
    o.ring_points.push_back({2.5 * std::cos(a), 2.5 * std::sin(a), 1.5});
  }
  o.label = "t = 10.0 s";
  return o;
}

TEST(OffscreenRenderer, RendersFloorAndRedBoxesWhereExpected) {
  auto m = LoadModel();
  auto d = MakeData(m.get());
  const int w = 640, h = 480;
  OffscreenRenderer renderer(m.get(), w, h);
  EXPECT_EQ(renderer.width(), w);
  EXPECT_EQ(renderer.height(), h);
  const auto& rgb = renderer.Render(d.get(), FollowCamera(), Overlay{}, kBoxA);
  ASSERT_EQ(rgb.size(), static_cast<size_t>(w) * h * 3);
  EXPECT_GT(Variance(rgb), 200.0) << "blank image";

  // Box A fills the centre; box B is to its right (+x is screen right at azimuth 90), and
  // nothing red is in the left third or the top rows (sky).
  const int centre = RedPixels(rgb, w, w / 2 - 20, w / 2 + 20, h / 2 - 20, h / 2 + 20);
  EXPECT_GT(centre, 1400) << "box A should fill the centre";
  const int right = RedPixels(rgb, w, 2 * w / 3, w, 0, h);
  EXPECT_GT(right, 1000) << "box B should appear on the right";
  EXPECT_EQ(RedPixels(rgb, w, 0, w / 4, 0, h), 0);
  EXPECT_EQ(RedPixels(rgb, w, 0, w, 0, 10), 0);
  WritePng("/tmp/mjf_render_plain.png", rgb.data(), w, h);

  // Follow: move the target onto box B and box B fills the centre.
  const double box_b[3] = {3, 0, 0.5};
  const auto& rgb_b = renderer.Render(d.get(), FollowCamera(), Overlay{}, box_b);
  EXPECT_GT(RedPixels(rgb_b, w, w / 2 - 20, w / 2 + 20, h / 2 - 20, h / 2 + 20), 1400);
  EXPECT_GT(RedPixels(rgb_b, w, 0, w / 3, 0, h), 1000) << "box A should now be on the left";
}

TEST(OffscreenRenderer, FixedAndModelCameras) {
  auto m = LoadModel();
  auto d = MakeData(m.get());
  const int w = 320, h = 240;
  OffscreenRenderer renderer(m.get(), w, h, false);
  CameraSpec fixed = FollowCamera();
  fixed.mode = "fixed";
  fixed.lookat[0] = 3;
  fixed.lookat[2] = 0.5;
  // The target is ignored in fixed mode: box B (at lookat) is in the centre.
  const auto& a = renderer.Render(d.get(), fixed, Overlay{}, kBoxA);
  EXPECT_GT(RedPixels(a, w, w / 2 - 10, w / 2 + 10, h / 2 - 10, h / 2 + 10), 350);
  EXPECT_GT(RedPixels(a, w, 0, w / 3, 0, h), 100);

  CameraSpec top;
  top.mode = "model";
  top.model_camera = "top";
  const auto& b = renderer.Render(d.get(), top, Overlay{}, nullptr);
  WritePng("/tmp/mjf_render_top.png", b.data(), w, h);
  EXPECT_GT(RedPixels(b, w, w / 2 - 10, w / 2 + 10, h / 2 - 10, h / 2 + 10), 350);

  top.model_camera = "nope";
  try {
    renderer.Render(d.get(), top, Overlay{});
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("nope"), std::string::npos) << e.what();
  }
  CameraSpec bad;
  bad.mode = "orbit";
  EXPECT_THROW(renderer.Render(d.get(), bad, Overlay{}), std::runtime_error);
}

TEST(OffscreenRenderer, OverlaysChangePixels) {
  auto m = LoadModel();
  auto d = MakeData(m.get());
  const int w = 1280, h = 720;
  OffscreenRenderer renderer(m.get(), w, h);
  const std::vector<unsigned char> plain = renderer.Render(d.get(), FollowCamera(), {}, kBoxA);

  Overlay trails_only;
  trails_only.trails = SampleOverlay().trails;
  const std::vector<unsigned char> with_trails =
      renderer.Render(d.get(), FollowCamera(), trails_only, kBoxA);
  EXPECT_GT(DifferentPixels(plain, with_trails), 5000);

  Overlay slots_only;
  slots_only.slots = SampleOverlay().slots;
  const std::vector<unsigned char> with_slots =
      renderer.Render(d.get(), FollowCamera(), slots_only, kBoxA);
  // Two slot spheres about 20 px across (some 300 px each); MuJoCo 2.2.2 also drew their shadows
  // on the floor (over 1000 px in all), MuJoCo 4's renderer draws 737 px.
  EXPECT_GT(DifferentPixels(plain, with_slots), 500);

  Overlay label_only;
  label_only.label = "t = 10.0 s";
  const std::vector<unsigned char> with_label =
      renderer.Render(d.get(), FollowCamera(), label_only, kBoxA);
  const int label_diff = DifferentPixels(plain, with_label);
  EXPECT_GT(label_diff, 200);

  const std::vector<unsigned char> all =
      renderer.Render(d.get(), FollowCamera(), SampleOverlay(), kBoxA);
  EXPECT_EQ(renderer.skipped_overlay_geoms(), 0);
  WritePng("/tmp/mjf_render_sample.png", all.data(), w, h);

  // Rendering without the overlay again gives the plain image back (no state left behind).
  const auto& again = renderer.Render(d.get(), FollowCamera(), {}, kBoxA);
  EXPECT_EQ(again, plain);
}

// Four vehicles as the runner composes them: a root body with geoms and a child body (a rotor)
// of its own, plus an invisible collision hull (alpha 0) on vehicle 1; all dark grey like the
// stock quadrotor, so that nothing tells them apart before the render-time colouring.
constexpr char kVehiclesXml[] = R"(
<mujoco model="vehicles">
  <visual><global offwidth="640" offheight="480"/></visual>
  <worldbody>
    <light pos="0 0 10" dir="0 0 -1" directional="true"/>
    <geom name="floor" type="plane" size="20 20 0.1" rgba="0.5 0.5 0.5 1"/>
    <body name="uav0_vehicle" pos="0 0 1"><freejoint/>
      <geom type="box" size="0.3 0.3 0.05" rgba="0.15 0.15 0.17 1"/>
      <body name="uav0_rotor" pos="0.3 0 0.05"><geom type="cylinder" size="0.1 0.01" rgba="0.9 0.15 0.1 0.75"/></body>
    </body>
    <body name="uav1_vehicle" pos="2 0 1"><freejoint/>
      <geom type="box" size="0.3 0.3 0.05" rgba="0.15 0.15 0.17 1"/>
      <geom type="box" size="0.3 0.3 0.05" rgba="0 0 0 0"/>
      <body name="uav1_rotor" pos="0.3 0 0.05"><geom type="cylinder" size="0.1 0.01" rgba="0.9 0.15 0.1 0.75"/></body>
    </body>
    <body name="uav2_vehicle" pos="-2 0 1"><freejoint/>
      <geom type="box" size="0.3 0.3 0.05" rgba="0.15 0.15 0.17 1"/>
    </body>
    <body name="uav3_vehicle" pos="0 2 1"><freejoint/>
      <geom type="box" size="0.3 0.3 0.05" rgba="0.15 0.15 0.17 1"/>
    </body>
  </worldbody>
</mujoco>
)";

std::vector<int> VehicleBodyIds(const mjModel* m) {
  std::vector<int> ids;
  for (int i = 0; i < 4; ++i) {
    ids.push_back(mj_name2id(m, mjOBJ_BODY, ("uav" + std::to_string(i) + "_vehicle").c_str()));
  }
  return ids;
}

// The vehicle (index into bodies) owning scene geom g, or -1.
int OwnerOf(const mjModel* m, const mjvGeom& g, const std::vector<int>& bodies) {
  if (g.objtype != mjOBJ_GEOM) return -1;
  for (int b = m->geom_bodyid[g.objid]; b > 0; b = m->body_parentid[b]) {
    for (size_t v = 0; v < bodies.size(); ++v) {
      if (bodies[v] == b) return static_cast<int>(v);
    }
  }
  return -1;
}

TEST(VehicleColours, EveryVehicleItsOwnColourInTheSceneGeomsLeaderDistinct) {
  auto m = LoadModel(kVehiclesXml);
  auto d = MakeData(m.get());
  mjvScene scn;
  mjvOption opt;
  mjvCamera cam;
  mjvPerturb pert;
  mjv_defaultScene(&scn);
  mjv_defaultOption(&opt);
  mjv_defaultCamera(&cam);
  mjv_defaultPerturb(&pert);
  mjv_makeScene(m.get(), &scn, 1000);
  mjv_updateScene(m.get(), d.get(), &opt, &pert, &cam, mjCAT_ALL, &scn);
  const std::vector<int> bodies = VehicleBodyIds(m.get());
  // Before: all vehicles' hulls share one colour (the control: the test can fail).
  std::vector<std::array<float, 3>> before;
  for (int k = 0; k < scn.ngeom; ++k) {
    if (OwnerOf(m.get(), scn.geoms[k], bodies) >= 0 && scn.geoms[k].rgba[3] == 1.0f) {
      before.push_back({scn.geoms[k].rgba[0], scn.geoms[k].rgba[1], scn.geoms[k].rgba[2]});
    }
  }
  ASSERT_EQ(before.size(), 4u);
  EXPECT_EQ(before[0], before[1]);

  const int tinted = TintVehicleGeoms(m.get(), &scn, bodies);
  // Per vehicle, the one colour all its visible geoms (rotors in child bodies included) got.
  std::vector<std::vector<std::array<float, 3>>> seen(4);
  int floor_geoms = 0, invisible = 0;
  for (int k = 0; k < scn.ngeom; ++k) {
    const mjvGeom& g = scn.geoms[k];
    const int v = OwnerOf(m.get(), g, bodies);
    if (v < 0) {
      floor_geoms += g.objtype == mjOBJ_GEOM;
      EXPECT_FLOAT_EQ(g.rgba[0], 0.5f) << "a geom outside the vehicles was recoloured";
      continue;
    }
    if (g.rgba[3] == 0.0f) {
      ++invisible;  // the collision hull stays invisible
      continue;
    }
    seen[v].push_back({g.rgba[0], g.rgba[1], g.rgba[2]});
  }
  EXPECT_EQ(floor_geoms, 1);
  // MuJoCo leaves alpha-0 geoms out of the scene; any that is there stayed invisible above.
  EXPECT_LE(invisible, 1);
  EXPECT_EQ(tinted, 6);  // 4 hulls + 2 rotors
  for (int v = 0; v < 4; ++v) {
    ASSERT_FALSE(seen[v].empty()) << v;
    for (const auto& c : seen[v]) EXPECT_EQ(c, seen[v][0]) << "vehicle " << v << " has two colours";
  }
  for (int a = 0; a < 4; ++a) {
    for (int b = a + 1; b < 4; ++b) {
      float diff = 0;
      for (int k = 0; k < 3; ++k) diff = std::max(diff, std::fabs(seen[a][0][k] - seen[b][0][k]));
      EXPECT_GT(diff, 0.1f) << "vehicles " << a << " and " << b << " look alike";
    }
  }
  // The leader stands out: farther from every follower than the followers need to be from
  // each other, and drawn brighter (emission).
  for (int v = 1; v < 4; ++v) {
    float diff = 0;
    for (int k = 0; k < 3; ++k) diff += std::fabs(seen[0][0][k] - seen[v][0][k]);
    EXPECT_GT(diff, 0.18f) << "the leader looks like follower " << v;
  }
  float leader_emission = -1, follower_emission = -1;
  for (int k = 0; k < scn.ngeom; ++k) {
    const int v = OwnerOf(m.get(), scn.geoms[k], bodies);
    if (v == 0) leader_emission = scn.geoms[k].emission;
    if (v > 0) follower_emission = std::max(follower_emission, scn.geoms[k].emission);
  }
  EXPECT_GT(leader_emission, follower_emission);
  // Same hue as the palette (the geoms get a fixed fraction of it, for the scene's lights).
  for (int v = 0; v < 4; ++v) {
    const auto c = VehicleColour(v);
    const float s = seen[v][0][0] / c[0];
    for (int k = 1; k < 3; ++k) EXPECT_NEAR(seen[v][0][k], s * c[k], 1e-4) << v;
  }
  mjv_freeScene(&scn);
}

TEST(VehicleColours, PaletteDistinctForLargeSwarmsAndNeverTheEventRed) {
  std::vector<std::array<float, 4>> colours;
  for (int i = 0; i < 1001; ++i) colours.push_back(VehicleColour(i));
  for (size_t a = 0; a < colours.size(); ++a) {
    // Not the events' red (a red-dominant colour with little green and blue).
    const auto& c = colours[a];
    EXPECT_FALSE(c[0] > 0.8f && c[1] < 0.3f && c[2] < 0.3f) << "vehicle " << a << " is red";
    for (size_t b = a + 1; b < colours.size(); ++b) {
      EXPECT_NE(colours[a], colours[b]) << a << " and " << b;
    }
  }
  // The fixed part (leader + 11 followers) is well separated, not only different.
  for (int a = 0; a < 12; ++a) {
    for (int b = a + 1; b < 12; ++b) {
      float diff = 0;
      for (int k = 0; k < 3; ++k) diff += std::fabs(colours[a][k] - colours[b][k]);
      EXPECT_GT(diff, 0.3f) << a << " and " << b;
    }
  }
  EXPECT_EQ(VehicleName(0), "leader");
  EXPECT_EQ(VehicleName(3), "follower 3");
}

// The legend: in the top-right corner, a swatch of each vehicle's exact palette colour; without
// it (legend_vehicles = 0) the corner shows none of them.
TEST(VehicleColours, LegendSwatchesInTheTopRightCorner) {
  auto m = LoadModel();
  auto d = MakeData(m.get());
  const int w = 1280, h = 720;
  OffscreenRenderer renderer(m.get(), w, h, false);
  Overlay o;
  const std::vector<unsigned char> plain = renderer.Render(d.get(), FollowCamera(), o, kBoxA);
  o.legend_vehicles = 7;
  const std::vector<unsigned char> legend = renderer.Render(d.get(), FollowCamera(), o, kBoxA);
  WritePng("/tmp/mjf_render_legend.png", legend.data(), w, h);
  auto swatch_pixels = [&](const std::vector<unsigned char>& rgb, int vehicle) {
    const auto c = VehicleColour(vehicle);
    int n = 0;
    for (int y = 0; y < h / 2; ++y) {
      for (int x = w - 400; x < w; ++x) {
        const unsigned char* p = &rgb[3 * (static_cast<size_t>(y) * w + x)];
        bool match = true;
        for (int k = 0; k < 3; ++k) match = match && std::abs(p[k] - std::lround(255 * c[k])) <= 2;
        n += match;
      }
    }
    return n;
  };
  for (int v = 0; v < 7; ++v) {
    EXPECT_GT(swatch_pixels(legend, v), 100) << "no swatch for " << VehicleName(v);
    EXPECT_LT(swatch_pixels(plain, v), 10) << VehicleName(v);
  }
  // The rest of the picture is as before: the legend is only in its corner.
  int outside = 0;
  for (int y = h / 2; y < h; ++y) {
    for (int x = 0; x < w - 400; ++x) {
      const size_t i = 3 * (static_cast<size_t>(y) * w + x);
      outside += plain[i] != legend[i] || plain[i + 1] != legend[i + 1];
    }
  }
  EXPECT_EQ(outside, 0);
  // A large swarm: at most kLegendRows rows and a "... and K more" line, still in the corner.
  o.legend_vehicles = 1001;
  renderer.Render(d.get(), FollowCamera(), o, kBoxA);
}

// A safety event mark is red where the event happened; without marks, that place is not red.
TEST(VehicleColours, EventMarkIsRedAtItsPlace) {
  auto m = LoadModel();
  auto d = MakeData(m.get());
  const int w = 640, h = 480;
  OffscreenRenderer renderer(m.get(), w, h, false);
  CameraSpec top;
  top.mode = "model";
  top.model_camera = "top";
  Overlay o;
  const double x = -4, y = -3;  // beside the boxes, on the floor
  const auto plain = renderer.Render(d.get(), top, o, nullptr);
  o.events.push_back({{x, y, 0.3}, "F2 flip 3.00 s"});
  const auto marked = renderer.Render(d.get(), top, o, nullptr);
  auto pure_red = [&](const std::vector<unsigned char>& rgb) {
    int n = 0;
    for (size_t i = 0; i + 2 < rgb.size(); i += 3)
      n += rgb[i] > 180 && rgb[i + 1] < 60 && rgb[i + 2] < 60;
    return n;
  };
  EXPECT_GT(pure_red(marked), pure_red(plain) + 30);
}

TEST(OffscreenRenderer, OverlayBeyondCapacityIsSkippedNotACrash) {
  auto m = LoadModel();
  auto d = MakeData(m.get());
  OffscreenRenderer renderer(m.get(), 160, 120, false);
  Overlay o;
  o.trails.emplace_back();
  for (int k = 0; k < 30000; ++k) o.trails[0].push_back({0.001 * k, 0, 1});
  o.slots.assign(100, {0, 0, 2});
  renderer.Render(d.get(), FollowCamera(), o, kBoxA);
  EXPECT_GT(renderer.skipped_overlay_geoms(), 10000);
}

TEST(OffscreenRenderer, DeterministicAcrossRendersRenderersAndThreads) {
  auto m = LoadModel();
  auto d = MakeData(m.get());
  // Move box A so that the state is not the initial one.
  d->qpos[0] = 0.3;
  d->qpos[3] = std::cos(0.2);
  d->qpos[6] = std::sin(0.2);
  mj_forward(m.get(), d.get());
  const int w = 640, h = 480;
  const Overlay overlay = SampleOverlay();
  std::vector<unsigned char> solo;
  {
    OffscreenRenderer r(m.get(), w, h);
    solo = r.Render(d.get(), FollowCamera(), overlay, kBoxA);
    EXPECT_EQ(r.Render(d.get(), FollowCamera(), overlay, kBoxA), solo) << "same renderer twice";
  }
  // Two renderers interleaved on one thread: each Render makes its own context current.
  {
    OffscreenRenderer r1(m.get(), w, h), r2(m.get(), 320, 240, false);
    r2.Render(d.get(), FollowCamera(), overlay, kBoxA);
    EXPECT_EQ(r1.Render(d.get(), FollowCamera(), overlay, kBoxA), solo);
    r2.Render(d.get(), FollowCamera(), overlay, kBoxA);
    EXPECT_EQ(r1.Render(d.get(), FollowCamera(), overlay, kBoxA), solo);
  }
  // Two threads, each with its own renderer (created in the thread) and its own copy of the
  // state, render at the same time.
  std::vector<std::vector<unsigned char>> results(2);
  std::vector<std::string> errors(2);
  std::vector<std::thread> threads;
  for (int t = 0; t < 2; ++t) {
    threads.emplace_back([&, t] {
      try {
        DataPtr copy(mj_copyData(nullptr, m.get(), d.get()));
        OffscreenRenderer r(m.get(), w, h);
        for (int k = 0; k < 3; ++k) {
          results[t] = r.Render(copy.get(), FollowCamera(), overlay, kBoxA);
          if (results[t] != solo) errors[t] = "frame " + std::to_string(k) + " differs";
        }
      } catch (const std::exception& e) {
        errors[t] = e.what();
      }
    });
  }
  for (auto& th : threads) th.join();
  for (int t = 0; t < 2; ++t) {
    EXPECT_EQ(errors[t], "") << "thread " << t;
    EXPECT_EQ(results[t], solo) << "thread " << t;
  }
}

TEST(OffscreenRenderer, RendererCreatedInOneThreadUsedInAnother) {
  auto m = LoadModel();
  auto d = MakeData(m.get());
  OffscreenRenderer r(m.get(), 320, 240);
  const std::vector<unsigned char> here = r.Render(d.get(), FollowCamera(), {}, kBoxA);
  std::vector<unsigned char> there;
  std::thread([&] { there = r.Render(d.get(), FollowCamera(), {}, kBoxA); }).join();
  EXPECT_EQ(here, there);
}

TEST(OffscreenRenderer, SizeLargerThanOffscreenBufferThrows) {
  auto m = LoadModel();
  try {
    OffscreenRenderer r(m.get(), 1920, 720);
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("1920x720"), std::string::npos) << what;
    EXPECT_NE(what.find("1280x720"), std::string::npos) << what;
    EXPECT_NE(what.find("offwidth"), std::string::npos) << what;
  }
  EXPECT_THROW(OffscreenRenderer(m.get(), 640, 721), std::runtime_error);
  EXPECT_THROW(OffscreenRenderer(m.get(), 0, 10), std::runtime_error);
}

// Reads an 8-bit RGB PNG back with libpng.
std::vector<unsigned char> ReadPng(const std::string& path, int* w, int* h) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw std::runtime_error("cannot open " + path);
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    std::fclose(f);
    throw std::runtime_error("libpng failed reading " + path);
  }
  png_init_io(png, f);
  png_read_info(png, info);
  *w = static_cast<int>(png_get_image_width(png, info));
  *h = static_cast<int>(png_get_image_height(png, info));
  const bool rgb8 =
      png_get_color_type(png, info) == PNG_COLOR_TYPE_RGB && png_get_bit_depth(png, info) == 8;
  std::vector<unsigned char> pixels(static_cast<size_t>(*w) * *h * 3);
  if (rgb8) {
    for (int y = 0; y < *h; ++y)
      png_read_row(png, pixels.data() + static_cast<size_t>(y) * *w * 3, nullptr);
    png_read_end(png, nullptr);
  }
  png_destroy_read_struct(&png, &info, nullptr);
  std::fclose(f);
  if (!rgb8) throw std::runtime_error(path + " is not 8-bit RGB");
  return pixels;
}

TEST(WritePng, RoundTrip) {
  const int w = 37, h = 23;  // odd sizes
  std::vector<unsigned char> rgb(static_cast<size_t>(w) * h * 3);
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = static_cast<unsigned char>((i * 7919) % 251);
  const std::string path = TempPath("roundtrip.png");
  WritePng(path, rgb.data(), w, h);
  EXPECT_NE(::access((path + ".tmp").c_str(), F_OK), 0) << "temporary file left behind";
  int rw = 0, rh = 0;
  EXPECT_EQ(ReadPng(path, &rw, &rh), rgb);
  EXPECT_EQ(rw, w);
  EXPECT_EQ(rh, h);
  std::remove(path.c_str());
}

TEST(WritePng, BadPathThrowsNamingThePath) {
  const std::vector<unsigned char> rgb(4 * 4 * 3, 128);
  const std::string path = "/nonexistent_dir_mjf/sub/snap.png";
  try {
    WritePng(path, rgb.data(), 4, 4);
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

std::string Shell(const std::string& command) {
  std::string out;
  std::FILE* p = ::popen(command.c_str(), "r");
  if (!p) return out;
  char buf[256];
  while (std::fgets(buf, sizeof(buf), p)) out += buf;
  ::pclose(p);
  return out;
}

TEST(VideoWriter, WritesMp4WithAllFrames) {
  auto m = LoadModel();
  auto d = MakeData(m.get());
  const int w = 320, h = 240, frames = 12;
  OffscreenRenderer renderer(m.get(), w, h, false);
  const std::string path = TempPath("video.mp4");
  {
    VideoWriter video(path, w, h, 25);
    for (int k = 0; k < frames; ++k) {
      double target[3] = {0.25 * k, 0, 0.5};
      video.AddFrame(renderer.Render(d.get(), FollowCamera(), {}, target).data());
      if (k == 0) {
        EXPECT_NE(::access(path.c_str(), F_OK), 0) << "the final name appears only when done";
      }
    }
    EXPECT_EQ(video.frames(), frames);
    video.Close();
    video.Close();  // idempotent
  }
  std::ifstream f(path, std::ios::binary | std::ios::ate);
  ASSERT_TRUE(f.good());
  EXPECT_GT(static_cast<long>(f.tellg()), 1000);
  const std::string count = Shell(
      "ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames,"
      "codec_name,pix_fmt,width,height -of default=noprint_wrappers=1 '" +
      path + "'");
  EXPECT_NE(count.find("nb_read_frames=" + std::to_string(frames)), std::string::npos) << count;
  EXPECT_NE(count.find("codec_name=h264"), std::string::npos) << count;
  EXPECT_NE(count.find("pix_fmt=yuv420p"), std::string::npos) << count;
  EXPECT_NE(count.find("width=320"), std::string::npos) << count;
  std::remove(path.c_str());
}

TEST(VideoWriter, OddSizeIsPadded) {
  const int w = 33, h = 17;
  const std::vector<unsigned char> rgb(static_cast<size_t>(w) * h * 3, 200);
  const std::string path = TempPath("odd.mp4");
  {
    VideoWriter video(path, w, h, 10);
    for (int k = 0; k < 3; ++k) video.AddFrame(rgb.data());
  }  // the destructor closes
  const std::string out = Shell(
      "ffprobe -v error -count_frames -show_entries "
      "stream=nb_read_frames -of csv=p=0 '" +
      path + "'");
  EXPECT_EQ(out, "3\n");
  std::remove(path.c_str());
}

TEST(VideoWriter, MissingDirectoryThrows) {
  const std::string path = "/nonexistent_dir_mjf/video.mp4";
  try {
    VideoWriter video(path, 64, 48, 30);
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos) << e.what();
  }
}

TEST(VideoWriter, MissingFfmpegThrows) {
  const char* old = std::getenv("PATH");
  const std::string saved = old ? old : "";
  ::setenv("PATH", "/nonexistent_dir_mjf", 1);
  try {
    VideoWriter video(TempPath("x.mp4"), 64, 48, 30);
    ::setenv("PATH", saved.c_str(), 1);
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    ::setenv("PATH", saved.c_str(), 1);
    EXPECT_NE(std::string(e.what()).find("ffmpeg not found on PATH"), std::string::npos)
        << e.what();
  }
}

TEST(VideoWriter, FfmpegFailureIsReported) {
  // ffmpeg cannot open its output when a directory sits at path + ".tmp": the failure surfaces as
  // an exception (from AddFrame or Close) that names the path and carries ffmpeg's message.
  const int w = 64, h = 48;
  const std::vector<unsigned char> rgb(static_cast<size_t>(w) * h * 3, 0);
  const std::string path = TempPath("blocked.mp4");
  ASSERT_EQ(::mkdir((path + ".tmp").c_str(), 0755), 0);
  std::string what;
  try {
    VideoWriter video(path, w, h, 30);
    for (int k = 0; k < 50; ++k) video.AddFrame(rgb.data());
    video.Close();
  } catch (const std::runtime_error& e) {
    what = e.what();
  }
  ::rmdir((path + ".tmp").c_str());
  EXPECT_NE(what.find(path), std::string::npos) << what;
  EXPECT_NE(what.find("ffmpeg"), std::string::npos) << what;
  EXPECT_NE(::access(path.c_str(), F_OK), 0) << "no file that looks complete after a failure";
}

}  // namespace
}  // namespace mjf::render
