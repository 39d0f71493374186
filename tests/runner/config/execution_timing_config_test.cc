// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// [execution] predict / clock_offset / clock_drift_ppm and the whole-step latency rule:
// parsed, and every bad value refused with FILE:LINE: [section] key.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "error_of.hpp"
#include "mjformation/config/experiment.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

// Leader -> 1 -> 2, the discrete law with T = 0.05 s, then `execution` and `extra`.
std::string Experiment(const std::string& execution, const std::string& extra = "") {
  return "[run]\nname = \"t\"\nduration = 2.0\ntimestep = 0.001\n"
         "[vehicles]\nmodel = \"pointmass\"\nfollowers = 2\n"
         "[topology]\nleader_links = [1]\nedges = [[1, 2]]\n"
         "[leader]\nplugin = \"hover\"\n[formation]\nplugin = \"smc_discrete\"\nperiod = 0.05\n"
         "[attitude]\nplugin = \"pointmass_direct\"\n" +
         execution + extra;
}

std::string ErrorOf(const std::string& text) {
  return mjf::testing::ErrorOf([&] { mjf::testing::Parse(text, "t.toml"); });
}

TEST(ExecutionTimingConfigTest, DefaultsPredictNothingInPhase) {
  const ExperimentConfig c = mjf::testing::Parse(Experiment("[execution]\nmode = \"per_agent\"\n"));
  EXPECT_EQ(c.network.predict, Predict::kNone);
  EXPECT_EQ(c.network.clock_offset, 0.0);
  EXPECT_EQ(c.network.clock_drift_ppm, 0.0);
  EXPECT_FALSE(c.network.clock_sync);
}

TEST(ExecutionTimingConfigTest, KeysParse) {
  const ExperimentConfig c =
      mjf::testing::Parse(Experiment("[execution]\nmode = \"per_agent\"\npredict = \"attitude\"\n"
                                     "clock_offset = 0.025\nclock_drift_ppm = 100.0\n"
                                     "clock_sync = true\n"));
  EXPECT_EQ(c.network.predict, Predict::kAttitude);
  EXPECT_EQ(c.network.clock_offset, 0.025);
  EXPECT_EQ(c.network.clock_drift_ppm, 100.0);
  EXPECT_TRUE(c.network.clock_sync);
}

TEST(ExecutionTimingConfigTest, BadValuesAreRefusedWithFileLineAndKey) {
  const std::string head = "[execution]\nmode = \"per_agent\"\n";  // lines 18-19
  EXPECT_THAT(
      ErrorOf(Experiment(head + "predict = \"kalman\"\n")),
      AllOf(HasSubstr("t.toml:20"), HasSubstr("[execution] predict"), HasSubstr("\"input\"")));
  EXPECT_THAT(
      ErrorOf(Experiment(head + "clock_offset = 0.05\n")),
      AllOf(HasSubstr("t.toml:20"), HasSubstr("[execution] clock_offset"), HasSubstr("T = 0.05")));
  EXPECT_THAT(ErrorOf(Experiment(head + "clock_offset = -0.001\n")),
              HasSubstr("[execution] clock_offset"));
  EXPECT_THAT(ErrorOf(Experiment(head + "clock_drift_ppm = 1.5e4\n")),
              AllOf(HasSubstr("t.toml:20"), HasSubstr("[execution] clock_drift_ppm")));
  EXPECT_THAT(ErrorOf(Experiment(head + "clock_drift_ppm = nan\n")),
              AllOf(HasSubstr("[execution] clock_drift_ppm"), HasSubstr("finite")));
  EXPECT_THAT(ErrorOf(Experiment(head + "clock_offset = inf\n")),
              HasSubstr("[execution] clock_offset"));
  EXPECT_THAT(ErrorOf(Experiment("[execution]\npredict = \"input\"\n")),
              AllOf(HasSubstr("[execution] predict"), HasSubstr("per_agent")));
  EXPECT_THAT(
      ErrorOf(Experiment("[execution]\nclock_sync = true\n")),
      AllOf(HasSubstr("t.toml:19"), HasSubstr("[execution] clock_sync"), HasSubstr("per_agent")));
  EXPECT_THAT(ErrorOf(Experiment(head + "clock_sync = \"gnss\"\n")),
              AllOf(HasSubstr("t.toml:20"), HasSubstr("[execution] clock_sync")));
}

TEST(ExecutionTimingConfigTest, SubStepLatencyIsRefusedNotRounded) {
  const std::string head = "[execution]\nmode = \"per_agent\"\n";
  EXPECT_THAT(ErrorOf(Experiment(head, "[network]\nlatency = 0.0005\n")),
              AllOf(HasSubstr("t.toml:21"), HasSubstr("[network] latency"),
                    HasSubstr("whole number of physics steps")));
  EXPECT_THAT(ErrorOf(Experiment(head,
                                 "[network]\n[[network.link]]\nfrom = 0\nto = 1\n"
                                 "latency = 0.0025\n")),
              HasSubstr("latency"));
  // Whole steps are kept exactly, including one that is not exact in binary (0.003 / 0.001).
  const ExperimentConfig c = mjf::testing::Parse(Experiment(head, "[network]\nlatency = 0.003\n"));
  EXPECT_EQ(c.network.defaults.latency, 0.003);
}

}  // namespace
}  // namespace mjf::runner
