// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Typed access to one table of the experiment file, refusing keys it does not know; every
// error is "FILE:LINE: [section] key: reason". Private to config/: toml++ is not part of the
// stage's public interface.
#ifndef MJFORMATION_CONFIG_SECTION_READER_HPP_
#define MJFORMATION_CONFIG_SECTION_READER_HPP_

#include <toml++/toml.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "mjformation/config/source_location.hpp"

namespace mjf::runner {

// Where `node` is: FILE:LINE, or for a value that came from the command line its origin
// "--set section.key=value" (ApplyOverrides parses each with that as its source path).
SourceLocation NodeLocation(const std::string& file, const toml::node* node,
                            const std::string& what);

// "a string", "an integer", ...: the kind of value a type error says it got.
const char* TypeName(const toml::node& node);

// Which keys each table accepts, as the readers themselves know them (the key reference's
// completeness test, key_reference.hpp AcceptedKeys): while an AcceptedKeysRecorder is alive on
// this thread, every RejectUnknown (and every plugin section) adds its section and known keys.
using AcceptedKeyMap = std::map<std::string, std::set<std::string>>;
class AcceptedKeysRecorder {
 public:
  explicit AcceptedKeysRecorder(AcceptedKeyMap* into);
  ~AcceptedKeysRecorder();
  AcceptedKeysRecorder(const AcceptedKeysRecorder&) = delete;
  AcceptedKeysRecorder& operator=(const AcceptedKeysRecorder&) = delete;
};
// Adds `keys` to the recorder's `section` (nothing when no recorder is alive).
void RecordAcceptedKeys(const std::string& section, const std::set<std::string>& keys);

class SectionReader {
 public:
  // `table` may be null (the section is absent): every read returns its fallback. `reference`
  // names the table in the key reference when `name`, the one messages show, differs (a gust is
  // "[wind] gusts[2] start" in a message, "wind.gusts" in the reference).
  SectionReader(std::string path, const toml::table* table, std::string name,
                std::string reference = "")
      : path_(std::move(path)),
        table_(table),
        name_(std::move(name)),
        reference_(reference.empty() ? name_ : std::move(reference)) {}

  bool Has(const std::string& key) const { return table_ && table_->contains(key); }
  const toml::node* Node(const std::string& key) const {
    return table_ ? table_->get(key) : nullptr;
  }
  std::string Where(const std::string& key) const { return SectionKey(name_, key); }
  // At the key's line, or the table's when the key is absent.
  [[noreturn]] void Fail(const std::string& key, const std::string& message) const {
    FailAt(Node(key), key, message);
  }
  // At `node`'s line (an array item, say), or the table's when `node` is null.
  [[noreturn]] void FailAt(const toml::node* node, const std::string& key,
                           const std::string& message) const;

  double Number(const std::string& key, double fallback);
  double AsNumber(const toml::node& node, const std::string& key) const;
  int64_t Integer(const std::string& key, int64_t fallback);
  bool Bool(const std::string& key, bool fallback);
  std::string String(const std::string& key, const std::string& fallback);
  const toml::array* Array(const std::string& key);
  std::vector<double> Numbers(const std::string& key, std::vector<double> fallback,
                              int expected_size = -1);
  std::array<double, 3> Vector3(const std::string& key, std::array<double, 3> fallback);
  void MarkUsed(const std::string& key) { used_.insert(key); }

  // One of a fixed set of words (a table of EnumWord, experiment.hpp), returned as its value;
  // anything else is refused listing the words in the table's order.
  template <typename E, size_t N>
  E Enum(const std::string& key, E fallback, const std::pair<const char*, E> (&words)[N]) {
    used_.insert(key);
    if (!Node(key)) return fallback;
    const std::string text = String(key, "");
    std::string list;
    for (const auto& [word, value] : words) {
      if (text == word) return value;
      list += (list.empty() ? "\"" : ", \"") + std::string(word) + "\"";
    }
    Fail(key, "must be one of " + list + " (got \"" + text + "\")");
  }

  // Refuses keys this section does not define (read or marked so far), listing the ones it
  // does.
  void RejectUnknown() const;
  const toml::table* table() const { return table_; }

 private:
  std::string path_;
  const toml::table* table_;
  std::string name_;
  std::string reference_;
  std::set<std::string> used_;
};

}  // namespace mjf::runner

#endif  // MJFORMATION_CONFIG_SECTION_READER_HPP_
