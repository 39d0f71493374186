// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// `mjformation bench`: not yet implemented; see issue 4.
#include "mjformation/runner/cli.hpp"

namespace mjf::runner {

void AddBenchCommand(CLI::App& app, CliCommands* commands) {
  (void)app;
  commands->bench = nullptr;
}

int BenchCommand(const CliCommands& commands) {
  (void)commands;
  return 2;
}

}  // namespace mjf::runner
