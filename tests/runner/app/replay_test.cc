// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// `mjformation replay`: a run directory rendered again from timeseries.csv and scene.xml alone
// shows the vehicles where the run's own snapshots showed them at the same times.
#include "mjformation/app/replay.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "mjformation/config/config.hpp"
#include "mjformation/run/run.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

using mjf::testing::ReadPng;

// Fraction of pixels whose largest channel difference exceeds 25 of 255.
double DifferentPixels(const std::string& a_path, const std::string& b_path) {
  int wa = 0, ha = 0, wb = 0, hb = 0;
  const auto a = ReadPng(a_path, &wa, &ha), b = ReadPng(b_path, &wb, &hb);
  EXPECT_FALSE(a.empty()) << a_path;
  EXPECT_EQ(a.size(), b.size()) << a_path << " vs " << b_path;
  if (a.empty() || a.size() != b.size()) return 1.0;
  size_t differ = 0;
  for (size_t p = 0; p < a.size(); p += 3) {
    int d = 0;
    for (int k = 0; k < 3; ++k) d = std::max(d, std::abs(int(a[p + k]) - int(b[p + k])));
    differ += d > 25;
  }
  return static_cast<double>(differ) / (a.size() / 3);
}

// "WIDTHxHEIGHT" of a video's first stream, by ffprobe.
std::string VideoSize(const std::string& path) {
  const std::string cmd =
      "ffprobe -v error -select_streams v:0 -show_entries stream=width,height "
      "-of csv=s=x:p=0 '" +
      path + "'";
  std::string out;
  if (FILE* p = popen(cmd.c_str(), "r")) {
    char buf[256];
    while (fgets(buf, sizeof(buf), p)) out += buf;
    pclose(p);
  }
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

class ReplayTest : public ::testing::Test {
 protected:
  // Exp 2 for 8 s (the followers sweep across the picture), snapshots at 0, 4 and 8 s.
  static void SetUpTestSuite() {
    run_dir_ = new std::string(mjf::testing::TempDir("replay") + "/run");
    const ExperimentConfig c = LoadExperiment(
        std::string(MJF_SOURCE_DIR) + "/experiments/exp2.toml",
        {"run.duration=8.0", "run.metric_window=[5.0, 8.0]", "render.snapshots=[0.0, 4.0, 8.0]",
         "render.width=640", "render.height=360", "render.video_width=320",
         "render.video_height=240", "render.video_fps=5.0"});
    RunOptions o;
    o.out_dir = *run_dir_;
    const RunResult r = RunExperiment(c, o);
    ASSERT_TRUE(r.complete) << r.error;
  }
  static void TearDownTestSuite() { delete run_dir_; }
  static std::string* run_dir_;
};
std::string* ReplayTest::run_dir_ = nullptr;

TEST_F(ReplayTest, RendersTheSnapshotsPositionsAtTheSameTimes) {
  const Recording rec = LoadRecording(*run_dir_);
  EXPECT_EQ(rec.n_vehicles, 7);
  EXPECT_EQ(rec.name, "exp2");
  const auto written = RenderReplay(rec, {0.0, 4.0, 8.0}, *run_dir_ + "/replay", {});
  ASSERT_EQ(written.size(), 3u);
  const char* const times[] = {"000.00", "004.00", "008.00"};
  for (const char* t : times) {
    const std::string snap = *run_dir_ + "/snapshots/t" + t + ".png";
    const std::string replay = *run_dir_ + "/replay/replay_t" + t + ".png";
    // Measured: at most 1 pixel in 10^6 differs (the CSV keeps 9 significant digits).
    EXPECT_LT(DifferentPixels(snap, replay), 1e-4) << t;
  }
  // Control: the same comparison across different times sees the vehicles elsewhere.
  EXPECT_GT(DifferentPixels(*run_dir_ + "/snapshots/t004.00.png",
                            *run_dir_ + "/replay/replay_t008.00.png"),
            0.01);
}

TEST_F(ReplayTest, WritesAVideo) {
  const Recording rec = LoadRecording(*run_dir_);
  const std::string video = *run_dir_ + "/replay.mp4";
  ReplayVideo v;
  v.path = video;
  v.progress = false;
  RenderReplay(rec, {}, "", v);
  struct stat st;
  ASSERT_EQ(stat(video.c_str(), &st), 0);
  EXPECT_GT(st.st_size, 10000);
  // The snapshots' size (640x360 here), not [render] video_width x video_height (320x240).
  EXPECT_EQ(VideoSize(video), "640x360");
}

TEST_F(ReplayTest, VideoSizeOverridesTheSnapshotSize) {
  const Recording rec = LoadRecording(*run_dir_);
  ReplayVideo v;
  v.path = *run_dir_ + "/replay_small.mp4";
  v.width = 322;  // not a size the run knows
  v.height = 182;
  v.progress = false;
  RenderReplay(rec, {}, "", v);
  EXPECT_EQ(VideoSize(v.path), "322x182");
}

// Red pixels of the safety-event marks (nothing else in the picture is that red).
int EventRed(const std::string& path) {
  int w = 0, h = 0;
  const auto rgb = ReadPng(path, &w, &h);
  int n = 0;
  for (size_t p = 0; p + 2 < rgb.size(); p += 3) {
    n += rgb[p] > 180 && rgb[p + 1] < 60 && rgb[p + 2] < 60;
  }
  return n;
}

// A safety event in summary.json is marked (red) in the replayed picture at and after its time,
// not before it; the same picture without the event has no such red.
TEST_F(ReplayTest, MarksSafetyEventsFromTheSummary) {
  Recording rec = LoadRecording(*run_dir_);
  ASSERT_TRUE(rec.events.empty());
  const std::string out = *run_dir_ + "/replay_events";  // RenderReplay makes one level
  RenderReplay(rec, {4.0}, out + "_none", {});
  rec.events.push_back({"flip", 3.0, {2}});
  RenderReplay(rec, {2.0, 4.0}, out + "_flip", {});
  const int before = EventRed(out + "_flip/replay_t002.00.png");
  const int after = EventRed(out + "_flip/replay_t004.00.png");
  const int without = EventRed(out + "_none/replay_t004.00.png");
  EXPECT_GT(after, without + 30) << "no red event mark at 4 s";  // measured: 0 without, 60+ with
  EXPECT_LT(before, without + 20) << "the mark appeared before the event";
  std::printf("red pixels: before %d, after %d, without the event %d\n", before, after, without);
}

// `run` marks its own safety events in its snapshots: a region the followers leave at once
// (left_region) puts red marks into the 2 s snapshot; the same run without the region has none.
// Replay, reading the events from summary.json, marks them too.
TEST(RunSnapshotEventsTest, SnapshotsAfterAnEventMarkIt) {
  const std::string root = mjf::testing::TempDir("snap_events");
  auto run = [&](const std::string& name, std::vector<std::string> sets) {
    sets.insert(sets.end(),
                {"vehicles.model=\"pointmass\"", "attitude={plugin=\"pointmass_direct\"}",
                 "run.duration=2.0", "run.metric_window=[1.0, 2.0]", "render.snapshots=[2.0]",
                 "render.width=640", "render.height=360"});
    const ExperimentConfig c =
        LoadExperiment(std::string(MJF_SOURCE_DIR) + "/experiments/exp2.toml", sets);
    RunOptions o;
    o.out_dir = root + "/" + name;
    const RunResult r = RunExperiment(c, o);
    EXPECT_TRUE(r.complete) << r.error;
    return o.out_dir;
  };
  const std::string plain = run("plain", {});
  const std::string left = run("left", {"safety.region=[[15.0, 25.0], [-5.0, 5.0], [0.0, 50.0]]"});
  const Recording rec = LoadRecording(left);
  ASSERT_FALSE(rec.events.empty()) << "the region did not produce an event";
  EXPECT_EQ(rec.events[0].kind, "left_region");
  const int without = EventRed(plain + "/snapshots/t002.00.png");
  const int with = EventRed(left + "/snapshots/t002.00.png");
  std::printf("event red pixels: %d without, %d with %zu events\n", without, with,
              rec.events.size());
  EXPECT_LT(without, 5);
  EXPECT_GT(with, 30);
  RenderReplay(rec, {2.0}, left + "/replay", {});
  EXPECT_GT(EventRed(left + "/replay/replay_t002.00.png"), 30);
}

TEST(ParseVideoSizeTest, AcceptsWxHWithinBoundsAndRefusesTheRest) {
  EXPECT_EQ(ParseVideoSize("1920x1080"), (std::array<int, 2>{1920, 1080}));
  EXPECT_EQ(ParseVideoSize("7680x4320"), (std::array<int, 2>{7680, 4320}));
  for (const char* bad : {"", "1920", "0x720", "-5x720", "1280x0", "abcx720", "1280x7e2",
                          "7681x4320", "1280x4321", "99999999999x1", " 1280x720", "+1280x720"}) {
    EXPECT_THROW(ParseVideoSize(bad), std::invalid_argument) << bad;
  }
}

// The point mass moves on three slide joints, not a free joint: replay poses those.
TEST(PointMassReplayTest, RendersTheSnapshotsPositionsAtTheSameTimes) {
  const std::string dir = mjf::testing::TempDir("replay_pm") + "/run";
  const ExperimentConfig c =
      LoadExperiment(std::string(MJF_SOURCE_DIR) + "/experiments/exp2.toml",
                     {"vehicles.model=\"pointmass\"", "attitude={plugin=\"pointmass_direct\"}",
                      "run.duration=6.0", "run.metric_window=[4.0, 6.0]",
                      "render.snapshots=[2.0, 6.0]", "render.width=640", "render.height=360"});
  RunOptions o;
  o.out_dir = dir;
  const RunResult r = RunExperiment(c, o);
  ASSERT_TRUE(r.complete) << r.error;
  const auto written = RenderReplay(LoadRecording(dir), {2.0, 6.0}, dir + "/replay", {});
  ASSERT_EQ(written.size(), 2u);
  for (const char* t : {"002.00", "006.00"}) {
    EXPECT_LT(DifferentPixels(dir + "/snapshots/t" + std::string(t) + ".png",
                              dir + "/replay/replay_t" + std::string(t) + ".png"),
              1e-4)
        << t;
  }
  EXPECT_GT(DifferentPixels(dir + "/snapshots/t002.00.png", dir + "/replay/replay_t006.00.png"),
            0.01);
}

TEST(ReplayErrorTest, NamesTheMissingFile) {
  const std::string dir = mjf::testing::TempDir("noreplay");
  try {
    LoadRecording(dir);
    FAIL() << "loaded an empty folder";
  } catch (const ReplayError& e) {
    EXPECT_NE(std::string(e.what()).find(dir + "/config.toml"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace mjf::runner
