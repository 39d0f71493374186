// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// runner/app/src/bench.cc: `mjformation bench` on a tiny experiment: the JSON report's sizes, step
// counts and the arithmetic of its ratios; bad input is exit code 1 before anything runs.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "test_util.hpp"

namespace mjf::runner {
namespace {

using mjf::testing::Cli;
using mjf::testing::HoverExperiment;
using mjf::testing::ReadFile;
using mjf::testing::TempDir;
using mjf::testing::WriteFile;

TEST(BenchTest, ReportOfTwoSizes) {
  const std::string dir = TempDir("bench");
  const std::string text = HoverExperiment(1, 0.02);
  const std::string exp = WriteFile(dir + "/e.toml", text);
  ::testing::internal::CaptureStdout();
  ASSERT_EQ(Cli({"bench", exp, "--followers", "1", "2", "--json", dir + "/b.json", "--set",
                 "vehicles.contacts=false"}),
            0);
  const std::string out = ::testing::internal::GetCapturedStdout();
  // The settings echoed, every column explained, headers that say what they are.
  EXPECT_THAT(out, ::testing::HasSubstr("contacts=false, sensors=ideal, wind=calm"));
  EXPECT_THAT(out, ::testing::HasSubstr("wall full/bare: full's wall time over bare's"));
  EXPECT_THAT(out, ::testing::HasSubstr("RTF: real-time factor"));
  EXPECT_THAT(out, ::testing::HasSubstr("best of: runs per point"));
  EXPECT_THAT(out, ::testing::HasSubstr("overhead us/foll/step: (full - bare wall time)"));
  EXPECT_THAT(out, ::testing::HasSubstr("compose s: wall time of composing and compiling"));
  EXPECT_THAT(out, ::testing::Not(::testing::HasSubstr("ratio full/bare")));
  const auto j = nlohmann::json::parse(ReadFile(dir + "/b.json"));
  EXPECT_EQ(j["contacts"], false);
  EXPECT_EQ(j["experiment"], exp);
  EXPECT_EQ(j["duration_s"], 0.02);
  EXPECT_EQ(j["timestep_s"], 0.001);
  EXPECT_EQ(j["rotor_model"], "actuator");
  ASSERT_EQ(j["points"].size(), 2u);
  for (int k = 0; k < 2; ++k) {
    const auto& p = j["points"][k];
    EXPECT_EQ(p["followers"], k + 1);
    EXPECT_EQ(p["steps"].get<double>(), 20.0);
    const double bare = p["bare_wall_s"], full = p["full_wall_s"];
    EXPECT_GT(bare, 0.0);
    EXPECT_GT(full, 0.0);
    EXPECT_DOUBLE_EQ(p["ratio_full_over_bare"].get<double>(), full / bare);
    EXPECT_DOUBLE_EQ(p["pipeline_us_per_follower_step"].get<double>(),
                     (full - bare) / 20.0 / (k + 1) * 1e6);
    EXPECT_DOUBLE_EQ(p["real_time_factor_full"].get<double>(), 0.02 / full);
    EXPECT_GT(p["peak_rss_mib_full"].get<double>(), 1.0);
    EXPECT_DOUBLE_EQ(p["peak_rss_kib_full_per_vehicle"].get<double>(),
                     p["peak_rss_mib_full"].get<double>() * 1024.0 / (k + 2));
    EXPECT_GT(p["compose_s"].get<double>(), 0.0);
    EXPECT_GE(p["best_of"].get<int>(), 1);
  }
  EXPECT_DOUBLE_EQ(j["per_follower_cost_growth"].get<double>(),
                   j["points"][1]["pipeline_us_per_follower_step"].get<double>() /
                       j["points"][0]["pipeline_us_per_follower_step"].get<double>());
}

// With an estimator configured, one line compares it with passthrough on the same
// suite; its ratio is a positive finite number (no timing threshold: the machine is shared).
TEST(BenchTest, EstimatorCostLine) {
  const std::string dir = TempDir("bench_est");
  const std::string exp =
      WriteFile(dir + "/e.toml",
                HoverExperiment(1, 0.2) +  // longer than the 0.11 s GNSS latency
                    "[sensors]\npreset = \"consumer_gnss\"\n[estimator]\nplugin = \"kf_ins\"\n");
  ::testing::internal::CaptureStdout();
  const int code = Cli({"bench", exp, "--json", dir + "/b.json"});
  const std::string out = ::testing::internal::GetCapturedStdout();
  ASSERT_EQ(code, 0);
  const size_t at = out.find("ratio kf_ins/passthrough ");
  ASSERT_NE(at, std::string::npos) << out;
  EXPECT_EQ(out.rfind("estimator: 1 followers, kf_ins ", at), out.rfind('\n', at) + 1) << out;
  const double ratio = std::stod(out.substr(at + std::strlen("ratio kf_ins/passthrough ")));
  EXPECT_TRUE(std::isfinite(ratio));
  EXPECT_GT(ratio, 0.0);
  const auto j = nlohmann::json::parse(ReadFile(dir + "/b.json"));
  EXPECT_EQ(j["estimator"]["estimator"], "kf_ins");
  EXPECT_DOUBLE_EQ(j["estimator"]["ratio_estimator_over_passthrough"].get<double>(),
                   j["estimator"]["steps_per_s_estimator"].get<double>() /
                       j["estimator"]["steps_per_s_passthrough"].get<double>());
  const double share = j["estimator"]["estimator_share_of_run"].get<double>();
  const double models = j["estimator"]["sensor_models_share_of_run"].get<double>();
  EXPECT_GT(share, 0.0);
  EXPECT_GT(models, 0.0);
  EXPECT_LT(share + models, 1.0);  // two parts of one run's wall time
  EXPECT_NE(out.find("the estimator plugins took "), std::string::npos) << out;
}

// Without an estimator the line is absent (the default bench prints what it printed before).
TEST(BenchTest, NoEstimatorLineWithPassthrough) {
  const std::string dir = TempDir("bench_noest");
  const std::string exp = WriteFile(dir + "/e.toml", HoverExperiment(1, 0.02));
  ::testing::internal::CaptureStdout();
  const int code = Cli({"bench", exp});
  const std::string out = ::testing::internal::GetCapturedStdout();
  ASSERT_EQ(code, 0);
  EXPECT_EQ(out.find("estimator:"), std::string::npos) << out;
}

// With per-agent execution configured, one line compares its cost per step with
// central mode's on the same experiment (no timing threshold: the machine is shared; the target
// is printed beside the ratio), and both runs' sigma_f are kept.
TEST(BenchTest, PerAgentExecutionCostLine) {
  const std::string dir = TempDir("bench_exec");
  const std::string exp = std::string(MJF_SOURCE_DIR) + "/experiments/exp2.toml";
  ::testing::internal::CaptureStdout();
  const int code =
      Cli({"bench", exp, "--duration", "0.3", "--set", "vehicles.model=\"pointmass\"", "--set",
           "attitude={plugin=\"pointmass_direct\"}", "--set",
           "execution={mode=\"per_agent\",coupling=\"central_solve\",predict=\"input\"}", "--json",
           dir + "/b.json"});
  const std::string out = ::testing::internal::GetCapturedStdout();
  ASSERT_EQ(code, 0);
  const std::string key = "cost per step per_agent/central ";
  const size_t at = out.find(key);
  ASSERT_NE(at, std::string::npos) << out;
  EXPECT_EQ(
      out.rfind("execution: 6 followers, per_agent (coupling central_solve, predict input) ", at),
      out.rfind('\n', at) + 1)
      << out;
  EXPECT_NE(out.find("(target <= 1.3)", at), std::string::npos) << out;
  const double printed = std::stod(out.substr(at + key.size()));
  const auto j = nlohmann::json::parse(ReadFile(dir + "/b.json"))["execution"];
  const double ratio = j["cost_ratio_per_agent_over_central"].get<double>();
  EXPECT_TRUE(std::isfinite(ratio));
  EXPECT_GT(ratio, 0.0);
  EXPECT_DOUBLE_EQ(
      ratio, j["steps_per_s_central"].get<double>() / j["steps_per_s_per_agent"].get<double>());
  EXPECT_NEAR(printed, ratio, 5e-4);  // printed with three decimals
  EXPECT_EQ(j["coupling"], "central_solve");
  EXPECT_EQ(j["predict"], "input");
  // The messages the per-agent run sent: every one of Exp 2's 13 links (the ring's 12 and the
  // leader's) carries each broadcast, so the count is a multiple of 13; what the cost per
  // message divides by.
  const int64_t sent = j["messages_sent"].get<int64_t>();
  EXPECT_GT(sent, 0);
  EXPECT_EQ(sent % 13, 0) << sent;
  EXPECT_LE(j["messages_delivered"].get<int64_t>(), sent);
  EXPECT_GT(j["messages_delivered"].get<int64_t>(), 0);
  EXPECT_TRUE(std::isfinite(j["extra_us_per_message"].get<double>()));
  char per_step[64];
  std::snprintf(per_step, sizeof(per_step), "%.0f messages sent per step", sent / 300.0);
  EXPECT_NE(out.find(per_step, at), std::string::npos) << out;
  // Both flights really ran Exp 2: a finite formation error each.
  EXPECT_TRUE(std::isfinite(j["sigma_f_mean_per_agent"].get<double>()));
  EXPECT_TRUE(std::isfinite(j["sigma_f_mean_central"].get<double>()));
}

// Central mode prints no execution line. The header gives the duration as benched, every digit
// (a fixed one decimal showed 0.05 s as 0.1 s).
TEST(BenchTest, NoExecutionLineInCentralMode) {
  ::testing::internal::CaptureStdout();
  const int code =
      Cli({"bench", std::string(MJF_SOURCE_DIR) + "/experiments/exp2.toml", "--duration", "0.05"});
  const std::string out = ::testing::internal::GetCapturedStdout();
  ASSERT_EQ(code, 0);
  EXPECT_EQ(out.find("execution:"), std::string::npos) << out;
  EXPECT_NE(out.find("exp2.toml: 0.05 s at "), std::string::npos) << out;
}

TEST(BenchTest, BadInputIsExitCodeOne) {
  const std::string dir = TempDir("bench_bad");
  EXPECT_EQ(Cli({"bench", dir + "/missing.toml"}), 1);
  const std::string exp = WriteFile(dir + "/e.toml", HoverExperiment(1, 0.02));
  EXPECT_EQ(Cli({"bench", exp, "--set", "run.nosuchkey=1"}), 1);
  EXPECT_FALSE(std::filesystem::exists(dir + "/b.json"));
}

// bench --json never replaces a file of the user's: refused before the bench runs (exit 1), the
// file's bytes kept; a new name is written.
TEST(BenchTest, AnExistingJsonFileIsNeverReplaced) {
  const std::string dir = TempDir("bench_json_keep");
  const std::string exp = WriteFile(dir + "/e.toml", HoverExperiment(1, 0.02));
  const std::string mine = WriteFile(dir + "/mine.json", "the user's figures\n");
  EXPECT_EQ(Cli({"bench", exp, "--json", mine}), 1);
  EXPECT_EQ(mjf::testing::ReadFile(mine), "the user's figures\n");
  EXPECT_EQ(Cli({"bench", exp, "--json", dir + "/new.json"}), 0);
  EXPECT_TRUE(std::filesystem::exists(dir + "/new.json"));
}

// The JSON is written after the bench: a folder it cannot go into is refused before the bench
// runs (nothing printed on stdout), naming the folder, rather than after minutes of work.
struct Outcome {
  int code;
  std::string out, err;
};
Outcome BenchOutcome(const std::vector<std::string>& args) {
  ::testing::internal::CaptureStdout();
  ::testing::internal::CaptureStderr();
  const int code = Cli(args);
  std::string err = ::testing::internal::GetCapturedStderr();
  return {code, ::testing::internal::GetCapturedStdout(), err};
}

TEST(BenchTest, AJsonFileInAMissingOrReadOnlyFolderIsRefusedFirst) {
  const std::string dir = TempDir("bench_json_folder");
  const std::string exp = WriteFile(dir + "/e.toml", HoverExperiment(1, 0.02));
  Outcome r = BenchOutcome({"bench", exp, "--json", dir + "/none/b.json"});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, ::testing::HasSubstr("b.json: the folder " + dir + "/none does not exist"));
  EXPECT_EQ(r.out, "");
  std::filesystem::create_directory(dir + "/locked");
  std::filesystem::permissions(
      dir + "/locked", std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
  if (access((dir + "/locked").c_str(), W_OK) != 0) {  // root may write anyway
    r = BenchOutcome({"bench", exp, "--json", dir + "/locked/b.json"});
    EXPECT_EQ(r.code, 1);
    EXPECT_THAT(r.err, ::testing::HasSubstr("the folder " + dir + "/locked is not writable"));
    EXPECT_EQ(r.out, "");
  }
  EXPECT_FALSE(std::filesystem::exists(dir + "/locked/b.json"));
}

}  // namespace
}  // namespace mjf::runner
