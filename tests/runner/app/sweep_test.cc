// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Monte Carlo sweeps: --seeds statistics, interrupted sweeps, --resume.
#include "../../../runner/app/src/sweep.hpp"  // private to the app stage: the tables' functions

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <csignal>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "mjformation/app/cli.hpp"
#include "mjformation/app/sweep_stats.hpp"
#include "mjformation/run/interrupt.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

using mjf::testing::HoverExperiment;
using mjf::testing::ReadFile;
using mjf::testing::TempDir;
using mjf::testing::WriteFile;
using ::testing::HasSubstr;

using mjf::testing::Cli;

TEST(SweepStats, StudentQuantilesAgainstTables) {
  EXPECT_NEAR(StudentT975(1), 12.7062, 1e-4);
  EXPECT_NEAR(StudentT975(10), 2.2281, 1e-4);
  EXPECT_NEAR(StudentT975(19), 2.0930, 1e-4);
  // Beyond the table: the expansion against tabulated values.
  EXPECT_NEAR(StudentT975(40), 2.0211, 2e-4);
  EXPECT_NEAR(StudentT975(60), 2.0003, 2e-4);
  EXPECT_NEAR(StudentT975(120), 1.9799, 2e-4);
  EXPECT_NEAR(StudentT975(100000), 1.95996, 1e-4);
}

TEST(SweepStats, MeanStdAndInterval) {
  const SampleStats s = Describe({1, 2, 3, 4});
  EXPECT_EQ(s.n, 4);
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_NEAR(s.std, std::sqrt(5.0 / 3.0), 1e-12);
  EXPECT_NEAR(s.ci95_high - s.mean, 3.1824 * std::sqrt(5.0 / 3.0) / 2, 1e-4);
  EXPECT_NEAR(s.mean - s.ci95_low, s.ci95_high - s.mean, 1e-12);
  EXPECT_TRUE(std::isnan(Describe({7}).std));
  EXPECT_TRUE(std::isnan(Describe({}).mean));
}

std::string Experiment(const std::string& dir) {
  // start_jitter makes every seed a different run.
  std::string text = HoverExperiment(1, 0.3);
  text.insert(text.find("leader_start"), "start_jitter = 0.5\n");
  return WriteFile(dir + "/e.toml", text);
}

TEST(SweepSeeds, PerCellStatisticsOverSeeds) {
  const std::string dir = TempDir("seeds");
  const std::string exp = Experiment(dir);
  ASSERT_EQ(Cli({"sweep", exp, "--vary", "vehicles.altitude=2.0,3.0", "--seeds", "3", "--out",
                 dir + "/s", "--no-render"}),
            0);
  const auto json = nlohmann::json::parse(ReadFile(dir + "/s/sweep.json"));
  EXPECT_TRUE(json["complete"].get<bool>());
  ASSERT_EQ(json["runs"].size(), 6u);
  ASSERT_EQ(json["cells"].size(), 2u);
  // Seeds are the config's seed (1) + 0, 1, 2, recorded in each run.
  for (int k = 0; k < 3; ++k) {
    const auto summary = nlohmann::json::parse(
        ReadFile(dir + "/s/altitude=3.0,seed=" + std::to_string(1 + k) + "/summary.json"));
    EXPECT_EQ(summary["seed"], 1 + k);
  }
  // The cell's statistics, recomputed here from the runs' own summaries.
  std::vector<double> v;
  for (int k = 1; k <= 3; ++k) {
    v.push_back(nlohmann::json::parse(ReadFile(dir + "/s/altitude=2.0,seed=" + std::to_string(k) +
                                               "/summary.json"))["metrics"]["min_separation_m"]
                    .get<double>());
  }
  ASSERT_NE(v[0], v[1]);  // seeds matter
  const double mean = (v[0] + v[1] + v[2]) / 3;
  double var = 0;
  for (double x : v) var += (x - mean) * (x - mean) / 2;
  const auto& cell = json["cells"][0]["metrics"]["min_separation_m"];
  EXPECT_EQ(cell["n"], 3);
  EXPECT_NEAR(cell["mean"].get<double>(), mean, 1e-12);
  EXPECT_NEAR(cell["std"].get<double>(), std::sqrt(var), 1e-12);
  EXPECT_NEAR(cell["ci95"][1].get<double>() - mean, 4.3027 * std::sqrt(var / 3), 1e-4);
  const std::string csv = ReadFile(dir + "/s/sweep.csv");
  EXPECT_THAT(csv, HasSubstr("vehicles.altitude,seeds,complete_runs,"));
  EXPECT_THAT(csv, HasSubstr("min_separation_m_mean,min_separation_m_std,"
                             "min_separation_m_ci95_low,min_separation_m_ci95_high"));
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 2);
  EXPECT_THAT(ReadFile(dir + "/s/sweep_runs.csv"), HasSubstr("2.0,2,true,"));
  // --seeds 0 is refused before anything runs (a usage error: out of [1, 100000]).
  EXPECT_EQ(Cli({"sweep", exp, "--seeds", "0", "--out", dir + "/zero"}), 2);  // usage
  EXPECT_EQ(Cli({"sweep", exp, "--out", dir + "/nothing"}), 1);  // neither --vary nor --seeds
}

