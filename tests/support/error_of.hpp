// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// What an error says, for the tests that check that it names the file, line, key or plugin and
// says what to do: every C++ test may use it (tests/CMakeLists.txt, mjf_test_support).
#ifndef MJFORMATION_TESTS_SUPPORT_ERROR_OF_HPP_
#define MJFORMATION_TESTS_SUPPORT_ERROR_OF_HPP_

#include <exception>
#include <string>

namespace mjf::testing {

// The message of the Error that `statement` throws, or `nothing` when it returns. Any other
// exception propagates, so the test fails when the wrong kind of error is raised.
template <typename Error = std::exception, typename Statement>
std::string ErrorOf(Statement&& statement, const char* nothing = "") {
  try {
    statement();
  } catch (const Error& e) {
    return e.what();
  }
  return nothing;
}

}  // namespace mjf::testing

#endif  // MJFORMATION_TESTS_SUPPORT_ERROR_OF_HPP_
