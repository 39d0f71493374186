// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// `--set section.key=value` applied to an experiment file's TOML document, for the readers that
// need the document itself rather than ExperimentConfig (export carries the document into a
// scene). Needs toml++: include it only where toml++ is linked.
#ifndef MJFORMATION_CONFIG_OVERRIDES_HPP_
#define MJFORMATION_CONFIG_OVERRIDES_HPP_

#include <toml++/toml.h>

#include <string>
#include <vector>

namespace mjf::runner {

// Applies "section.key=value" overrides (TOML values) to `root`. `section={...}` replaces the
// section's plain keys and keeps its sub-tables. Throws ConfigError naming the override.
void ApplyOverrides(toml::table& root, const std::vector<std::string>& overrides);

}  // namespace mjf::runner

#endif  // MJFORMATION_CONFIG_OVERRIDES_HPP_