// A flip, ground impact or collision leaves a run out of the cell statistics; a near miss (Exp 2's
// start ring under turbulence gives every run one) is reported and kept. Three runs of one cell:
// sigma_f 1 (no event), 2 (a near miss), 10 (a flip): the valid statistics are over 1 and 2, and
// the tables and the summary say that one run was left out and why.
TEST(SweepSeeds, NearMissesAreKeptAndFlipsLeftOut) {
  sweep::SweepPlan plan;
  plan.out = TempDir("valid");
  plan.axes.push_back({"formation.q", {"1.0"}});
  plan.cells = {{0}};
  plan.seeds = 3;
  std::vector<sweep::RunOutcome> outcomes(3);
  const double sigma[] = {1.0, 2.0, 10.0};
  const char* kind[] = {"", "near_miss", "flip"};
  for (int k = 0; k < 3; ++k) {
    sweep::RunSpec run;
    run.cell = 0;
    run.seed = 1 + k;
    run.name = "q=1.0,seed=" + std::to_string(1 + k);
    plan.runs.push_back(run);
    outcomes[k].state = sweep::RunOutcome::kFinished;
    outcomes[k].summary = {{"complete", true}, {"metrics", {{"sigma_f_mean", sigma[k]}}}};
    if (*kind[k]) {
      sweep::Json by_kind = {{"flip", 0},
                             {"ground_impact", 0},
                             {"collision", 0},
                             {"near_miss", 0},
                             {"left_region", 0}};
      by_kind[kind[k]] = 1;
      outcomes[k].summary["events"] = {
          {"count", 1},
          {"by_kind", by_kind},
          {"list", {{{"kind", kind[k]}, {"what", std::string("follower 1 ") + kind[k]}}}}};
    }
  }
  sweep::WriteTables(plan, outcomes);
  const auto json = nlohmann::json::parse(ReadFile(plan.out + "/sweep.json"));
  const auto& cell = json["cells"][0];
  EXPECT_EQ(cell["runs_with_safety_events"], 2);
  EXPECT_EQ(cell["runs_left_out"], 1);
  EXPECT_EQ(cell["valid_complete_runs"], 2);
  EXPECT_EQ(cell["metrics_valid"]["sigma_f_mean"]["n"], 2);
  EXPECT_DOUBLE_EQ(cell["metrics_valid"]["sigma_f_mean"]["mean"].get<double>(), 1.5);
  EXPECT_EQ(cell["metrics"]["sigma_f_mean"]["n"], 3);
  EXPECT_EQ(json["left_out_events"], nlohmann::json({"flip", "ground_impact", "collision"}));
  EXPECT_EQ(json["runs"][1]["invalidating_events"], 0);
  EXPECT_EQ(json["runs"][2]["invalidating_events"], 1);
  const std::string csv = ReadFile(plan.out + "/sweep.csv");
  EXPECT_THAT(csv, HasSubstr("seeds,runs_with_safety_events,runs_left_out,statistics_over,runs,"));
  EXPECT_THAT(csv, HasSubstr("1.0,3,2,1,valid_runs,2,1.5,"));
  const std::string text = sweep::SummaryText(plan, outcomes);
  // sigma_f >= 0: the t interval over {1, 2}, 1.5 -+ 12.7062 * 0.7071 / sqrt(2) = [-4.853,
  // 7.853], is cut at 0, and the summary and sweep.json say how the interval was made.
  EXPECT_THAT(text, HasSubstr("sigma_f_mean 1.5, 95 % CI [0, 7.853] over 2 runs (Student t, cut "
                              "at 0)"));
  EXPECT_EQ(cell["metrics_valid"]["sigma_f_mean"]["ci95"][0].get<double>(), 0.0);
  EXPECT_THAT(json["ci95_method"].get<std::string>(), HasSubstr("Student t"));
  EXPECT_THAT(csv, HasSubstr("1.0,3,2,1,valid_runs,2,1.5,0.707107,0,7.8531"));
  EXPECT_THAT(text, HasSubstr("1 of 3 complete runs left out (a flip, ground impact or collision"));
  EXPECT_THAT(text, HasSubstr("; 1 run with near misses or region exits only (reported, kept)"));
}

