// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// runner/record/src/recorders.cc: which recorders an experiment gets, when they want a frame, the
// exact bytes of a timeseries.csv row, and the close-on-error contract (Finish throws, a destructor
// never does).
#include "mjformation/record/recorders.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>

#include "mjformation/record/output.hpp"
#include "mjformation/sim/simulation.hpp"
#include "point_mass_util.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

using mjf::testing::Parse;
using mjf::testing::PointMassExperiment;
using mjf::testing::ReadFile;
using mjf::testing::TempDir;
using ::testing::HasSubstr;

TEST(RecordersTest, WhatAnExperimentGets) {
  Simulation sim(Parse(PointMassExperiment(-2, 0, 2, 0)));
  EXPECT_TRUE(MakeRecorders(sim, nullptr, {}).empty());  // no directory: nothing kept
  const std::string dir = TempDir("rec_which");
  RunDirectory run(dir, true);
  // The leader-acceleration monitor and the safety events always; timeseries.csv when recording.
  EXPECT_EQ(MakeRecorders(sim, &run, {true, true}).size(), 3u);
  EXPECT_EQ(MakeRecorders(sim, &run, {false, true}).size(), 2u);
}

TEST(RecordersTest, TheTimeseriesWantsRecordTicksAndTheLastStep) {
  // 100 Hz at 1 ms: every 10th step, and step 25 (the last of 0.025 s) although 25 % 10 != 0.
  Simulation sim(Parse(PointMassExperiment(-2, 0, 2, 0, 0.025)));
  ASSERT_EQ(sim.total_steps(), 25);
  RunDirectory run(TempDir("rec_wants"), true);
  auto recorders = MakeRecorders(sim, &run, {true, false});
  const Recorder& csv = *recorders.back();
  std::vector<int64_t> wanted;
  for (int64_t step = 0; step <= 25; ++step) {
    if (csv.Wants(step)) wanted.push_back(step);
  }
  EXPECT_EQ(wanted, (std::vector<int64_t>{0, 10, 20, 25}));
  EXPECT_FALSE(recorders.front()->Wants(0));  // the monitor needs OnStep only
}

TEST(RecordersTest, ATimeseriesRowByteForByte) {
  // Vehicles at rest at their start (leader (0, 0), followers (-2, 1) and (2.5, 0), 2 m up),
  // hover: every velocity, angle and command is zero at t = 0; hover has no sliding variable
  // (empty sx, sy cells); sigma_f and the slots are what the frame carries.
  Simulation sim(Parse(PointMassExperiment(-2, 1, 2.5, 0)));
  const std::string dir = TempDir("rec_row");
  RunDirectory run(dir, true);
  auto recorders = MakeRecorders(sim, &run, {true, false});
  sim.ComputeControls();
  for (auto& r : recorders) r->OnStep(sim);
  const std::vector<double> slots = {0, 0, -2, 0, 2, 0.125};
  const Frame frame{sim, 0, 1.118033988749895, slots};
  for (auto& r : recorders) {
    if (r->Wants(0)) r->Record(frame);
  }
  for (auto& r : recorders) r->Finish();
  const std::string csv = ReadFile(dir + "/timeseries.csv");
  const std::string row = csv.substr(csv.find('\n') + 1);
  EXPECT_EQ(row,
            "0.000000,1.11803399,"
            "0,0,2,0,0,0,0,0,0,0,0,,,0,0,"
            "-2,1,2,0,0,0,0,0,0,0,0,,,-2,0,"
            "2.5,0,2,0,0,0,0,0,0,0,0,,,2,0.125\n");
  nlohmann::ordered_json summary;
  for (const auto& r : recorders) r->Summarize(&summary);
  EXPECT_TRUE(summary.contains("leader_acceleration"));
}

