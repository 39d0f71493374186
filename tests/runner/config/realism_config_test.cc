// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// [sensors] and [wind] of an experiment file: the presets, the per-channel keys and the errors.
//
// Unit tests of the source:
// runner/config/src/realism_config.cc: the [sensors] and [wind] readers beyond what
// realism_runner_test.cc checks: the named turbulence levels, the default airspeed, drag and
// gust keys and their errors, and what summary.json says about both sections.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "error_of.hpp"
#include "mjformation/config/config_error.hpp"
#include "mjformation/config/experiment.hpp"
#include "mjformation/run/run.hpp"
#include "mjformation/run/summary.hpp"
#include "mjformation/sim/simulation.hpp"
#include "point_mass_util.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

using mjf::testing::HoverExperiment;
using mjf::testing::Parse;
using ::testing::AllOf;
using ::testing::HasSubstr;

std::string ErrorOf(const std::string& text) {
  return mjf::testing::ErrorOf([&] { Parse(text); });
}

// The sensor and estimator keys: each refused with FILE:LINE: [sensors] key and the reason.
TEST(RealismConfig, SensorSuiteKeysAreRangeChecked) {
  const std::string base = HoverExperiment(2, 2.0);  // 16 lines
  const std::pair<const char*, const char*> bad[] = {
      {"position_wander = -1.0", "[sensors] position_wander"},
      {"position_wander = inf", "[sensors] position_wander"},
      {"position_wander_tau = 0.0", "[sensors] position_wander_tau"},
      {"velocity_correlation = 1.5", "[sensors] velocity_correlation"},
      {"accel_noise = -0.1", "[sensors] accel_noise"},
      {"accel_bias_walk = nan", "[sensors] accel_bias_walk"},
      {"imu = \"mpu6050\"", "[sensors] imu"},
      {"preset = \"rtk\"\nposition_rate = 30.0", "[sensors] position_rate"}};
  for (const auto& [line, key] : bad) {
    EXPECT_THAT(ErrorOf(base + "[sensors]\n" + line + "\n"),
                AllOf(HasSubstr("exp.toml:"), HasSubstr(key)))
        << line;
  }
  // The presets parse and switch the accelerometer on; typical keeps it off.
  for (const char* preset : {"consumer_gnss", "rtk", "mocap"}) {
    const ExperimentConfig c =
        Parse(base + "[sensors]\npreset = \"" + std::string(preset) + "\"\n");
    EXPECT_TRUE(c.sensors.params.accel.enabled) << preset;
  }
  EXPECT_FALSE(Parse(base + "[sensors]\npreset = \"typical\"\n").sensors.params.accel.enabled);
}

// Every noise key is bounded at parse time, as latency and scale are: 1e300 m of position noise
// once ran to "complete" on 1e300 m estimates. The bound is the channel's, in its unit, and every
// preset at the largest scale (100) stays inside it.
TEST(RealismConfig, EveryNoiseKeyIsBoundedInItsUnit) {
  const std::string base = HoverExperiment(2, 2.0);
  const std::pair<const char*, const char*> bad[] = {
      {"preset = \"mocap\"\nposition_std = 1e300",
       "[sensors] position_std: must be a number in [0, 1000] m"},
      {"position_wander = 1e200", "[sensors] position_wander: must be a number in [0, 1000] m"},
      {"velocity_std = 1e6", "[sensors] velocity_std: must be a number in [0, 100] m/s"},
      {"attitude_std = 4.0", "[sensors] attitude_std: must be a number in [0, 3.2] rad"},
      {"body_rate_bias_walk = 1e9",
       "[sensors] body_rate_bias_walk: must be a number in [0, 10] rad/s/sqrt(s)"},
      {"position_bias_walk = 101.0", "[sensors] position_bias_walk"},
      {"accel_noise = 1e300", "[sensors] accel_noise: must be a number in [0, 100] m/s^2/sqrt(Hz)"},
      {"accel_bias_walk = 11.0", "[sensors] accel_bias_walk: must be a number in [0, 10]"}};
  for (const auto& [lines, message] : bad) {
    EXPECT_THAT(ErrorOf(base + "[sensors]\n" + lines + "\n"), HasSubstr(message)) << lines;
  }
  for (const char* preset : {"typical", "consumer_gnss", "rtk", "mocap"}) {
    for (const char* imu : {"icm42688", "ekf2"}) {
      EXPECT_NO_THROW(Parse(base + "[sensors]\npreset = \"" + std::string(preset) + "\"\nimu = \"" +
                            imu + "\"\nscale = 100.0\n"))
          << preset << " " << imu;
    }
  }
}

