// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// run --resume with a checkpoint it must not use (docs/ARCHITECTURE.md, "Checkpoint and
// resume"): a damaged file, one of an older format, one of another set of recorders. Each is
// refused as bad input (exit 1) with the file named, and the run directory is left byte for
// byte as it was. The resumed run that equals an uninterrupted one is
// tests/runner/checkpoint_resume.sh.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "mjformation/app/cli.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

namespace fs = std::filesystem;
using mjf::testing::Cli;
using mjf::testing::HoverExperiment;
using mjf::testing::ReadFile;
using mjf::testing::TempDir;
using mjf::testing::WriteFile;
using ::testing::HasSubstr;
using ::testing::Not;

// Every file of a folder (relative path) and its bytes.
std::map<std::string, std::string> FolderBytes(const std::string& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    if (entry.is_regular_file()) {
      files[fs::relative(entry.path(), dir).string()] = ReadFile(entry.path().string());
    }
  }
  return files;
}

std::pair<int, std::string> CliStderr(const std::vector<std::string>& args) {
  ::testing::internal::CaptureStderr();
  const int code = Cli(args);
  return {code, ::testing::internal::GetCapturedStderr()};
}

// A finished run of a small experiment with checkpoints (the last one, at 0.8 s, stays in the
// folder), its experiment file and its folder. `extra`: more options for the run.
struct CheckpointedRun {
  std::string exp, out, checkpoint;
};
CheckpointedRun RunWithCheckpoints(const std::string& tag,
                                   const std::vector<std::string>& extra = {"--no-render"}) {
  const std::string dir = TempDir(tag);
  CheckpointedRun run{WriteFile(dir + "/e.toml", HoverExperiment(2, 1.0)), dir + "/run", ""};
  run.checkpoint = run.out + "/checkpoint.mjfstate";
  std::vector<std::string> args = {"run", run.exp, "--out", run.out, "-q", "--checkpoint-every",
                                   "0.4"};
  args.insert(args.end(), extra.begin(), extra.end());
  EXPECT_EQ(Cli(args), 0);
  EXPECT_TRUE(fs::exists(run.checkpoint));
  return run;
}

// The resume of `run` (with `extra` options) is refused with exit 1, names the checkpoint and
// says `why`, and changes no file of the folder. Returns what it printed.
std::string ExpectRefusedResume(const CheckpointedRun& run, const std::string& why,
                                const std::vector<std::string>& extra = {"--no-render"}) {
  const auto before = FolderBytes(run.out);
  std::vector<std::string> args = {"run", run.exp, "--out", run.out, "-q", "--resume"};
  args.insert(args.end(), extra.begin(), extra.end());
  const auto [code, err] = CliStderr(args);
  EXPECT_EQ(code, 1) << err;
  EXPECT_THAT(err, HasSubstr(run.checkpoint + ": "));
  EXPECT_THAT(err, HasSubstr(why));
  EXPECT_TRUE(FolderBytes(run.out) == before) << "a refused resume changed the run directory";
  return err;
}

// The resume of a good checkpoint works (the refusals below are of what was done to the file).
TEST(CheckpointTest, AnUntouchedCheckpointResumes) {
  const CheckpointedRun run = RunWithCheckpoints("ckpt_good");
  const std::string rows = ReadFile(run.out + "/timeseries.csv");
  EXPECT_EQ(Cli({"run", run.exp, "--out", run.out, "-q", "--resume", "--no-render"}), 0);
  EXPECT_EQ(ReadFile(run.out + "/timeseries.csv"), rows);
}

// One flipped bit in a number would load and resume into another run: the checksum refuses it
// before any of the file is used.
TEST(CheckpointTest, AFlippedBitIsRefusedAsDamaged) {
  const CheckpointedRun run = RunWithCheckpoints("ckpt_flip");
  std::string bytes = ReadFile(run.checkpoint);
  ASSERT_GT(bytes.size(), 600u);
  bytes[600] = static_cast<char>(bytes[600] ^ 0x10);
  WriteFile(run.checkpoint, bytes);
  ExpectRefusedResume(run, "the checkpoint is damaged");
}

// The last 8 bytes zeroed: the damage lies past the recorders' states, so a resume that checked
// the end last would have cut timeseries.csv back to the checkpoint first.
TEST(CheckpointTest, AZeroedTailIsRefusedAndNoRowIsCut) {
  const CheckpointedRun run = RunWithCheckpoints("ckpt_tail");
  std::string bytes = ReadFile(run.checkpoint);
  bytes.replace(bytes.size() - 8, 8, std::string(8, '\0'));
  WriteFile(run.checkpoint, bytes);
  ExpectRefusedResume(run, "damaged");
}

// A checkpoint of the format before the checksum (the same payload, no digest at its end): both
// format numbers are named.
TEST(CheckpointTest, AnOlderFormatNamesBothNumbers) {
  const CheckpointedRun run = RunWithCheckpoints("ckpt_format");
  std::string bytes = ReadFile(run.checkpoint);
  const std::string label = "mjformation checkpoint 5";
  const size_t at = bytes.find(label);
  ASSERT_NE(at, std::string::npos);
  bytes[at + label.size() - 1] = '4';
  bytes.resize(bytes.size() - 64);
  WriteFile(run.checkpoint, bytes);
  ExpectRefusedResume(run, "a checkpoint of format 4, where this build reads format 5");
}

// Another file (binary, with a NUL in its first label) in the checkpoint's place.
TEST(CheckpointTest, AForeignFileIsRefused) {
  const CheckpointedRun run = RunWithCheckpoints("ckpt_foreign");
  WriteFile(run.checkpoint, std::string("\x05\0\0\0\0\0\0\0ab\0cd", 13) + std::string(64, '0'));
  ExpectRefusedResume(run, "not a mjformation checkpoint, or a damaged one");
}

// A run checkpointed with --no-render has no snapshot recorder: resumed with snapshots, the
// recorders differ. Refused before summary.json or timeseries.csv is touched.
TEST(CheckpointTest, AnotherSetOfRecordersIsRefusedBeforeAnyFileChanges) {
  const std::vector<std::string> snapshots = {
      "--set", "render.snapshots=[0.2]", "--set", "render.width=64", "--set", "render.height=48"};
  std::vector<std::string> no_render = snapshots;
  no_render.push_back("--no-render");
  const CheckpointedRun run = RunWithCheckpoints("ckpt_recorders", no_render);
  const std::string err =
      ExpectRefusedResume(run, "the checkpoint holds 3 recorders where this run has 4", snapshots);
  EXPECT_THAT(err, Not(HasSubstr("stopped")));
}

}  // namespace
}  // namespace mjf::runner
