// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// FixedStateArchive's walk of a Mersenne twister: Loading skips the words a block already holds
// and Updating writes them only after a twist, and either way the engine and the block end as a
// plain Saving and Loading leave them.
#include "mjformation/config/fixed_state_archive.hpp"

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

namespace mjf::runner {
namespace {

struct Stream {
  std::mt19937_64 engine;
  double value = 0;
  template <typename Archive>
  void VisitState(Archive& a) {
    a(engine, value);
  }
};

size_t Size() {
  Stream s;
  FixedStateArchive sizing = FixedStateArchive::Sizing();
  sizing(s);
  return sizing.size();
}

std::vector<double> Saved(Stream s) {
  std::vector<double> block(Size());
  FixedStateArchive saving = FixedStateArchive::Saving(block.data());
  saving(s);
  return block;
}

void Load(Stream& s, const std::vector<double>& block) {
  FixedStateArchive loading = FixedStateArchive::Loading(block.data());
  loading(s);
}

void Draw(Stream& s, int draws) {
  for (int k = 0; k < draws; ++k) s.value += static_cast<double>(s.engine() >> 40);
}

// Draws from one state, `ahead` draws on: within a twist (5), onto a twist's last word (311),
// across one (312, 700), from a freshly seeded engine (0).
class TwisterWalk : public ::testing::TestWithParam<int> {};

TEST_P(TwisterWalk, UpdatingWritesWhatSavingWrites) {
  Stream s{std::mt19937_64(42)};
  Draw(s, 100);
  std::vector<double> block = Saved(s);
  Load(s, block);  // the block is what s last loaded, as plugin_state between two ticks
  Draw(s, GetParam());
  FixedStateArchive updating = FixedStateArchive::Updating(block.data());
  updating(s);
  EXPECT_EQ(block, Saved(s));
}

TEST_P(TwisterWalk, LoadingGivesTheSavedStreamBack) {
  Stream saved{std::mt19937_64(7)};
  Draw(saved, 300);
  const std::vector<double> block = Saved(saved);
  // The engine that loads it is ahead of or behind it (the native plugin's cache after a
  // mj_setState to an earlier step, or to a later one).
  Stream loaded = saved;
  Draw(loaded, GetParam());
  Load(loaded, block);
  EXPECT_EQ(loaded.engine, saved.engine);
  EXPECT_EQ(loaded.value, saved.value);
  Stream behind{std::mt19937_64(7)};
  Draw(behind, GetParam());
  Load(behind, block);
  EXPECT_EQ(behind.engine, saved.engine);
}

INSTANTIATE_TEST_SUITE_P(Draws, TwisterWalk, ::testing::Values(0, 5, 311, 312, 700));

TEST(TwisterWalk, AnotherStreamsBlockIsLoadedWhole) {
  Stream other{std::mt19937_64(1)};
  Draw(other, 3);
  const std::vector<double> block = Saved(other);
  Stream s{std::mt19937_64(2)};
  Draw(s, 3);
  Load(s, block);
  EXPECT_EQ(s.engine, other.engine);
}

// A block that is not the engine's own is read word by word, each checked: a value that is not a
// whole 32-bit word was not written by a walk, and is refused.
TEST(TwisterWalk, ABlockOfAnotherStreamIsCheckedWordByWord) {
  Stream s{std::mt19937_64(3)};
  std::vector<double> block = Saved(s);
  Stream other{std::mt19937_64(4)};
  block[100] = 0.5;  // not a word: the block is not other's, so its words are read and checked
  try {
    Load(other, block);
    ADD_FAILURE() << "loaded a block with a fraction where a word is stored";
  } catch (const StateArchiveError& e) {
    EXPECT_NE(std::string(e.what()).find("0.5"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("at position 100 "), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace mjf::runner
