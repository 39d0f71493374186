// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The `mjformation` command: parses the command line and calls the runner library.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "mjformation/runner/cli.hpp"
#include "mjformation/runner/interrupt.hpp"

int main(int argc, char** argv) {
  CLI::App app{"mjformation: distributed formation control of quadrotor swarms in MuJoCo"};
  mjf::runner::CliCommands commands;
  mjf::runner::AddCommands(app, &commands);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version end here with 0; every misuse of the command line exits 2.
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  mjf::runner::InstallInterruptHandlers();
  return mjf::runner::Dispatch(app, commands);
}
