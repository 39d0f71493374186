// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Reading the experiment file (TOML, with --set overrides) into ExperimentConfig
// (experiment.hpp). Parsing checks every key and type and reports errors as
// "FILE:LINE: [section] key: what is wrong" (ConfigError).
#ifndef MJFORMATION_CONFIG_CONFIG_HPP_
#define MJFORMATION_CONFIG_CONFIG_HPP_

#include <string>
#include <vector>

#include "mjformation/config/config_error.hpp"
#include "mjformation/config/experiment.hpp"

namespace mjf::runner {

// Follower edges of a generated topology ([topology] generate): the chain 1 -> 2 -> ... -> n,
// closed into a ring by n -> 1 when `ring` and n > 2. 0-based, weight 1.
std::vector<ExperimentConfig::Edge> GeneratedEdges(int n, bool ring);

// Which checks apply: a run without rendering (`--no-render`) skips the render-only ones
// ([render] snapshots inside the run), since nothing is rendered.
struct ExperimentChecks {
  bool render = true;
  // [run] plugin_path's folders exist. An exported scene opened on another machine keeps the
  // folders it was exported with, which need not be there (its plugins are built in).
  bool plugin_folders = true;
  static ExperimentChecks Rendering(bool render) {
    ExperimentChecks checks;
    checks.render = render;
    return checks;
  }
};

// Reads and checks an experiment file; `overrides` are "section.key=value" strings (TOML
// values) applied on top, e.g. "formation.rho=0.1". Throws ConfigError.
ExperimentConfig LoadExperiment(const std::string& path,
                                const std::vector<std::string>& overrides = {},
                                ExperimentChecks checks = {});

// The experiment file's text; a folder or an unreadable file is refused by name. Throws
// ConfigError.
std::string ReadExperimentText(const std::string& path);

// Same from text already in memory (tests); `path` names it in messages.
ExperimentConfig ParseExperiment(const std::string& text, const std::string& path,
                                 const std::vector<std::string>& overrides = {},
                                 ExperimentChecks checks = {});

}  // namespace mjf::runner

#endif  // MJFORMATION_CONFIG_CONFIG_HPP_