TEST(RealismConfig, DefaultsAreIdealAndCalm) {
  const ExperimentConfig c = Parse(HoverExperiment());
  EXPECT_FALSE(c.sensors.enabled());
  EXPECT_FALSE(c.wind.enabled());
  EXPECT_EQ(c.sensors.preset, "ideal");
}

TEST(RealismConfig, PresetScaleAndPerChannelKeys) {
  const ExperimentConfig c = Parse(HoverExperiment() +
                                   "[sensors]\npreset = \"typical\"\nscale = 3.0\n"
                                   "velocity_std = 0.25\nposition_latency = 0.0\n");
  const auto typical = realism::SensorParams::Typical();
  using realism::Channel;
  EXPECT_DOUBLE_EQ(c.sensors.params[Channel::kPosition].white_std,
                   3 * typical[Channel::kPosition].white_std);
  EXPECT_DOUBLE_EQ(c.sensors.params[Channel::kAttitude].bias_walk,
                   3 * typical[Channel::kAttitude].bias_walk);
  EXPECT_EQ(c.sensors.params[Channel::kVelocity].white_std, 0.25);
  EXPECT_EQ(c.sensors.params[Channel::kPosition].latency_s, 0.0);
  EXPECT_EQ(c.sensors.params[Channel::kPosition].rate_hz, 10.0);

  const ExperimentConfig w =
      Parse(HoverExperiment() +
            "[wind]\nmean = [3.0, 4.0, 0.0]\nturbulence = \"moderate\"\naltitude = 5.0\n"
            "gusts = [{start = 0.5, duration = 1.0, amplitude = [0, 2, 0]}]\n");
  EXPECT_TRUE(w.wind.enabled());
  EXPECT_NEAR(w.wind.w20, 15.43, 0.01);                           // 30 knots
  EXPECT_NEAR(w.wind.params.dryden.sigma[2], 1.543, 0.001);       // 0.1 W20
  EXPECT_NEAR(w.wind.params.dryden.scale_length[2], 5.0, 1e-12);  // L_w = h
  EXPECT_DOUBLE_EQ(w.wind.params.dryden.airspeed, 5.0);           // |mean|
  ASSERT_EQ(w.wind.params.gusts.size(), 1u);
  EXPECT_EQ(w.wind.params.gusts[0].amplitude[1], 2.0);
}

