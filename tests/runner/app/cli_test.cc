// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The command line as users type it: exit codes and the sweep command.
#include "mjformation/app/cli.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "test_util.hpp"

namespace mjf::runner {
namespace {

using mjf::testing::HoverExperiment;
using mjf::testing::ReadFile;
using mjf::testing::TempDir;
using mjf::testing::WriteFile;
using ::testing::HasSubstr;

using mjf::testing::Cli;

TEST(CliTest, ExitCodes) {
  const std::string dir = TempDir("cli");
  const std::string good = WriteFile(dir + "/good.toml", HoverExperiment(1, 0.2));
  const std::string bad = WriteFile(dir + "/bad.toml", "[run]\nduration = \"x\"\n");
  EXPECT_EQ(Cli({"check", good}), 0);
  EXPECT_EQ(Cli({"check", bad}), 1);
  EXPECT_EQ(Cli({"run", bad, "--out", dir + "/bad_run"}), 1);
  EXPECT_EQ(Cli({"run", good, "--out", dir + "/run", "-q"}), 0);
  EXPECT_EQ(Cli({"run", good, "--out", dir + "/run", "-q"}), 1);  // refuses to overwrite
  EXPECT_EQ(Cli({"run"}), 2);                                     // usage
  EXPECT_EQ(Cli({"frobnicate"}), 2);
}

TEST(CliTest, SweepRunsEveryPointAndWritesTheTable) {
  const std::string dir = TempDir("sweep");
  const std::string exp = WriteFile(dir + "/e.toml", HoverExperiment(1, 0.3));
  ASSERT_EQ(Cli({"sweep", exp, "--vary", "vehicles.altitude=2.0,3.0", "--vary", "run.seed=1,2",
                 "--out", dir + "/s", "--no-render"}),
            0);
  const std::string csv = ReadFile(dir + "/s/sweep.csv");
  EXPECT_THAT(csv, HasSubstr("vehicles.altitude,run.seed,complete,sigma_f_mean"));
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 4);
  const auto json = nlohmann::json::parse(ReadFile(dir + "/s/sweep.json"));
  EXPECT_TRUE(json["complete"].get<bool>());
  const auto& table = json["runs"];
  ASSERT_EQ(table.size(), 4u);
  EXPECT_EQ(table[3]["vehicles.altitude"], "3.0");
  EXPECT_EQ(table[3]["run.seed"], "2");
  const auto summary = nlohmann::json::parse(ReadFile(dir + "/s/altitude=3.0,seed=2/summary.json"));
  EXPECT_TRUE(summary["complete"].get<bool>());
  EXPECT_EQ(summary["seed"], 2);
  // A bad value is refused before anything runs.
  EXPECT_EQ(Cli({"sweep", exp, "--vary", "vehicles.altitude=2.0,high", "--out", dir + "/bad"}), 1);
}

}  // namespace
}  // namespace mjf::runner
