// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// [sensors] and [wind] of an experiment file: the presets, the per-channel keys and the errors.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "mjformation/config/config.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

using mjf::testing::HoverExperiment;
using mjf::testing::Parse;
using ::testing::AllOf;
using ::testing::HasSubstr;

std::string ErrorOf(const std::string& text) {
  try {
    Parse(text);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
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
  EXPECT_THAT(
      ErrorOf(base + "[sensors]\nposition_std = -0.1\n"),
      AllOf(HasSubstr("exp.toml:18:"), HasSubstr("[sensors] position_std"), HasSubstr(">= 0")));
  EXPECT_THAT(ErrorOf(base + "[sensors]\nbody_rate_bias_walk = nan\n"),
              AllOf(HasSubstr("exp.toml:18:"), HasSubstr("[sensors] body_rate_bias_walk"),
                    HasSubstr("finite")));
  EXPECT_THAT(ErrorOf(base + "[sensors]\npreset = \"perfect\"\n"),
              AllOf(HasSubstr("exp.toml:18:"), HasSubstr("[sensors] preset"),
                    HasSubstr("known: ideal, typical")));
  EXPECT_THAT(ErrorOf(base + "[sensors]\nattitude_rate = 300.0\n"),
              AllOf(HasSubstr("[sensors] attitude_rate"), HasSubstr("whole number")));
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
              AllOf(HasSubstr("exp.toml:18:"), HasSubstr("gusts[0] start"),
                    HasSubstr("must lie in the run")));
  EXPECT_THAT(ErrorOf(base + "[wind]\nmean = [1.0, nan, 0.0]\n"),
              AllOf(HasSubstr("[wind] mean"), HasSubstr("finite")));
}

}  // namespace
}  // namespace mjf::runner