TEST(RealismConfig, BadInputNamesFileLineAndKey) {
  const std::string base = HoverExperiment(2, 2.0);  // 16 lines
  EXPECT_THAT(ErrorOf(base + "[sensors]\nposition_std = -0.1\n"),
              AllOf(HasSubstr("exp.toml:18:"), HasSubstr("[sensors] position_std"),
                    HasSubstr("a number in [0, 1000] m")));
  EXPECT_THAT(ErrorOf(base + "[sensors]\nbody_rate_bias_walk = nan\n"),
              AllOf(HasSubstr("exp.toml:18:"), HasSubstr("[sensors] body_rate_bias_walk"),
                    HasSubstr("finite")));
  EXPECT_THAT(
      ErrorOf(base + "[sensors]\npreset = \"perfect\"\n"),
      AllOf(HasSubstr("exp.toml:18:"), HasSubstr("[sensors] preset"),
            HasSubstr(
                "must be one of \"ideal\", \"typical\", \"consumer_gnss\", \"rtk\", \"mocap\"")));
  EXPECT_THAT(ErrorOf(base + "[sensors]\nattitude_rate = 300.0\n"),
              AllOf(HasSubstr("[sensors] attitude_rate"), HasSubstr("whole number")));
  EXPECT_THAT(ErrorOf(base + "[sensors]\nscale = \"high\"\n"),
              AllOf(HasSubstr("exp.toml:18: [sensors] scale"),
                    HasSubstr("expected a number, got a string")));
  EXPECT_THAT(ErrorOf(base + "[wind]\ngusts = 3\n"),
              AllOf(HasSubstr("exp.toml:18: [wind] gusts"),
                    HasSubstr("expected an array, got an integer")));
  EXPECT_THAT(ErrorOf(base + "[sensors]\nposition_sd = 1.0\n"),
              AllOf(HasSubstr("[sensors] position_sd"), HasSubstr("unknown key")));
  EXPECT_THAT(ErrorOf(base + "[wind]\nturbulence = \"w20\"\nw20 = 80.0\n"),
              AllOf(HasSubstr("exp.toml:19:"), HasSubstr("[wind] w20"), HasSubstr("[0, 40]")));
  EXPECT_THAT(
      ErrorOf(base +
              "[wind]\nturbulence = \"light\"\naltitude = 5.0\nscale_length = [0.1, 10, 10]\n"),
      AllOf(HasSubstr("exp.toml:20:"), HasSubstr("[wind] scale_length"), HasSubstr("[1, 3000]")));
  EXPECT_THAT(
      ErrorOf(base + "[wind]\nturbulence = \"light\"\naltitude = 5.0\nsigma = [1, 30, 1]\n"),
      AllOf(HasSubstr("[wind] sigma"), HasSubstr("[0, 20]")));
  EXPECT_THAT(
      ErrorOf(base + "[wind]\nturbulence = \"light\"\naltitude = 1.0\n"),
      AllOf(HasSubstr("exp.toml:19:"), HasSubstr("[wind] altitude"), HasSubstr("10..1000 ft")));
  EXPECT_THAT(ErrorOf(base + "[wind]\nturbulence = \"storm\"\n"),
              AllOf(HasSubstr("[wind] turbulence"), HasSubstr("unknown level")));
  EXPECT_THAT(ErrorOf(base + "[wind]\ngusts = [{start = 1.5, duration = 1.0, amplitude = [1, 0, "
                             "0]}]\n"),
              AllOf(HasSubstr("exp.toml:18:"), HasSubstr("gusts[1] start"),
                    HasSubstr("must lie in the run")));
  EXPECT_THAT(ErrorOf(base + "[wind]\nmean = [1.0, nan, 0.0]\n"),
              AllOf(HasSubstr("[wind] mean"), HasSubstr("finite")));
}

using mjf::testing::Parse;
using mjf::testing::PointMassExperiment;
using ::testing::AllOf;
using ::testing::HasSubstr;

// The point-mass experiment (22 lines) followed by `sections`: its first line is line 23.
std::string With(const std::string& sections) {
  return PointMassExperiment(-2, 1, 2, 1, 2.0, "", sections);
}

