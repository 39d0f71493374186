// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// runner/src/realism_config.cc: the [sensors] and [wind] readers beyond what
// realism_runner_test.cc checks: the named turbulence levels, the default airspeed, drag and
// gust keys and their errors, and what summary.json says about both sections.
#include "mjformation/runner/realism_config.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mjformation/runner/config.hpp"
#include "mjformation/runner/run.hpp"
#include "mjformation/runner/simulation.hpp"
#include "mjformation/runner/summary.hpp"
#include "point_mass_util.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

using mjf::testing::Parse;
using mjf::testing::PointMassExperiment;
using ::testing::AllOf;
using ::testing::HasSubstr;

// The point-mass experiment (22 lines) followed by `sections`: its first line is line 23.
std::string With(const std::string& sections) {
  return PointMassExperiment(-2, 1, 2, 1, 2.0, "", sections);
}

std::string ErrorOf(const std::string& sections) {
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
  EXPECT_THAT(ErrorOf("[wind]\nturbulence = \"light\"\naltitude = 5.0\nw20 = 5.0\n"),
              HasSubstr("[wind] w20: give either turbulence = \"light\" or w20"));
  EXPECT_THAT(ErrorOf("[wind]\nturbulence = \"w20\"\n"),
              HasSubstr("[wind] w20: missing: turbulence = \"w20\" needs w20 (m/s)"));
  EXPECT_THAT(ErrorOf("[wind]\nsigma = [1.0, 1.0, 1.0]\n"),
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
        ErrorOf(std::string("[wind]\nturbulence = \"light\"\naltitude = 5.0\nturbulence_rate = ") +
                rate + "\n"),
        HasSubstr("[wind] turbulence_rate: 1 / rate must be a whole number"))
        << rate;
  }
  EXPECT_THAT(
      ErrorOf("[wind]\nturbulence = \"light\"\naltitude = 5.0\nturbulence_correlation = 1.5\n"),
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
  EXPECT_THAT(ErrorOf("[wind]\nmean = [1.0, 0.0, 0.0]\ndrag_rotor_linear = -0.1\n"),
              HasSubstr("exp.toml:25: [wind] drag_rotor_linear: must be >= 0 N s/m"));
  EXPECT_THAT(ErrorOf("[wind]\nmean = [1.0, 0.0, 0.0]\nair_density = 2.5\n"),
              HasSubstr("[wind] air_density: must be in (0, 2) kg/m^3"));
}

TEST(RealismConfigTest, GustErrors) {
  EXPECT_THAT(ErrorOf("[wind]\ngusts = [3]\n"),
              HasSubstr("[wind] gusts: expected {start = s, duration = s, amplitude = [x, y, z]}"));
  EXPECT_THAT(ErrorOf("[wind]\ngusts = [{start = 0.5, duration = 1.0}]\n"),
              HasSubstr("each gust needs start, duration and amplitude"));
  EXPECT_THAT(ErrorOf("[wind]\ngusts = [{start = 0.5, duration = 0.0, amplitude = [1, 0, 0]}]\n"),
              HasSubstr("[wind] gusts[0] duration: must be > 0 s"));
  EXPECT_THAT(ErrorOf("[wind]\ngusts = [{start = 0.5, duration = 1.0, amplitude = [1, 0, 0]}, "
                      "{start = 0.1, duration = 0.5, amplitude = [0, 60, 0]}]\n"),
              HasSubstr("[wind] gusts[1] amplitude: components must be within +-50 m/s"));
  EXPECT_THAT(ErrorOf("[wind]\ngusts = [{start = 0.5, duration = 1.0, amplitude = [1, 0, 0], "
                      "shape = \"square\"}]\n"),
              AllOf(HasSubstr("gusts[0] shape"), HasSubstr("unknown key")));
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
