// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Where in the experiment file a value is, for the one form every input error takes:
// "FILE:LINE: [section] key: reason" (docs/ARCHITECTURE.md, failure contract).
#ifndef MJFORMATION_CONFIG_SOURCE_LOCATION_HPP_
#define MJFORMATION_CONFIG_SOURCE_LOCATION_HPP_

#include <string>

#include "mjformation/config/config_error.hpp"
#include "mjformation/config/experiment.hpp"

namespace mjf::runner {

// "[section] key", or "[section]" when there is no key.
inline std::string SectionKey(const std::string& section, const std::string& key = "") {
  return "[" + section + "]" + (key.empty() ? "" : " " + key);
}

// `text` with control characters (other than newline and tab) and DEL written as \xNN: a
// message that quotes a user's file never sends terminal escape sequences.
inline std::string EscapeControl(const std::string& text) {
  static const char* const kHex = "0123456789abcdef";
  std::string out;
  for (char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if ((c < 0x20 && c != '\n' && c != '\t') || c == 0x7f) {
      out += std::string("\\x") + kHex[c >> 4] + kHex[c & 15];
    } else {
      out += ch;
    }
  }
  return out;
}

// `text` on one line: newline, carriage return and tab as \n, \r, \t, every other control
// character and DEL as \xNN. For text given on the command line that is quoted in a message or
// in a comment of a written file, where a line break would end the comment.
inline std::string OneLineEscaped(const std::string& text) {
  std::string out;
  for (char ch : text) {
    if (ch == '\n') {
      out += "\\n";
    } else if (ch == '\r') {
      out += "\\r";
    } else if (ch == '\t') {
      out += "\\t";
    } else {
      out += EscapeControl(std::string(1, ch));
    }
  }
  return out;
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

// Where `origin` points, naming `what` there: "FILE:LINE: what", or "--set run.threads=4: what"
// for a value from the command line.
inline SourceLocation OriginLocation(const std::string& file, const ValueOrigin& origin,
                                     const std::string& what) {
  if (!origin.argument.empty()) return {origin.argument, 0, what};
  return {file, origin.line, what};
}

}  // namespace mjf::runner

#endif  // MJFORMATION_CONFIG_SOURCE_LOCATION_HPP_
