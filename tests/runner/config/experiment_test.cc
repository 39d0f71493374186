// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Unit tests of the source:
// runner/config/src/experiment.cc: each enum's one table of words, through which the parser
// reads and ToString writes.

#include "mjformation/config/experiment.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "test_util.hpp"

namespace mjf::runner {
namespace {

using ::testing::HasSubstr;

// Every word of a table names a different value, and ToString gives back the word.
template <typename E, size_t N>
void ExpectRoundTrip(const EnumWord<E> (&words)[N], size_t n_values) {
  std::set<E> values;
  std::set<std::string> spelled;
  for (const auto& [word, value] : words) {
    values.insert(value);
    spelled.insert(word);
    EXPECT_STREQ(ToString(value), word);
  }
  EXPECT_EQ(values.size(), n_values) << "a value of the enum has no word, or two words";
  EXPECT_EQ(spelled.size(), N);
}

TEST(ExperimentTest, EveryEnumValueHasOneWordAndToStringWritesIt) {
  ExpectRoundTrip(kRotorModelWords, 2);
  ExpectRoundTrip(kCameraModeWords, 3);
  ExpectRoundTrip(kShapeTypeWords, 4);
  ExpectRoundTrip(kExecutionWords, 2);
  ExpectRoundTrip(kCouplingWords, 3);
  ExpectRoundTrip(kPredictWords, 3);
  ExpectRoundTrip(kExchangeRoundsWords, 2);
  ExpectRoundTrip(kRoundPolicyWords, 2);
}

// The parser reads through the same tables: each word is accepted, anything else is refused
// with the table's words in its order.
TEST(ExperimentTest, TheParserReadsTheTablesWords) {
  for (const auto& [word, value] : kCouplingWords) {
    if (value == Coupling::kLastInput) continue;  // the default: giving it is refused with central
    const ExperimentConfig c = mjf::testing::Parse(
        mjf::testing::HoverExperiment() + "[execution]\nmode = \"per_agent\"\ncoupling = \"" +
        std::string(word) + "\"\n");
    EXPECT_EQ(c.network.coupling, value) << word;
  }
  try {
    mjf::testing::Parse(mjf::testing::HoverExperiment() + "[execution]\nmode = \"distributed\"\n");
    FAIL() << "an unknown mode was accepted";
  } catch (const std::exception& e) {
    EXPECT_THAT(e.what(), HasSubstr("[execution] mode: must be one of \"central\", \"per_agent\" "
                                    "(got \"distributed\")"));
  }
}

}  // namespace
}  // namespace mjf::runner
