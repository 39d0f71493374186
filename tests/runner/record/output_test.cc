// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// timeseries.csv's byte promise: the fast number formatter gives exactly std::to_chars'
// (general, 9 significant digits) bytes, on random bit patterns, near-ties, powers of ten and
// their neighbours, and the magnitudes a run records.
//
// Unit tests of the source:
// runner/record/src/output.cc: the run directory (what --overwrite may and may not delete), atomic
// small files, the timeseries header and its error paths, the config echo and its hash.
#include "mjformation/record/output.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <random>
#include <string>

#include "error_of.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

std::string Reference(double v) {
  char buf[64];
  return std::string(buf,
                     std::to_chars(buf, buf + sizeof(buf), v, std::chars_format::general, 9).ptr);
}
std::string Fast(double v) {
  char buf[64];
  return std::string(buf, FormatG9(buf, buf + sizeof(buf), v));
}

TEST(FormatG9Test, MatchesToCharsOnRandomBitPatterns) {
  std::mt19937_64 rng(20261201);
  int checked = 0;
  for (int k = 0; k < 2000000; ++k) {
    const uint64_t bits = rng();
    double v;
    std::memcpy(&v, &bits, sizeof(v));
    if (!std::isfinite(v)) continue;
    ASSERT_EQ(Fast(v), Reference(v)) << "bits " << bits;
    ++checked;
  }
  EXPECT_GT(checked, 1900000);
}

TEST(FormatG9Test, MatchesToCharsOnRecordedMagnitudes) {
  // Positions, velocities, angles, sliding variables: |v| in [1e-12, 1e4], both signs.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> exponent(-12, 4), mantissa(1, 10);
  for (int k = 0; k < 2000000; ++k) {
    const double v = (k % 2 ? -1 : 1) * mantissa(rng) * std::pow(10.0, std::floor(exponent(rng)));
    ASSERT_EQ(Fast(v), Reference(v)) << v;
  }
}

TEST(FormatG9Test, MatchesToCharsOnTiesPowersOfTenAndTheirNeighbours) {
  for (int e = -20; e <= 20; ++e) {
    const double p = std::pow(10.0, e);
    for (double v : {p, std::nextafter(p, 0.0), std::nextafter(p, 1e300), -p}) {
      ASSERT_EQ(Fast(v), Reference(v)) << v;
    }
    // Near-ties at the 9th significant digit: d.dddddddd5 x 10^e and its neighbours.
    for (int d = 0; d < 1000; ++d) {
      const double tie = (1.000000005 + d * 1.37e-6) * p;
      for (double v : {tie, std::nextafter(tie, 0.0), std::nextafter(tie, 1e300)}) {
        ASSERT_EQ(Fast(v), Reference(v)) << v;
      }
    }
  }
  // 1 to 9 significant digits (the trailing zeros "%g" drops) at every decimal exponent the fast
  // path takes, in each layout (0.000ddd, ddd.ddd, d.ddde+XX), with the room the writer gives
  // and the least room the fast path takes (less goes to std::to_chars).
  std::mt19937_64 rng(11);
  for (int e = -13; e <= 14; ++e) {
    for (int digits = 1; digits <= 9; ++digits) {
      for (int k = 0; k < 200; ++k) {
        const double m = std::uniform_int_distribution<int64_t>(
            static_cast<int64_t>(std::pow(10.0, digits - 1)),
            static_cast<int64_t>(std::pow(10.0, digits)) - 1)(rng);
        const double v = (k % 2 ? -1 : 1) * m * std::pow(10.0, e - digits + 1);
        for (size_t room : {size_t{24}, size_t{23}}) {
          char buf[24];
          ASSERT_EQ(std::string(buf, FormatG9(buf, buf + room, v)), Reference(v)) << v;
        }
      }
    }
  }
  for (double v : {0.0, -0.0, std::numeric_limits<double>::min(),
                   std::numeric_limits<double>::max(), std::numeric_limits<double>::denorm_min()}) {
    EXPECT_EQ(Fast(v), Reference(v)) << v;
  }
}

namespace fs = std::filesystem;
using mjf::testing::ReadFile;
using mjf::testing::TempDir;
using mjf::testing::WriteFile;
using ::testing::AllOf;
using ::testing::HasSubstr;

std::string OutputErrorOf(const std::function<void()>& f) {
  return mjf::testing::ErrorOf<OutputError>(f, "(nothing thrown)");
}

