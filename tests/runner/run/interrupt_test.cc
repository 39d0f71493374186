// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// runner/run/src/interrupt.cc: SIGINT / SIGTERM / SIGHUP as a polled flag, the exit code, and the
// second Ctrl-C that ends the process at once.
#include "mjformation/run/interrupt.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <thread>

namespace mjf::runner {
namespace {

// Leaves the process as it found it: no flag, default dispositions.
class InterruptTest : public ::testing::Test {
 protected:
  void TearDown() override {
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    std::signal(SIGHUP, SIG_DFL);
    std::signal(SIGXFSZ, SIG_DFL);
    ClearInterrupt();
  }
};

TEST_F(InterruptTest, FlagSignalAndExitCode) {
  ClearInterrupt();
  EXPECT_FALSE(InterruptRequested());
  EXPECT_EQ(InterruptSignal(), 0);
  EXPECT_EQ(InterruptExitCode(), 0);
  RequestInterrupt(SIGTERM);
  EXPECT_TRUE(InterruptRequested());
  EXPECT_EQ(InterruptSignal(), SIGTERM);
  EXPECT_EQ(InterruptExitCode(), 143);
  RequestInterrupt(SIGINT);
  EXPECT_EQ(InterruptExitCode(), 130);
  RequestInterrupt(SIGHUP);
  EXPECT_EQ(InterruptExitCode(), 129);
  ClearInterrupt();
  EXPECT_FALSE(InterruptRequested());
  EXPECT_EQ(InterruptExitCode(), 0);
}

TEST_F(InterruptTest, ARealSignalSetsTheFlagAndDoesNotEndTheProcess) {
  ClearInterrupt();
  InstallInterruptHandlers();
  InstallInterruptHandlers();  // idempotent
  ASSERT_EQ(std::raise(SIGTERM), 0);
  EXPECT_TRUE(InterruptRequested());
  EXPECT_EQ(InterruptSignal(), SIGTERM);
  // The first signal is the one kept: a later SIGTERM does not replace it or end the process.
  ASSERT_EQ(std::raise(SIGTERM), 0);
  EXPECT_EQ(InterruptSignal(), SIGTERM);
  ClearInterrupt();
  ASSERT_EQ(std::raise(SIGINT), 0);
  EXPECT_EQ(InterruptSignal(), SIGINT);
  EXPECT_EQ(InterruptExitCode(), 130);
  // A closed terminal or a dropped ssh session: the same clean stop, not the default's death.
  ClearInterrupt();
  ASSERT_EQ(std::raise(SIGHUP), 0);
  EXPECT_EQ(InterruptSignal(), SIGHUP);
  EXPECT_EQ(InterruptExitCode(), 129);
}

TEST_F(InterruptTest, OversizedFileSignalIsIgnoredOnceInstalled) {
  InstallInterruptHandlers();
  struct sigaction now {};
  ASSERT_EQ(sigaction(SIGXFSZ, nullptr, &now), 0);
  EXPECT_EQ(now.sa_handler, SIG_IGN);
}

TEST_F(InterruptTest, SecondCtrlCAfterTheFirstWasSeenEndsTheProcessWith130) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        ClearInterrupt();
        InstallInterruptHandlers();
        std::raise(SIGINT);                        // first: the flag
        if (!InterruptRequested()) std::_Exit(2);  // the loop sees it
        std::this_thread::sleep_for(std::chrono::milliseconds(80));
        std::raise(SIGINT);  // second, later: out now
        std::_Exit(0);       // not reached
      },
      ::testing::ExitedWithCode(130), "");
}

// `timeout -s INT` signals the process and then its group: two SIGINTs in the same instant. The
// duplicate must not end the process before the clean stop writes the summary.
TEST_F(InterruptTest, DuplicateSigintInTheSameInstantKeepsTheCleanStop) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        ClearInterrupt();
        InstallInterruptHandlers();
        std::raise(SIGINT);
        std::raise(SIGINT);  // before the first was seen: a duplicate
        if (!InterruptRequested()) std::_Exit(2);
        std::raise(SIGINT);  // seen, but within the same instant: still a duplicate
        std::_Exit(InterruptSignal() == SIGINT ? 7 : 3);
      },
      ::testing::ExitedWithCode(7), "");
}

}  // namespace
}  // namespace mjf::runner
