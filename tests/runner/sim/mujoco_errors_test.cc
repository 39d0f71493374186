// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// runner/sim/src/mujoco_errors.cc: an engine error throws MujocoError on the thread that raised it
// (and no other); a warning is kept per thread and never written to MUJOCO_LOG.TXT.
#include "mjformation/sim/mujoco_errors.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>
#include <unistd.h>

#include <atomic>
#include <fstream>
#include <string>
#include <thread>

#include "error_of.hpp"

namespace mjf::runner {
namespace {

using ::testing::HasSubstr;

std::string ErrorOf(void (*raise)()) {
  return mjf::testing::ErrorOf<MujocoError>(raise, "(nothing thrown)");
}

TEST(MujocoErrorsTest, AnEngineErrorThrowsWithMujocosMessage) {
  InstallMujocoHandlers();
  EXPECT_EQ(ErrorOf([] { mju_error("the stack is full"); }), "MuJoCo error: the stack is full");
  EXPECT_EQ(ErrorOf([] { mju_error("bad id %d", 7); }), "MuJoCo error: bad id 7");
  // A MujocoError is a SimulationError: the run loop's handler ends the run with it.
  EXPECT_THROW(mju_error("x"), SimulationError);
}

TEST(MujocoErrorsTest, TheErrorStaysOnTheThreadThatRaisedIt) {
  InstallMujocoHandlers();
  std::atomic<int> caught_here{0};
  std::string message;
  std::thread worker([&] {
    try {
      mju_error("raised on %s", "the worker");
    } catch (const MujocoError& e) {
      message = e.what();
      caught_here = 1;
    }
  });
  worker.join();
  EXPECT_EQ(caught_here.load(), 1);
  EXPECT_EQ(message, "MuJoCo error: raised on the worker");
  // And this thread's own errors are still its own.
  EXPECT_EQ(ErrorOf([] { mju_error("main"); }), "MuJoCo error: main");
}

TEST(MujocoErrorsTest, AnErrorInsideARealStepUnwindsToTheCaller) {
  InstallMujocoHandlers();
  char error[256] = "";
  const std::string path = ::testing::TempDir() + "/mjf_mujoco_errors_ball.xml";
  std::ofstream(path) << "<mujoco><worldbody><body><freejoint/><geom size=\"0.1\"/></body>"
                         "</worldbody></mujoco>";
  mjModel* m = mj_loadXML(path.c_str(), nullptr, error, sizeof(error));
  ASSERT_NE(m, nullptr) << error;
  mjData* d = mj_makeData(m);
  // An mjData whose stack is used up (the stack grows down from the arena's end towards the
  // arena): the step's first mj_stackAlloc raises mju_error.
  d->pstack = d->narena - d->parena;
  try {
    mj_step(m, d);
    ADD_FAILURE() << "mj_step with no stack did not raise an engine error";
  } catch (const MujocoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("MuJoCo error:"));
  }
  mj_deleteData(d);
  mj_deleteModel(m);
}

TEST(MujocoErrorsTest, WarningsAreKeptPerThreadAndNotWrittenToTheWorkingDirectory) {
  InstallMujocoHandlers();
  char cwd[4096];
  ASSERT_NE(getcwd(cwd, sizeof(cwd)), nullptr);
  const std::string log = std::string(cwd) + "/MUJOCO_LOG.TXT";
  const bool log_existed = access(log.c_str(), F_OK) == 0;
  ClearMujocoWarning();
  EXPECT_EQ(LastMujocoWarning(), "");
  mju_warning("careful");
  EXPECT_EQ(LastMujocoWarning(), "careful");
  std::string seen_by_other = "unset";
  std::thread other([&] { seen_by_other = LastMujocoWarning(); });
  other.join();
  EXPECT_EQ(seen_by_other, "");
  ClearMujocoWarning();
  EXPECT_EQ(LastMujocoWarning(), "");
  if (!log_existed) {
    EXPECT_NE(access(log.c_str(), F_OK), 0) << "MuJoCo wrote " << log;
  }
}

}  // namespace
}  // namespace mjf::runner
