// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Where in the experiment file a value is, for the one form every input error takes:
// "FILE:LINE: [section] key: reason" (docs/ARCHITECTURE.md, failure contract).
#ifndef MJFORMATION_CONFIG_SOURCE_LOCATION_HPP_
#define MJFORMATION_CONFIG_SOURCE_LOCATION_HPP_

#include <string>

#include "mjformation/config/config.hpp"

namespace mjf::runner {

// "[section] key", or "[section]" when there is no key.
inline std::string SectionKey(const std::string& section, const std::string& key = "") {
  return "[" + section + "]" + (key.empty() ? "" : " " + key);
}

// The file, the line (0: not known, e.g. a default or an override) and what is there
// (usually SectionKey(...)).
struct SourceLocation {
  std::string path;
  int line = 0;
  std::string what;

  // "FILE:LINE: what", or "FILE: what" without a line.
  std::string Prefix() const {
    return path + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " + what;
  }
  [[noreturn]] void Fail(const std::string& reason) const {
    throw ConfigError(Prefix() + ": " + reason);
  }
};

}  // namespace mjf::runner

#endif  // MJFORMATION_CONFIG_SOURCE_LOCATION_HPP_