TEST(RecordersTest, LeaderAccelerationColumnsOnlyWhenAskedFor) {
  Simulation sim(
      Parse(PointMassExperiment(-2, 0, 2, 0, 0.02, "record_leader_acceleration = true\n")));
  const std::string dir = TempDir("rec_lacc");
  RunDirectory run(dir, true);
  auto recorders = MakeRecorders(sim, &run, {true, false});
  for (auto& r : recorders) r->Finish();
  const std::string csv = ReadFile(dir + "/timeseries.csv");
  EXPECT_EQ(csv.substr(csv.size() - 21), ",leader_ax,leader_ay\n");
}

TEST(RecordersTest, FinishThrowsWhenTheDiskIsFullAndDestructorsStayQuiet) {
  Simulation sim(Parse(PointMassExperiment(-2, 0, 2, 0)));
  const std::string dir = TempDir("rec_full");
  RunDirectory run(dir, true);
  std::filesystem::create_symlink("/dev/full", dir + "/timeseries.csv");
  sim.ComputeControls();
  const std::vector<double> slots(6, 0.0);
  {
    auto recorders = MakeRecorders(sim, &run, {true, false});
    recorders.back()->Record(Frame{sim, 0, 0.0, slots});
    try {
      recorders.back()->Finish();
      ADD_FAILURE() << "Finish on a full disk did not throw";
    } catch (const OutputError& e) {
      EXPECT_THAT(e.what(), HasSubstr("timeseries.csv: write failed: No space left on device"));
    }
  }
  // Never finished (the run failed elsewhere): destroyed without a word.
  EXPECT_NO_THROW({
    auto recorders = MakeRecorders(sim, &run, {true, false});
    recorders.back()->Record(Frame{sim, 0, 0.0, slots});
  });
}

// Writes `rows` rows into `path` in a child process whose files may not exceed `limit` bytes;
// returns the child's exit status: 3 when Close() reported the failed write, 0 when it did not.
int WriteRowsUnderFileSizeLimit(const std::string& path, int rows, rlim_t limit) {
  Simulation sim(Parse(PointMassExperiment(-2, 0, 2, 0)));
  sim.ComputeControls();
  const std::vector<double> slots(6, 0.0);
  const pid_t child = fork();
  if (child == 0) {
    const rlimit cap{limit, limit};
    setrlimit(RLIMIT_FSIZE, &cap);
    std::signal(SIGXFSZ, SIG_IGN);  // as the CLI does: the write fails with EFBIG instead
    TimeseriesWriter writer(path, sim.n_vehicles());
    for (int k = 0; k < rows; ++k) writer.Write(sim, 0.5, slots);
    try {
      writer.Close();
    } catch (const OutputError&) {
      _exit(3);
    }
    _exit(0);
  }
  int status = 0;
  waitpid(child, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(RecordersTest, AWriteCutShortLeavesOnlyWholeRows) {
  const std::string dir = TempDir("rec_fsize");
  // Unlimited first: the length of the header and of one row.
  ASSERT_EQ(WriteRowsUnderFileSizeLimit(dir + "/whole.csv", 3, RLIM_INFINITY), 0);
  const std::string whole = ReadFile(dir + "/whole.csv");
  const size_t header = whole.find('\n') + 1;
  const size_t row = (whole.size() - header) / 3;
  ASSERT_EQ(header + 3 * row, whole.size());
  // Room for the header, two rows and half of the third: the third must not be left cut off.
  const rlim_t limit = header + 2 * row + row / 2;
  ASSERT_EQ(WriteRowsUnderFileSizeLimit(dir + "/cut.csv", 3, limit), 3);
  EXPECT_EQ(ReadFile(dir + "/cut.csv"), whole.substr(0, header + 2 * row));
  // Not even the header fits: an empty file rather than part of a header.
  ASSERT_EQ(WriteRowsUnderFileSizeLimit(dir + "/none.csv", 3, header / 2), 3);
  EXPECT_EQ(ReadFile(dir + "/none.csv"), "");
}

}  // namespace
}  // namespace mjf::runner
