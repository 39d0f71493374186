// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// StateArchive's refusals quote what the bytes hold printably: a damaged or foreign state is
// binary, and a NUL in the message would end it where it is printed.
#include "mjformation/config/state_archive.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

namespace mjf::runner {
namespace {

using ::testing::HasSubstr;

std::string LoadError(const std::string& saved_label, const std::string& expected_label) {
  StateArchive saving;
  saving.Tag(saved_label);
  StateArchive loading(saving.bytes());
  try {
    loading.Tag(expected_label);
  } catch (const StateArchiveError& e) {
    return e.what();
  }
  return "";
}

TEST(StateArchiveTest, AForeignLabelIsQuotedWithItsBinaryBytesEscaped) {
  const std::string message = LoadError(std::string("ab\0\x01\xff\\z", 7), "simulation");
  EXPECT_THAT(message, HasSubstr("holds 'ab\\x00\\x01\\xff\\x5cz' where 'simulation' was"));
  EXPECT_EQ(message.find('\0'), std::string::npos);
}

TEST(StateArchiveTest, ALongForeignLabelIsCutToItsFirstBytes) {
  const std::string message = LoadError(std::string(1000, 'x'), "end");
  EXPECT_THAT(message, HasSubstr("holds '" + std::string(48, 'x') + "... (1000 bytes)' where"));
}

}  // namespace
}  // namespace mjf::runner
