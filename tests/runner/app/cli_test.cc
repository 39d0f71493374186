// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The command line as users type it: exit codes and the sweep command.
#include "mjformation/app/cli.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
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

// The exit code and what stderr says for a command line.
std::pair<int, std::string> CliStderr(const std::vector<std::string>& args) {
  ::testing::internal::CaptureStderr();
  const int code = Cli(args);
  return {code, ::testing::internal::GetCapturedStderr()};
}

// Every integer option says what it takes, with the value given (CLI11's own message for a
// PositiveNumber check was a floating-point range of 309 digits that contradicted itself).
TEST(CliTest, EveryIntegerOptionSaysWhatItTakes) {
  const std::string dir = TempDir("cli_integers");
  const std::string exp = WriteFile(dir + "/e.toml", HoverExperiment(1, 0.2));
  const std::pair<std::vector<std::string>, std::string> cases[] = {
      {{"run", exp, "--threads", "0"}, "--threads: an integer in [1, 1024], got '0'"},
      {{"run", exp, "--threads", "two"}, "--threads: an integer in [1, 1024], got 'two'"},
      {{"run", exp, "--threads", "1.5"}, "--threads: an integer in [1, 1024], got '1.5'"},
      {{"run", exp, "--threads", "100000"}, "--threads: an integer in [1, 1024], got '100000'"},
      {{"bench", exp, "--threads", "1,0"}, "--threads: an integer in [1, 1024], got '0'"},
      {{"bench", exp, "--followers", "x"}, "--followers: an integer in [1, 100000], got 'x'"},
      // An empty item of a list is refused, not dropped.
      {{"bench", exp, "--followers", "2,,4"}, "--followers: an empty item in '2,,4'"},
      {{"bench", exp, "--threads", "1,"}, "--threads: an empty item in '1,'"},
      {{"sweep", exp, "--seeds", "0"}, "--seeds: an integer in [1, 100000], got '0'"},
      {{"sweep", exp, "--vary", "run.seed=1,2", "--jobs", "-1"},
       "--jobs: an integer in [1, 1024], got '-1'"}};
  for (const auto& [args, message] : cases) {
    const auto [code, err] = CliStderr(args);
    EXPECT_EQ(code, 2) << message;
    EXPECT_THAT(err, HasSubstr(message));
    EXPECT_THAT(err, ::testing::Not(HasSubstr("1797693134")));
  }
}

// --checkpoint-every takes a finite number of seconds > 0: NaN compared false against every
// step, so a run given it never wrote a checkpoint; a negative value was named with a range of
// 309 digits.
TEST(CliTest, CheckpointEveryTakesAFinitePositiveNumberOfSeconds) {
  const std::string dir = TempDir("cli_checkpoint_every");
  const std::string exp = WriteFile(dir + "/e.toml", HoverExperiment(1, 0.2));
  for (const std::string value : {"nan", "NaN", "inf", "-1", "0", "-0", "1e-400x", "soon"}) {
    const auto [code, err] =
        CliStderr({"run", exp, "--no-render", "-o", dir + "/r", "--checkpoint-every", value});
    EXPECT_EQ(code, 2) << value;
    EXPECT_THAT(
        err, HasSubstr("--checkpoint-every: a finite number of seconds > 0, got '" + value + "'"));
    EXPECT_THAT(err, ::testing::Not(HasSubstr("1797693134")));
    EXPECT_FALSE(std::filesystem::exists(dir + "/r")) << value;
  }
  EXPECT_EQ(Cli({"run", exp, "--no-render", "-q", "-o", dir + "/r", "--checkpoint-every", "0.1"}),
            0);
  EXPECT_TRUE(std::filesystem::exists(dir + "/r/checkpoint.mjfstate"));
}

// A key varied twice would run every cell at the last value while the run names and sweep.csv
// showed both: refused before anything is written.
TEST(CliTest, AKeyVariedTwiceIsRefused) {
  const std::string dir = TempDir("cli_vary_twice");
  const std::string exp = WriteFile(dir + "/e.toml", HoverExperiment(1, 0.2));
  const auto [code, err] =
      CliStderr({"sweep", exp, "--vary", "vehicles.altitude=3.0", "--vary",
                 "vehicles.altitude=1.0,2.0", "--out", dir + "/s", "--no-render"});
  EXPECT_EQ(code, 1);
  EXPECT_THAT(err, HasSubstr("--vary vehicles.altitude is given twice"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/s"));
}

// A key both fixed and swept would run at the swept values with the --set dropped silently; a
// sweep asked to resume and to start over at once has no meaning. Both refused before anything
// is written.
TEST(CliTest, ASweepRefusesAKeyFixedAndVariedAndResumeWithOverwrite) {
  const std::string dir = TempDir("cli_sweep_conflicts");
  const std::string exp = WriteFile(dir + "/e.toml", HoverExperiment(1, 0.2));
  {
    const auto [code, err] =
        CliStderr({"sweep", exp, "--vary", "vehicles.altitude=1.0,2.0", "--set",
                   " vehicles.altitude =3.0", "--out", dir + "/s", "--no-render"});
    EXPECT_EQ(code, 1);
    EXPECT_THAT(err, HasSubstr("--set  vehicles.altitude =3.0 and --vary vehicles.altitude=..."));
  }
  {
    const auto [code, err] =
        CliStderr({"sweep", exp, "--vary", "vehicles.altitude=1.0,2.0", "--resume", "--overwrite",
                   "--out", dir + "/s", "--no-render"});
    EXPECT_NE(code, 0);
    EXPECT_THAT(err, HasSubstr("excludes"));
  }
  EXPECT_FALSE(std::filesystem::exists(dir + "/s"));
}

// Values from the command line are named by their origin, not by a line of the experiment file
// (which does not hold them): the number of partitions, a plugin's refusal, a section a --set
// made.
TEST(CliTest, ValuesFromTheCommandLineAreReportedAtTheirOrigin) {
  const std::string dir = TempDir("cli_origins");
  const std::string exp =
      WriteFile(dir + "/e.toml", "# a comment on line 1\n" + HoverExperiment(1, 0.2));
  const std::pair<std::vector<std::string>, std::string> cases[] = {
      {{"check", exp, "--set", "run.threads=3"},
       "error: --set run.threads=3: [run] threads: 3 partitions for 2 vehicles"},
      {{"run", exp, "--threads", "3", "-o", dir + "/r"},
       "error: --threads 3: [run] threads: 3 partitions for 2 vehicles"},
      {{"check", exp, "--set", "estimator={plugin=\"kf_ins\"}"},
       "error: --set estimator={plugin=\"kf_ins\"}: [estimator] plugin 'kf_ins'"},
      {{"check", exp, "--set", "vehicles.thrust=\"rotor0\"", "--set",
        "vehicles.moments=[\"rotor1\", \"rotor2\", \"rotor3\"]"},
       "error: --set vehicles.thrust=\"rotor0\": [vehicles] thrust: "},
      {{"check", exp, "--set", "network.link=[{from=0,to=1}]"},
       "error: --set network.link=[{from=0,to=1}]: [network]: needs [execution]"}};
  for (const auto& [args, message] : cases) {
    const auto [code, err] = CliStderr(args);
    EXPECT_EQ(code, 1) << message;
    EXPECT_THAT(err, HasSubstr(message));
  }
  EXPECT_FALSE(std::filesystem::exists(dir + "/r"));
}

}  // namespace
}  // namespace mjf::runner
