// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// `mjformation benchmark`: the formation-tracking board (docs/BENCHMARK.md). The work is done by
// analysis/benchmark.py, which flies one `mjformation run` per law, scenario and seed with this
// very executable, scores the runs (analysis/mjfanalysis/benchmark_metrics.py) and writes the
// board; this command only starts it, as `view` starts mjformation-view.
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "mjformation/app/cli.hpp"
#include "mjformation/config/paths.hpp"

namespace mjf::runner {

void AddBenchmarkCommand(CLI::App& app, CliCommands* c) {
  c->benchmark = app.add_subcommand(
      "benchmark",
      "Fly the formation-tracking benchmark (laws x scenarios x seeds) and write its board "
      "(docs/BENCHMARK.md); `benchmark --help` lists its options");
  c->benchmark->allow_extras();
  c->benchmark->prefix_command();  // every argument goes to analysis/benchmark.py as is
  c->benchmark->set_help_flag();   // so does --help: the options are the script's
}

int BenchmarkCommand(const CliCommands& c) {
  // analysis/ runs on Debian's Python with numpy and matplotlib (analysis/README.md), unless
  // MJF_PYTHON names another.
  const char* env = std::getenv("MJF_PYTHON");
  const std::string python = env && *env ? env : "/usr/bin/python3";
  const std::string script = MJF_BENCHMARK_SCRIPT;
  if (!IsFile(script)) {
    std::fprintf(stderr,
                 "mjformation benchmark: error: %s is missing; the benchmark runs from a clone "
                 "of the repository (its analysis/ and experiments/benchmark/)\n",
                 script.c_str());
    return 1;
  }
  // The package mjfanalysis beside the script, found as analysis/README.md says: PYTHONPATH.
  const std::string analysis = script.substr(0, script.find_last_of('/'));
  const char* path = std::getenv("PYTHONPATH");
  setenv("PYTHONPATH", (path && *path ? analysis + ":" + path : analysis).c_str(), 1);
  std::vector<std::string> args = {python, script, "--mjformation",
                                   ExecutableDir() + "/mjformation"};
  for (const std::string& a : c.benchmark->remaining()) args.push_back(a);
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  execv(python.c_str(), argv.data());
  std::perror(("mjformation benchmark: cannot start " + python +
               " (set MJF_PYTHON to a Python with numpy and matplotlib)")
                  .c_str());
  return 1;
}

}  // namespace mjf::runner