TEST(OutputTest, Sha256OfKnownTexts) {
  // FIPS 180-2 test vectors.
  EXPECT_EQ(Sha256Hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(Sha256Hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST(OutputTest, JsonNumberIsNullForNonFinite) {
  EXPECT_EQ(JsonNumber(1.25).dump(), "1.25");
  EXPECT_TRUE(JsonNumber(std::numeric_limits<double>::quiet_NaN()).is_null());
  EXPECT_TRUE(JsonNumber(std::numeric_limits<double>::infinity()).is_null());
  EXPECT_TRUE(JsonNumber(-std::numeric_limits<double>::infinity()).is_null());
}

TEST(OutputTest, ConfigEchoNamesTheFileAloneAndTheOverrides) {
  ExperimentConfig c;
  c.source_path = "/home/someone/experiments/exp2.toml";
  c.source_text = "[run]\nname = \"x\"\n";
  EXPECT_EQ(ConfigEcho(c),
            "# Experiment file exp2.toml as run by mjformation.\n[run]\nname = \"x\"\n");
  c.overrides = {"run.seed=3", "formation.rho=0.1"};
  c.effective_text = "merged\n";
  EXPECT_EQ(ConfigEcho(c),
            "# Experiment file exp2.toml as run by mjformation.\n# with --set run.seed=3\n"
            "# with --set formation.rho=0.1\nmerged\n");
  // No override's text can end the comment and become a line of TOML.
  c.overrides = {"run.seed=7\nduration=0.2\r\x01"};
  EXPECT_EQ(ConfigEcho(c),
            "# Experiment file exp2.toml as run by mjformation.\n"
            "# with --set run.seed=7\\nduration=0.2\\r\\x01\nmerged\n");
  // A path without a folder.
  c.source_path = "bare.toml";
  c.overrides.clear();
  EXPECT_EQ(ConfigEcho(c).substr(0, 39), "# Experiment file bare.toml as run by m");
}

TEST(OutputTest, ANewRunDirectoryHasItsMarkerAndSnapshotsFolder) {
  const std::string dir = TempDir("out_new") + "/a/b";  // parents are made too
  RunDirectory run(dir, false);
  EXPECT_TRUE(fs::is_directory(dir + "/snapshots"));
  EXPECT_THAT(ReadFile(dir + "/.mjformation-run"), HasSubstr("mjformation run directory"));
  EXPECT_EQ(run.Path("summary.json"), dir + "/summary.json");
}

TEST(OutputTest, WriteTextIsWholeAndLeavesNoTemporary) {
  const std::string dir = TempDir("out_write");
  RunDirectory run(dir, false);
  run.WriteText("summary.json", "{}\n");
  run.WriteText("summary.json", "{\"a\": 1}\n");  // replaces
  EXPECT_EQ(ReadFile(dir + "/summary.json"), "{\"a\": 1}\n");
  EXPECT_FALSE(fs::exists(dir + "/summary.json.tmp"));
  EXPECT_THAT(OutputErrorOf([&] { run.WriteText("no/such/folder.txt", "x"); }),
              HasSubstr(dir + "/no/such/folder.txt.tmp: cannot write: No such file or directory"));
}

TEST(OutputTest, RefusesAFileAndANonEmptyDirectoryWithoutOverwrite) {
  const std::string base = TempDir("out_refuse");
  const std::string file = WriteFile(base + "/plain", "mine");
  EXPECT_THAT(OutputErrorOf([&] { RunDirectory(file, true); }),
              HasSubstr(file + ": exists and is not a directory"));
  const std::string dir = base + "/run";
  fs::create_directories(dir);
  WriteFile(dir + "/timeseries.csv", "old");
  EXPECT_THAT(OutputErrorOf([&] { RunDirectory(dir, false); }),
              AllOf(HasSubstr("exists and is not empty"), HasSubstr("--overwrite")));
  EXPECT_EQ(ReadFile(dir + "/timeseries.csv"), "old");
}

TEST(OutputTest, OverwriteNeedsTheMarkerAndDeletesNothingOtherwise) {
  const std::string dir = TempDir("out_nomarker");
  WriteFile(dir + "/timeseries.csv", "someone's");
  EXPECT_THAT(
      OutputErrorOf([&] { RunDirectory(dir, true); }),
      AllOf(HasSubstr("not a mjformation run directory"), HasSubstr("nothing was deleted")));
  EXPECT_EQ(ReadFile(dir + "/timeseries.csv"), "someone's");
}

TEST(OutputTest, OverwriteRefusesForeignFilesAndDeletesNothing) {
  const std::string dir = TempDir("out_foreign");
  { RunDirectory first(dir, false); }
  WriteFile(dir + "/timeseries.csv", "run");
  WriteFile(dir + "/notes.txt", "the user's");
  fs::create_directories(dir + "/analysis");
  EXPECT_THAT(OutputErrorOf([&] { RunDirectory(dir, true); }),
              AllOf(HasSubstr("holds files mjformation did not write ("), HasSubstr("analysis"),
                    HasSubstr("notes.txt"), HasSubstr("nothing was deleted")));
  EXPECT_EQ(ReadFile(dir + "/timeseries.csv"), "run");
  EXPECT_EQ(ReadFile(dir + "/notes.txt"), "the user's");
}

TEST(OutputTest, OverwriteRefusesLinksAndFoldersInsideSnapshots) {
  const std::string dir = TempDir("out_links");
  const std::string outside = TempDir("out_links_target");
  WriteFile(outside + "/precious.png", "keep");
  { RunDirectory first(dir, false); }
  fs::create_symlink(outside + "/precious.png", dir + "/snapshots/t001.00.png");
  EXPECT_THAT(OutputErrorOf([&] { RunDirectory(dir, true); }),
              HasSubstr("(snapshots/t001.00.png)"));
  fs::remove(dir + "/snapshots/t001.00.png");
  fs::create_symlink(outside, dir + "/figures");
  EXPECT_THAT(OutputErrorOf([&] { RunDirectory(dir, true); }), HasSubstr("(figures)"));
  EXPECT_EQ(ReadFile(outside + "/precious.png"), "keep");
}

// Inside snapshots/ and figures/ only the names the runner and analysis/figures.py give their
// pictures are the run's: a user's file there is refused by its path, as at the top level.
TEST(OutputTest, OverwriteRefusesAUsersFileInsideSnapshotsOrFigures) {
  const std::string dir = TempDir("out_foreign_inside");
  { RunDirectory first(dir, false); }
  WriteFile(dir + "/snapshots/t000.50.png", "run");
  WriteFile(dir + "/snapshots/keep_me.txt", "the user's");
  EXPECT_THAT(OutputErrorOf([&] { RunDirectory(dir, true); }),
              AllOf(HasSubstr("holds files mjformation did not write (snapshots/keep_me.txt)"),
                    HasSubstr("nothing was deleted")));
  EXPECT_EQ(ReadFile(dir + "/snapshots/keep_me.txt"), "the user's");
  EXPECT_EQ(ReadFile(dir + "/snapshots/t000.50.png"), "run");
  fs::remove(dir + "/snapshots/keep_me.txt");
  // Near misses of a snapshot's name are not the run's either.
  for (const char* name : {"t0.50.png", "t000.5.png", "tabc.de.png", "t000.50.jpg"}) {
    WriteFile(dir + "/snapshots/" + name, "the user's");
    EXPECT_THAT(OutputErrorOf([&] { RunDirectory(dir, true); }),
                HasSubstr(std::string("(snapshots/") + name + ")"));
    fs::remove(dir + "/snapshots/" + name);
  }
  fs::create_directories(dir + "/figures");
  WriteFile(dir + "/figures/sigma_f.png", "run");
  WriteFile(dir + "/figures/my_plot.png", "the user's");
  EXPECT_THAT(OutputErrorOf([&] { RunDirectory(dir, true); }), HasSubstr("(figures/my_plot.png)"));
  EXPECT_EQ(ReadFile(dir + "/figures/my_plot.png"), "the user's");
  EXPECT_EQ(ReadFile(dir + "/figures/sigma_f.png"), "run");
}

TEST(OutputTest, OverwriteReplacesARunsOwnFiles) {
  const std::string dir = TempDir("out_replace");
  { RunDirectory first(dir, false); }
  for (const char* f : {"config.toml", "scene.xml", "timeseries.csv", "summary.json", "video.mp4",
                        "summary.json.tmp", "snapshots/t001.00.png", "snapshots/t1234.50.png",
                        "snapshots/t002.00.png.tmp"}) {
    WriteFile(dir + "/" + f, "old");
  }
  fs::create_directories(dir + "/figures");
  WriteFile(dir + "/figures/sigma_f.png", "old");
  WriteFile(dir + "/figures/trajectories_xy.png", "old");
  RunDirectory again(dir, true);
  std::vector<std::string> left;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    left.push_back(fs::relative(e.path(), dir).string());
  }
  std::sort(left.begin(), left.end());
  EXPECT_EQ(left, (std::vector<std::string>{".mjformation-run", "snapshots"}));
}

TEST(OutputTest, TimeseriesHeaderColumns) {
  const std::string dir = TempDir("out_header");
  {
    TimeseriesWriter w(dir + "/plain.csv", 1);
    w.Close();
  }
  EXPECT_EQ(ReadFile(dir + "/plain.csv"),
            "t,sigma_f,uav0_px,uav0_py,uav0_pz,uav0_vx,uav0_vy,uav0_vz,uav0_roll,uav0_pitch,"
            "uav0_yaw,uav0_ax_cmd,uav0_ay_cmd,uav0_sx,uav0_sy,uav0_slot_x,uav0_slot_y\n");
  {
    TimeseriesWriter w(dir + "/all.csv", 2, true, true, {"leader_ax", "leader_ay"});
    w.Close();
  }
  const std::string all = ReadFile(dir + "/all.csv");
  // Usual columns of every vehicle first, then measured, then wind, then the extra ones.
  const size_t last_usual = all.find("uav1_slot_y");
  const size_t first_meas = all.find("uav0_px_meas");
  const size_t last_meas = all.find("uav1_yaw_meas");
  const size_t first_wind = all.find("uav0_wind_x");
  const size_t last_wind = all.find("uav1_wind_z");
  const size_t extra = all.find("leader_ax,leader_ay\n");
  ASSERT_NE(extra, std::string::npos);
  EXPECT_LT(last_usual, first_meas);
  EXPECT_LT(last_meas, first_wind);
  EXPECT_LT(last_wind, extra);
  EXPECT_THAT(all,
              HasSubstr(",uav0_px_meas,uav0_py_meas,uav0_pz_meas,uav0_vx_meas,uav0_vy_meas,"
                        "uav0_vz_meas,uav0_roll_meas,uav0_pitch_meas,uav0_yaw_meas,uav1_px_meas"));
  EXPECT_THAT(all, HasSubstr(",uav0_wind_x,uav0_wind_y,uav0_wind_z,uav1_wind_x,uav1_wind_y,"
                             "uav1_wind_z,leader_ax"));
  EXPECT_EQ(std::count(all.begin(), all.end(), ','), 1 + 2 * (15 + 9 + 3) + 2);
}

// The estimate columns come after every _meas column and before the wind.
TEST(OutputTest, TimeseriesHeaderWithEstimateColumns) {
  const std::string dir = TempDir("out_header_est");
  {
    TimeseriesWriter w(dir + "/est.csv", 2, true, true, {}, true);
    w.Close();
  }
  const std::string all = ReadFile(dir + "/est.csv");
  EXPECT_THAT(all, HasSubstr(",uav1_yaw_meas,uav0_px_est,uav0_py_est,uav0_pz_est,uav0_vx_est,"
                             "uav0_vy_est,uav0_vz_est,uav0_px_std,uav0_py_std,uav0_pz_std,"
                             "uav0_vx_std,uav0_vy_std,uav0_vz_std,uav0_nees,uav1_px_est"));
  EXPECT_THAT(all, HasSubstr(",uav1_vz_std,uav1_nees,uav0_wind_x"));
  EXPECT_EQ(std::count(all.begin(), all.end(), ','), 1 + 2 * (15 + 9 + 13 + 3));
}

TEST(OutputTest, TimeseriesWriterErrors) {
  EXPECT_THAT(OutputErrorOf([] { TimeseriesWriter w("/nonexistent_dir_mjf/t.csv", 1); }),
              HasSubstr("/nonexistent_dir_mjf/t.csv: cannot write: No such file or directory"));
  // A full disk: Close() is the checked path and says so ...
  TimeseriesWriter full("/dev/full", 1);
  EXPECT_THAT(OutputErrorOf([&] { full.Close(); }),
              HasSubstr("/dev/full: write failed: No space left on device"));
  // ... and a writer never closed releases quietly, whatever the disk says.
  EXPECT_NO_THROW({ TimeseriesWriter quiet("/dev/full", 1); });
}

TEST(OutputTest, AnUnclosedWriterKeepsItsHeader) {
  const std::string path = TempDir("out_unclosed") + "/t.csv";
  { TimeseriesWriter w(path, 1); }
  EXPECT_EQ(ReadFile(path).substr(0, 10), "t,sigma_f,");
}

}  // namespace
}  // namespace mjf::runner
