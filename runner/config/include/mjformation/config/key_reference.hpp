// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The reference of every key of the experiment file: section, key, type, unit, default, range
// and what it does. Word ranges come from the parser's own tables (experiment.hpp's EnumWord
// tables), defaults from the structs the parser fills, so the reference cannot list a word or a
// default the parser does not have; a test compares the keys listed here with the keys the
// readers accept (AcceptedKeys). `mjformation keys` prints it; docs/EXPERIMENT_FILE.md is its
// output.
#ifndef MJFORMATION_CONFIG_KEY_REFERENCE_HPP_
#define MJFORMATION_CONFIG_KEY_REFERENCE_HPP_

#include <map>
#include <set>
#include <string>
#include <vector>

namespace mjf::runner {

struct KeyEntry {
  std::string section;  // "run", "formation.shape", "wind.gusts", "network.link"
  std::string key;
  std::string type;  // "number", "integer", "boolean", "string", "word", "[x, y]", ...
  std::string unit;  // "s", "m", "Hz", ... ; empty: none
  // The default as a TOML value when it is one ("40.0", "\"circle\""), else empty and
  // `default_text` says what it is ("the file's stem").
  std::string default_toml;
  std::string default_text;
  std::string range;
  std::string what;
  // TOML lines this key needs beside it in its section ("coupling = \"jacobi\""), or empty.
  std::string needs;
};

// Every key, section by section in kExperimentSections order (each section followed by its
// sub-tables).
const std::vector<KeyEntry>& ExperimentKeyReference();

// The reference as Markdown: what `mjformation keys` prints and docs/EXPERIMENT_FILE.md holds.
// `section` empty: every section; else that section and its sub-tables (ConfigError for a
// section the file format does not have).
std::string KeyReferenceMarkdown(const std::string& section = "");

// The keys the parser accepts in each table it reads while parsing `text` (an experiment file),
// as the readers know them: "run" -> {"duration", ...}; plugin sections list only their own keys
// ("plugin", and "shape" for [formation]), every other key being the chosen plugin's attribute.
// Throws ConfigError when `text` does not parse.
std::map<std::string, std::set<std::string>> AcceptedKeys(const std::string& text,
                                                          const std::string& path);

}  // namespace mjf::runner

#endif  // MJFORMATION_CONFIG_KEY_REFERENCE_HPP_
