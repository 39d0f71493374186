// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The `mjformation` command: the runner library's command line, with Ctrl-C / SIGTERM / SIGHUP
// handled.
#include "mjformation/app/cli.hpp"
#include "mjformation/run/interrupt.hpp"

int main(int argc, char** argv) {
  mjf::runner::InstallInterruptHandlers();
  return mjf::runner::RunCommandLine(argc, argv);
}