std::string SectionErrorOf(const std::string& sections) {
  try {
    Parse(With(sections));
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(RealismConfigTest, NamedTurbulenceLevelsAreMilF8785cW20) {
  const double knot = 0.514444;
  EXPECT_DOUBLE_EQ(Parse(With("[wind]\nturbulence = \"light\"\naltitude = 5.0\n")).wind.w20,
                   15 * knot);
  EXPECT_DOUBLE_EQ(Parse(With("[wind]\nturbulence = \"moderate\"\naltitude = 5.0\n")).wind.w20,
                   30 * knot);
  EXPECT_DOUBLE_EQ(Parse(With("[wind]\nturbulence = \"severe\"\naltitude = 5.0\n")).wind.w20,
                   45 * knot);
  const ExperimentConfig w =
      Parse(With("[wind]\nturbulence = \"w20\"\nw20 = 12.5\naltitude = 5.0\n"));
  EXPECT_EQ(w.wind.w20, 12.5);
  EXPECT_TRUE(w.wind.params.turbulence);
  EXPECT_TRUE(w.wind.enabled());
}

TEST(RealismConfigTest, TurbulenceKeysThatContradictEachOther) {
  EXPECT_THAT(SectionErrorOf("[wind]\nturbulence = \"light\"\naltitude = 5.0\nw20 = 5.0\n"),
              HasSubstr("[wind] w20: give either turbulence = \"light\" or w20"));
  EXPECT_THAT(SectionErrorOf("[wind]\nturbulence = \"w20\"\n"),
              HasSubstr("[wind] w20: missing: turbulence = \"w20\" needs w20 (m/s)"));
  EXPECT_THAT(SectionErrorOf("[wind]\nsigma = [1.0, 1.0, 1.0]\n"),
              HasSubstr("[wind] turbulence: is \"none\": w20, sigma and scale_length need a "
                        "turbulence level"));
}

TEST(RealismConfigTest, TheDefaultAirspeedIsTheMeanWindWithAOneMetreFloor) {
  EXPECT_DOUBLE_EQ(
      Parse(With("[wind]\nmean = [3.0, 4.0, 9.0]\nturbulence = \"light\"\naltitude = 5.0\n"))
          .wind.params.dryden.airspeed,
      5.0);  // horizontal only
  EXPECT_DOUBLE_EQ(
      Parse(With("[wind]\nmean = [0.3, 0.0, 0.0]\nturbulence = \"light\"\naltitude = 5.0\n"))
          .wind.params.dryden.airspeed,
      1.0);
  EXPECT_DOUBLE_EQ(Parse(With("[wind]\nturbulence = \"light\"\naltitude = 5.0\nairspeed = 7.0\n"))
                       .wind.params.dryden.airspeed,
                   7.0);
}

TEST(RealismConfigTest, TurbulenceRateMustBeAWholeNumberOfSteps) {
  // 1 ms physics: 250 Hz is 4 steps; 300 Hz is 3.33 steps; 2 kHz is half a step.
  EXPECT_EQ(Parse(With("[wind]\nturbulence = \"light\"\naltitude = 5.0\nturbulence_rate = 250.0\n"))
                .wind.params.turbulence_rate_hz,
            250.0);
  for (const char* rate : {"300.0", "2000.0", "0.0", "-10.0"}) {
    EXPECT_THAT(
        SectionErrorOf(
            std::string("[wind]\nturbulence = \"light\"\naltitude = 5.0\nturbulence_rate = ") +
            rate + "\n"),
        HasSubstr("[wind] turbulence_rate: 1 / rate must be a whole number"))
        << rate;
  }
  EXPECT_THAT(SectionErrorOf(
                  "[wind]\nturbulence = \"light\"\naltitude = 5.0\nturbulence_correlation = 1.5\n"),
              HasSubstr("[wind] turbulence_correlation: must be in [0, 1]"));
}

TEST(RealismConfigTest, DragKeys) {
  const ExperimentConfig c =
      Parse(With("[wind]\nmean = [1.0, 0.0, 0.0]\ndrag_rotor_linear = 0.5\n"
                 "drag_cda_horizontal = 0.02\ndrag_cda_vertical = 0.04\nair_density = 1.0\n"));
  EXPECT_EQ(c.wind.drag.rotor_linear, 0.5);
  EXPECT_EQ(c.wind.drag.cda_horizontal, 0.02);
  EXPECT_EQ(c.wind.drag.cda_vertical, 0.04);
  EXPECT_EQ(c.wind.drag.air_density, 1.0);
  // Without them: the Iris-like quadrotor's drag.
  const ExperimentConfig iris = Parse(With("[wind]\nmean = [1.0, 0.0, 0.0]\n"));
  EXPECT_EQ(iris.wind.drag.rotor_linear, realism::DragParams::Iris().rotor_linear);
  // Errors name the file, the line of the key, the section and the key.
  EXPECT_THAT(SectionErrorOf("[wind]\nmean = [1.0, 0.0, 0.0]\ndrag_rotor_linear = -0.1\n"),
              HasSubstr("exp.toml:25: [wind] drag_rotor_linear: must be >= 0 N s/m"));
  EXPECT_THAT(SectionErrorOf("[wind]\nmean = [1.0, 0.0, 0.0]\nair_density = 2.5\n"),
              HasSubstr("[wind] air_density: must be in (0, 2) kg/m^3"));
}

TEST(RealismConfigTest, GustErrors) {
  EXPECT_THAT(SectionErrorOf("[wind]\ngusts = [3]\n"),
              HasSubstr("[wind] gusts: expected {start = s, duration = s, amplitude = [x, y, z]}"));
  EXPECT_THAT(SectionErrorOf("[wind]\ngusts = [{start = 0.5, duration = 1.0}]\n"),
              HasSubstr("each gust needs start, duration and amplitude"));
  // A misspelt key is named as written, not reported as the key it was meant to be.
  EXPECT_THAT(SectionErrorOf("[wind]\ngusts = [{start = 0.5, duration = 1.0, amplitud = [1, 0, "
                             "0]}]\n"),
              AllOf(HasSubstr("gusts[1] amplitud"), HasSubstr("unknown key")));
  EXPECT_THAT(
      SectionErrorOf("[wind]\ngusts = [{start = 0.5, duration = 0.0, amplitude = [1, 0, 0]}]\n"),
      HasSubstr("[wind] gusts[1] duration: must be at least two physics steps"));
  EXPECT_THAT(
      SectionErrorOf("[wind]\ngusts = [{start = 0.5, duration = 1.0, amplitude = [1, 0, 0]}, "
                     "{start = 0.1, duration = 0.5, amplitude = [0, 60, 0]}]\n"),
      HasSubstr("[wind] gusts[2] amplitude: components must be within +-50 m/s"));
  EXPECT_THAT(
      SectionErrorOf("[wind]\ngusts = [{start = 0.5, duration = 1.0, amplitude = [1, 0, 0], "
                     "shape = \"square\"}]\n"),
      AllOf(HasSubstr("gusts[1] shape"), HasSubstr("unknown key")));
  // A gust alone is wind.
  EXPECT_TRUE(
      Parse(With("[wind]\ngusts = [{start = 0.5, duration = 1.0, amplitude = [1, 0, 0]}]\n"))
          .wind.enabled());
}

TEST(RealismConfigTest, SectionsMustBeTables) {
  // A top-level key (before any table) named like a section: the experiment reader refuses it
  // before the realism reader sees it.
  try {
    Parse("sensors = 3\n" + With(""));
    ADD_FAILURE() << "accepted";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr("exp.toml:1: sensors: expected a [section] table")));
  }
}

