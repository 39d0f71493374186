// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// [sensors] and [wind]: typed, range-checked, with errors naming FILE:LINE: [section] key.
#include "realism_config.hpp"

#include <cmath>
#include <set>
#include <sstream>

#include "mjformation/time_steps.hpp"
#include "section_reader.hpp"

namespace mjf::runner {
namespace {

void ParseSensors(const toml::table* table, const std::string& path, ExperimentConfig* c) {
  SectionReader keys(path, table, "sensors");
  SensorsConfig& s = c->sensors;
  s.params = keys.Enum("preset", &realism::SensorParams::Ideal, kSensorPresetWords)();
  s.preset = keys.String("preset", s.preset);
  s.scale = keys.Number("scale", s.scale);
  keys.MarkUsed("imu");  // known even when absent: the unknown-key message lists it
  if (keys.Has("imu")) {
    s.imu = keys.String("imu", "");
    if (!realism::SensorParams::ImuGrade(s.imu, &s.params.accel)) {
      keys.Fail("imu", "unknown IMU grade '" + s.imu + "' (known: icm42688, ekf2)");
    }
  }
  if (!(s.scale >= 0 && s.scale <= 100)) keys.Fail("scale", "must be in [0, 100] (1: the preset)");
  s.params = s.params.Scaled(s.scale);
  for (int k = 0; k < realism::kChannels; ++k) {
    const std::string name = realism::ChannelName(static_cast<realism::Channel>(k));
    realism::ChannelNoise& n = s.params.channel[k];
    n.white_std = keys.Number(name + "_std", n.white_std);
    n.bias_walk = keys.Number(name + "_bias_walk", n.bias_walk);
    n.rate_hz = keys.Number(name + "_rate", n.rate_hz);
    n.latency_s = keys.Number(name + "_latency", n.latency_s);
    n.wander_sigma = keys.Number(name + "_wander", n.wander_sigma);
    n.wander_tau = keys.Number(name + "_wander_tau", n.wander_tau);
    n.correlation = keys.Number(name + "_correlation", n.correlation);
  }
  realism::AccelNoise& a = s.params.accel;
  if (keys.Has("accel_noise") || keys.Has("accel_bias_walk")) a.enabled = true;
  a.noise_density = keys.Number("accel_noise", a.noise_density);
  a.bias_walk = keys.Number("accel_bias_walk", a.bias_walk);
  keys.RejectUnknown();
  const std::string problem = s.params.Validate(c->timestep);
  if (!problem.empty()) {
    const auto colon = problem.find(':');
    keys.Fail(problem.substr(0, colon), problem.substr(colon + 2));
  }
  for (int k = 0; k < realism::kChannels; ++k) {  // a later reading never arrives
    if (s.params.channel[k].latency_s > c->duration) {
      const std::string key =
          std::string(realism::ChannelName(static_cast<realism::Channel>(k))) + "_latency";
      keys.Fail(key, "is longer than the run (" + std::to_string(c->duration) + " s)");
    }
  }
}

// MIL-F-8785C's W20 for its named intensities: 15, 30 and 45 knots.
double NamedW20(const std::string& name) {
  const double knot = 0.514444;  // m/s
  if (name == "light") return 15 * knot;
  if (name == "moderate") return 30 * knot;
  if (name == "severe") return 45 * knot;
  return -1;
}

// The turbulence keys of [wind], read before any of them is checked against the others.
struct TurbulenceKeys {
  bool has_w20 = false, has_sigma = false, has_length = false;
  double altitude = 0, airspeed = 0;
  std::array<double, 3> sigma{}, length{};
};

void ReadMeanWind(SectionReader& keys, realism::WindParams& p) {
  p.mean = keys.Vector3("mean", p.mean);
  for (double v : p.mean) {
    if (std::abs(v) > 50) keys.Fail("mean", "components must be within +-50 m/s");
  }
}

TurbulenceKeys ReadTurbulenceKeys(SectionReader& keys, const ExperimentConfig& c, WindConfig& w) {
  realism::WindParams& p = w.params;
  TurbulenceKeys t;
  w.turbulence = keys.String("turbulence", w.turbulence);
  t.has_w20 = keys.Has("w20");
  w.w20 = keys.Number("w20", 0.0);
  t.altitude = keys.Number("altitude", c.altitude);
  const double horizontal = std::hypot(p.mean[0], p.mean[1]);
  // Taylor's frozen turbulence is carried past a hovering vehicle by the mean wind; 1 m/s floor.
  t.airspeed = keys.Number("airspeed", std::max(1.0, horizontal));
  p.turbulence_rate_hz = keys.Number("turbulence_rate", p.turbulence_rate_hz);
  if (!(p.turbulence_rate_hz > 0) || WholeSteps(1.0 / p.turbulence_rate_hz, c.timestep) < 1) {
    keys.Fail("turbulence_rate", "1 / rate must be a whole number (>= 1) of physics steps");
  }
  p.turbulence_correlation = keys.Number("turbulence_correlation", 0.0);
  if (!(p.turbulence_correlation >= 0 && p.turbulence_correlation <= 1)) {
    keys.Fail("turbulence_correlation", "must be in [0, 1]");
  }
  t.has_sigma = keys.Has("sigma");
  t.has_length = keys.Has("scale_length");
  t.sigma = keys.Vector3("sigma", {0, 0, 0});
  t.length = keys.Vector3("scale_length", {0, 0, 0});
  return t;
}

// The turbulence level: a named MIL-F-8785C intensity or w20, then the Dryden parameters at
// the altitude, with sigma and scale_length overriding the standard's.
void ApplyTurbulence(const SectionReader& keys, const TurbulenceKeys& t, WindConfig& w) {
  realism::WindParams& p = w.params;
  // Checked with or without turbulence: a value that is read must be valid.
  if (!(t.airspeed >= 0.5 && t.airspeed <= 100)) keys.Fail("airspeed", "must be in [0.5, 100] m/s");
  if (!(t.altitude >= 0 && t.altitude <= 1000)) keys.Fail("altitude", "must be in [0, 1000] m");
  if (w.turbulence == "none") {
    if (t.has_w20 || t.has_sigma || t.has_length) {
      keys.Fail("turbulence", "is \"none\": w20, sigma and scale_length need a turbulence level");
    }
    return;
  }
  if (w.turbulence == "w20") {
    if (!t.has_w20) keys.Fail("w20", "missing: turbulence = \"w20\" needs w20 (m/s)");
  } else if (NamedW20(w.turbulence) >= 0) {
    if (t.has_w20) keys.Fail("w20", "give either turbulence = \"" + w.turbulence + "\" or w20");
    w.w20 = NamedW20(w.turbulence);
  } else {
    keys.Fail("turbulence",
              "unknown level '" + w.turbulence + "' (known: none, light, moderate, severe, w20)");
  }
  if (!(w.w20 >= 0 && w.w20 <= 40)) keys.Fail("w20", "must be in [0, 40] m/s");
  if (!(t.airspeed >= 0.5 && t.airspeed <= 100)) keys.Fail("airspeed", "must be in [0.5, 100] m/s");
  try {
    p.dryden = realism::DrydenParams::LowAltitude(t.altitude, w.w20, t.airspeed);
  } catch (const std::invalid_argument& e) {
    keys.Fail("altitude", e.what());
  }
  if (t.has_sigma) {
    for (double v : t.sigma) {
      if (!(v >= 0 && v <= 20)) keys.Fail("sigma", "intensities must be in [0, 20] m/s");
    }
    p.dryden.sigma = t.sigma;
  }
  if (t.has_length) {
    for (double v : t.length) {
      if (!(v >= 1 && v <= 3000)) keys.Fail("scale_length", "must be in [1, 3000] m");
    }
    p.dryden.scale_length = t.length;
  }
  p.turbulence = true;
}

// One entry of [wind] gusts: a 1-cosine gust inside the run.
realism::OneCosineGust ReadGust(const SectionReader& keys, const toml::node& item, int index,
                                const std::string& path, double duration, double timestep) {
  const toml::table* g = item.as_table();
  if (!g) keys.FailAt(&item, "gusts", "expected {start = s, duration = s, amplitude = [x, y, z]}");
  SectionReader gust(path, g, "wind] gusts[" + std::to_string(index), "wind.gusts");
  realism::OneCosineGust one;
  one.start = gust.Number("start", 0);
  one.duration = gust.Number("duration", 1);
  one.amplitude = gust.Vector3("amplitude", {0, 0, 0});
  gust.RejectUnknown();  // before "missing": a misspelt key is named as the user wrote it
  if (!g->contains("start") || !g->contains("duration") || !g->contains("amplitude")) {
    keys.FailAt(&item, "gusts", "each gust needs start, duration and amplitude");
  }
  if (!(one.duration >= 2 * timestep)) {  // a shorter 1-cosine gust never acts on a step
    gust.Fail("duration",
              "must be at least two physics steps (" + std::to_string(2 * timestep) + " s)");
  }
  if (one.start < 0 || one.start + one.duration > duration + 1e-9) {
    gust.Fail("start", "the gust [start, start + duration] must lie in the run [0, " +
                           std::to_string(duration) + "] s");
  }
  for (double v : one.amplitude) {
    if (std::abs(v) > 50) gust.Fail("amplitude", "components must be within +-50 m/s");
  }
  return one;
}

void ReadDragKeys(SectionReader& keys, realism::DragParams& drag) {
  drag.rotor_linear = keys.Number("drag_rotor_linear", drag.rotor_linear);
  drag.cda_horizontal = keys.Number("drag_cda_horizontal", drag.cda_horizontal);
  drag.cda_vertical = keys.Number("drag_cda_vertical", drag.cda_vertical);
  drag.air_density = keys.Number("air_density", drag.air_density);
}

void CheckDrag(const SectionReader& keys, const realism::DragParams& drag) {
  if (drag.rotor_linear < 0) keys.Fail("drag_rotor_linear", "must be >= 0 N s/m");
  if (drag.cda_horizontal < 0) keys.Fail("drag_cda_horizontal", "must be >= 0 m^2");
  if (drag.cda_vertical < 0) keys.Fail("drag_cda_vertical", "must be >= 0 m^2");
  if (!(drag.air_density > 0 && drag.air_density < 2)) {
    keys.Fail("air_density", "must be in (0, 2) kg/m^3");
  }
}

void ParseWind(const toml::table* table, const std::string& path, ExperimentConfig* c) {
  SectionReader keys(path, table, "wind");
  WindConfig& w = c->wind;
  ReadMeanWind(keys, w.params);
  ApplyTurbulence(keys, ReadTurbulenceKeys(keys, *c, w), w);
  if (const toml::array* gusts = keys.Array("gusts")) {
    for (const toml::node& item : *gusts) {
      w.params.gusts.push_back(ReadGust(keys, item, static_cast<int>(w.params.gusts.size()) + 1,
                                        path, c->duration, c->timestep));
    }
  }
  ReadDragKeys(keys, w.drag);
  keys.RejectUnknown();
  CheckDrag(keys, w.drag);
}

}  // namespace

void ParseRealismSections(const toml::table& root, const std::string& path, ExperimentConfig* c) {
  for (const char* name : {"sensors", "wind"}) {
    const toml::node* node = root.get(name);
    if (node && !node->is_table()) {
      SectionReader(path, nullptr, name).FailAt(node, "", "expected a table");
    }
  }
  ParseSensors(root.get_as<toml::table>("sensors"), path, c);
  ParseWind(root.get_as<toml::table>("wind"), path, c);
}

}  // namespace mjf::runner
