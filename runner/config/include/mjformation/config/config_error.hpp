// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The one error every reader of outside input in config/ throws: a message already formatted
// with file, line and key ("FILE:LINE: [section] key: what is wrong").
#ifndef MJFORMATION_CONFIG_CONFIG_ERROR_HPP_
#define MJFORMATION_CONFIG_CONFIG_ERROR_HPP_

#include <stdexcept>

namespace mjf::runner {

// A configuration problem, already formatted with file, line and key.
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace mjf::runner

#endif  // MJFORMATION_CONFIG_CONFIG_ERROR_HPP_
