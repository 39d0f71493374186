// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// runner/config/src/nearest_word.cc: the edit distance by hand, and which slips get a "did you
// mean" and which words are too far from any candidate to be one.
#include "mjformation/config/nearest_word.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace mjf::runner {
namespace {

TEST(NearestWordTest, EditDistanceCountsEachKindOfEditOnce) {
  EXPECT_EQ(EditDistance("run", "run"), 0u);
  EXPECT_EQ(EditDistance("rnu", "run"), 1u);  // two neighbours swapped
  EXPECT_EQ(EditDistance("circel", "circle"), 1u);
  EXPECT_EQ(EditDistance("chek", "check"), 1u);   // a letter left out
  EXPECT_EQ(EditDistance("Hover", "hover"), 0u);  // case does not count
  EXPECT_EQ(EditDistance("kitten", "sitting"), 3u);
  EXPECT_EQ(EditDistance("", "abc"), 3u);
  EXPECT_EQ(EditDistance("abc", ""), 3u);
}

TEST(NearestWordTest, ASlipGetsTheNearestWordAndAStrangerNothing) {
  const std::vector<std::string> commands = {"run",   "check",  "plugins", "keys",  "bench",
                                             "sweep", "replay", "view",    "export"};
  EXPECT_EQ(NearestWord("rnu", commands), "run");
  EXPECT_EQ(NearestWord("swep", commands), "sweep");
  EXPECT_EQ(NearestWord("exprot", commands), "export");
  EXPECT_EQ(NearestWord("frobnicate", commands), "");
  EXPECT_EQ(NearestWord("xyz", commands), "");  // 3 letters: one edit at most
  EXPECT_EQ(NearestWord("run", commands), "");  // a known word is no slip
  EXPECT_EQ(DidYouMean("rnu", commands), "; did you mean 'run'?");
  EXPECT_EQ(DidYouMean("frobnicate", commands), "");
  const std::vector<std::string> plugins = {"consensus_linear", "continuous_smc", "hover"};
  EXPECT_EQ(NearestWord("consensus_linaer", plugins), "consensus_linear");
  EXPECT_EQ(NearestWord("continous_smc", plugins), "continuous_smc");
}

}  // namespace
}  // namespace mjf::runner
