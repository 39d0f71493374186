// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// plugin_state.hpp: a VisitState lists doubles, integers, flags, enums, containers, nested
// members and random engines; StateSize counts them, GetState / SetState carry every bit.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mjformation/plugin_state.hpp>
#include <random>
#include <sstream>
#include <vector>

namespace {

enum class Phase { kIdle, kSampling = 7 };

struct Inner {
  int64_t count = 0;
  std::array<double, 2> held{};
  template <typename Visit>
  void VisitState(Visit& visit) {
    visit(count, held);
  }
};

struct Law {
  double integral = 0;
  bool has_sample = false;
  int round = 0;
  uint64_t draws = 0;
  Phase phase = Phase::kIdle;
  double window[3] = {0, 0, 0};
  std::vector<double> held = std::vector<double>(4, 0.0);
  Inner inner;
  std::mt19937 rng{5};
  template <typename Visit>
  void VisitState(Visit& visit) {
    visit(integral, has_sample, round, draws, phase, window, held, inner, rng);
  }
};

TEST(PluginState, CountsEveryMemberAndRoundTripsEveryBit) {
  Law a;
  a.integral = -0.1;
  a.has_sample = true;
  a.round = -3;
  a.draws = std::numeric_limits<uint64_t>::max() - 5;  // not exact as one double
  a.phase = Phase::kSampling;
  a.window[2] = std::numeric_limits<double>::denorm_min();
  a.held = {1, 2, 3, std::numeric_limits<double>::quiet_NaN()};
  a.inner.count = -(int64_t{1} << 60) - 1;
  a.inner.held = {4, 5};
  a.rng.discard(1000);
  // 1 + 1 + 1 + 2 (64-bit) + 1 + 3 + 4 + (2 + 2) + the engine's words, 2 each.
  std::ostringstream text;
  text << a.rng;
  size_t words = 0;
  std::istringstream in(text.str());
  for (unsigned long long w; in >> w;) ++words;
  ASSERT_EQ(mjf::plugin::StateSize(a), 17 + 2 * words);
  std::vector<double> state(mjf::plugin::StateSize(a));
  mjf::plugin::GetState(a, state.data());
  Law b;
  mjf::plugin::SetState(b, state.data());
  EXPECT_EQ(b.integral, a.integral);
  EXPECT_TRUE(b.has_sample);
  EXPECT_EQ(b.round, -3);
  EXPECT_EQ(b.draws, a.draws);
  EXPECT_EQ(b.phase, Phase::kSampling);
  EXPECT_EQ(b.window[2], a.window[2]);
  EXPECT_EQ(b.held[2], 3);
  EXPECT_TRUE(std::isnan(b.held[3]));
  EXPECT_EQ(b.inner.count, a.inner.count);
  EXPECT_EQ(b.inner.held[1], 5);
  EXPECT_EQ(b.rng(), a.rng());  // the stream goes on where a's does
  EXPECT_TRUE(mjf::plugin::kHasVisitState<Law>);
  EXPECT_FALSE(mjf::plugin::kHasVisitState<std::vector<double>>);
}

// A table of at most four items, the rest as unused slots: counted as four items, written as
// zeros, and skipped when read (the reader's blank slots keep what they hold).
struct Table {
  std::vector<Inner> used;
  template <typename Visit>
  void VisitState(Visit& visit) {
    int count = static_cast<int>(used.size());
    visit(count);
    used.resize(static_cast<size_t>(count));
    for (Inner& item : used) visit(item);
    Inner blank;
    visit.Unused(4 - used.size(), blank);
  }
};

TEST(PluginState, UnusedSlotsAreZerosCountedAndNotRead) {
  Table a;
  a.used.push_back(Inner{3, {1, 2}});
  ASSERT_EQ(mjf::plugin::StateSize(a), 1 + 4 * 4u);
  std::vector<double> state(mjf::plugin::StateSize(a), -1.0);
  mjf::plugin::GetState(a, state.data());
  EXPECT_EQ(std::vector<double>(state.begin() + 5, state.end()), std::vector<double>(12, 0.0));
  EXPECT_EQ(state[3], 1);
  Table b;
  b.used.resize(3);
  std::fill(state.begin() + 5, state.end(), std::nan(""));  // never read
  mjf::plugin::SetState(b, state.data());
  ASSERT_EQ(b.used.size(), 1u);
  EXPECT_EQ(b.used[0].count, 3);
  EXPECT_EQ(b.used[0].held[1], 2);
}

}  // namespace