TEST(RealismConfigTest, WhatSummaryJsonSaysAboutBoth) {
  Simulation sim(
      Parse(With("[sensors]\npreset = \"typical\"\nscale = 2.0\n"
                 "position_latency = 0.0\n[wind]\nmean = [2.0, 0.0, 0.0]\n"
                 "turbulence = \"light\"\naltitude = 5.0\n"
                 "gusts = [{start = 0.5, duration = 1.0, amplitude = [0, 1, 0]}]\n")));
  const auto s = BuildSummary(sim, RunResult{}, nlohmann::ordered_json::object());
  ASSERT_TRUE(s.contains("sensors"));
  EXPECT_EQ(s["sensors"]["preset"], "typical");
  EXPECT_EQ(s["sensors"]["scale"], 2.0);
  const auto typical = realism::SensorParams::Typical();
  int k = 0;
  for (const char* name : {"position", "velocity", "attitude", "body_rate"}) {
    const auto& ch = s["sensors"]["channels"][name];
    EXPECT_DOUBLE_EQ(ch["std"].get<double>(), 2.0 * typical.channel[k].white_std) << name;
    EXPECT_EQ(ch["rate_hz"].get<double>(), typical.channel[k].rate_hz) << name;
    ++k;
  }
  EXPECT_EQ(s["sensors"]["channels"]["position"]["latency_s"], 0.0);  // the per-channel key
  const auto& w = s["wind"];
  EXPECT_EQ(w["turbulence"], "light");
  EXPECT_DOUBLE_EQ(w["w20"].get<double>(), 15 * 0.514444);
  EXPECT_EQ(w["airspeed"], 2.0);
  ASSERT_EQ(w["gusts"].size(), 1u);
  EXPECT_EQ(w["gusts"][0]["amplitude"], nlohmann::ordered_json::parse("[0.0, 1.0, 0.0]"));
  EXPECT_EQ(w["drag"]["air_density"], 1.225);
}

}  // namespace
}  // namespace mjf::runner