// A comma inside a TOML string does not split, whichever its quotes: a literal string '...'
// (no escapes; a " inside is a plain character) and a basic string with an escaped quote.
TEST(SweepSeeds, CommasInsideTomlStringsDoNotSplit) {
  using Values = std::vector<std::string>;
  EXPECT_EQ(sweep::ParseAxis("run.name='a,b','c'").values, (Values{"'a,b'", "'c'"}));
  EXPECT_EQ(sweep::ParseAxis("run.name='say \"hi, there','c'").values,
            (Values{"'say \"hi, there'", "'c'"}));
  EXPECT_EQ(sweep::ParseAxis(R"(run.name="a\",b","c")").values, (Values{R"("a\",b")", R"("c")"}));
  EXPECT_EQ(sweep::ParseAxis(R"(run.name="it's,x","y")").values, (Values{R"("it's,x")", R"("y")"}));
  try {
    sweep::ParseAxis("run.name='a,b");
    ADD_FAILURE() << "an unterminated literal string was accepted";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("--vary 'run.name='a,b': unbalanced [ { or a string's quote"));
  }
}

// Values with commas inside [], {} or quotes are one value; the CSV quotes them.
TEST(SweepSeeds, TableAndArrayValuesOnAnAxis) {
  const std::string dir = TempDir("axis");
  const std::string exp = Experiment(dir);
  ASSERT_EQ(Cli({"sweep", exp, "--vary", "wind.mean=[0.0,0.0,0.0],[2.0,0.0,0.0]", "--vary",
                 "sensors={preset=\"ideal\"},{preset=\"typical\", scale=3.0}", "--seeds", "2",
                 "--out", dir + "/s", "--no-render"}),
            0);
  const std::string csv = ReadFile(dir + "/s/sweep.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 4);
  EXPECT_THAT(csv, HasSubstr("\n\"[2.0,0.0,0.0]\",\"{preset=\"\"typical\"\", scale=3.0}\",2,2,"));
  // Readable and shell-safe folder names: no brackets, commas inside values written '_'.
  const std::string name = "mean=2.0_0.0_0.0,sensors={preset=typical_scale=3.0},seed=2";
  const auto summary = nlohmann::json::parse(ReadFile(dir + "/s/" + name + "/summary.json"));
  EXPECT_EQ(summary["sensors"]["scale"], 3.0);
  EXPECT_EQ(summary["wind"]["mean"][0], 2.0);
  // A sweep written with the older %XX names resumes: its finished runs are found, not rerun.
  std::filesystem::rename(
      dir + "/s/" + name,
      dir + "/s/mean=%5B2.0%2C0.0%2C0.0%5D,sensors={preset=typical%2Cscale=3.0},seed=2");
  const auto before = ReadFile(dir +
                               "/s/mean=%5B2.0%2C0.0%2C0.0%5D,sensors={preset=typical%2C"
                               "scale=3.0},seed=2/summary.json");
  ::testing::internal::CaptureStderr();
  ASSERT_EQ(Cli({"sweep", exp, "--vary", "wind.mean=[0.0,0.0,0.0],[2.0,0.0,0.0]", "--vary",
                 "sensors={preset=\"ideal\"},{preset=\"typical\", scale=3.0}", "--seeds", "2",
                 "--out", dir + "/s", "--no-render", "--resume"}),
            0);
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_THAT(err, HasSubstr("resuming, 8 of 8 runs done before")) << err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/s/" + name));
  EXPECT_EQ(ReadFile(dir + "/s/mean=%5B2.0%2C0.0%2C0.0%5D,sensors={preset=typical%2Cscale=3.0},"
                           "seed=2/summary.json"),
            before);
  EXPECT_EQ(Cli({"sweep", exp, "--vary", "wind.mean=[1.0,0.0", "--out", dir + "/bad"}), 1);
}

// Readable run folders (key=value,seed=N), plain values in the tables (none, not """none"""),
// the run column quoted as RFC 4180 wants when the name holds a comma.
TEST(SweepSeeds, ReadableNamesAndPlainValues) {
  const std::string dir = TempDir("names");
  const std::string exp = Experiment(dir);
  ASSERT_EQ(Cli({"sweep", exp, "--vary", "wind.turbulence=\"none\",\"light\"", "--set",
                 "wind.altitude=10.0", "--seeds", "2", "--out", dir + "/s", "--no-render"}),
            0);
  EXPECT_EQ(
      nlohmann::json::parse(ReadFile(dir + "/s/turbulence=light,seed=2/summary.json"))["seed"], 2);
  const std::string cells = ReadFile(dir + "/s/sweep.csv");
  EXPECT_THAT(cells, HasSubstr("\nnone,2,2,"));
  EXPECT_THAT(cells, HasSubstr("\nlight,2,2,"));
  EXPECT_THAT(cells, ::testing::Not(HasSubstr("\"")));
  const std::string runs = ReadFile(dir + "/s/sweep_runs.csv");
  EXPECT_THAT(runs, HasSubstr(",\"turbulence=none,seed=1\","));
  // sweep.json keeps the exact TOML text of the value (what config.toml holds).
  const auto json = nlohmann::json::parse(ReadFile(dir + "/s/sweep.json"));
  EXPECT_EQ(json["runs"][0]["wind.turbulence"], "\"none\"");
  EXPECT_EQ(json["runs"][0]["run"], "turbulence=none,seed=1");
}

// An interrupted sweep marks what did not run, tables complete = false; --resume finishes it
// and gives the bytes of an uninterrupted sweep; it reruns only missing or changed runs.
TEST(SweepResume, InterruptedThenResumedGivesTheUninterruptedBytes) {
  const std::string dir = TempDir("resume");
  const std::string exp = Experiment(dir);
  const std::vector<std::string> args = {"sweep", exp, "--seeds", "4", "--no-render", "-j", "2"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> a = args;
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  ASSERT_EQ(Cli(with({"--out", dir + "/whole"})), 0);

  RequestInterrupt(SIGINT);  // as if Ctrl-C came before any run started
  EXPECT_EQ(Cli(with({"--out", dir + "/cut"})), 128 + SIGINT);
  ClearInterrupt();
  const auto cut = nlohmann::json::parse(ReadFile(dir + "/cut/sweep.json"));
  EXPECT_FALSE(cut["complete"].get<bool>());
  EXPECT_THAT(ReadFile(dir + "/cut/sweep_runs.csv"), HasSubstr("false,,,,,,,,seed=1,not run"));
  EXPECT_EQ(Cli(with({"--out", dir + "/cut"})), 1);  // exists: needs --resume or --overwrite
  ASSERT_EQ(Cli(with({"--out", dir + "/cut", "--resume"})), 0);
  for (const char* f : {"sweep.csv", "sweep_runs.csv", "sweep.json"}) {
    EXPECT_EQ(ReadFile(dir + "/whole/" + f), ReadFile(dir + "/cut/" + f)) << f;
  }

  // A run killed before its summary.json, and one made for another configuration, are rerun;
  // the others are kept as they are.
  std::remove((dir + "/cut/seed=2/summary.json").c_str());
  std::string other = ReadFile(dir + "/cut/seed=3/summary.json");
  other.replace(other.find("\"config_sha256\": \"") + 18, 4, "0000");
  WriteFile(dir + "/cut/seed=3/summary.json", other);
  struct stat before {};
  stat((dir + "/cut/seed=4/summary.json").c_str(), &before);
  const std::string kept = ReadFile(dir + "/cut/seed=4/summary.json");
  ASSERT_EQ(Cli(with({"--out", dir + "/cut", "--resume"})), 0);
  EXPECT_EQ(ReadFile(dir + "/cut/seed=4/summary.json"), kept);  // not rerun: timing unchanged
  EXPECT_NE(ReadFile(dir + "/cut/seed=3/summary.json"), other);
  for (const char* f : {"sweep.csv", "sweep_runs.csv", "sweep.json"}) {
    EXPECT_EQ(ReadFile(dir + "/whole/" + f), ReadFile(dir + "/cut/" + f)) << f;
  }
}

// An output folder that cannot be made is refused before any run (a file stands in its way:
// this works even as root, who may write anywhere).
TEST(SweepResume, UnwritableOutputIsAClearError) {
  const std::string dir = TempDir("ro");
  const std::string exp = Experiment(dir);
  EXPECT_EQ(Cli({"sweep", exp, "--seeds", "2", "--out", exp + "/s", "--no-render"}), 1);
  EXPECT_EQ(ReadFile(exp + "/s/sweep.csv"), "");
}

}  // namespace
}  // namespace mjf::runner
