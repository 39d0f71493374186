// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// `mjformation sweep`: runs an experiment over the Cartesian product of parameter values and,
// with --seeds N, N seeds per grid cell (Monte Carlo); one run directory per run; the tables
// sweep.csv / sweep.json. The plan, the execution and the tables are in sweep_plan.cc,
// sweep_execute.cc and sweep_tables.cc.
#include "sweep.hpp"

#include <fmt/format.h>

#include <cstdio>

#include "mjformation/app/cli.hpp"
#include "mjformation/run/interrupt.hpp"

namespace mjf::runner {

int SweepCommand(const CliCommands& c) {
  using namespace sweep;
  InstallInterruptHandlers();
  const SweepPlan plan = PlanSweep(c);
  std::vector<RunOutcome> outcomes;
  if (UnderMpiLauncher()) {
    if (RunMpi(plan, c, &outcomes) != 0) return 0;  // worker ranks: rank 0 writes the tables
  } else {
    const std::vector<size_t> todo = PrepareOutput(plan, c, &outcomes);
    Progress progress(plan, &outcomes, todo.size());
    RunThreaded(plan, c, todo, &progress);
  }
  WriteTables(plan, outcomes);
  int failures = 0, not_run = 0;
  for (const RunOutcome& o : outcomes) {
    failures += o.state == RunOutcome::kFinished && !o.complete();
    not_run += o.state == RunOutcome::kNotRun;
  }
  std::printf("%s", SummaryText(plan, outcomes).c_str());
  std::fprintf(
      stderr, "sweep: tables in %s/sweep.csv and sweep.json%s%s%s\n", plan.out.c_str(),
      plan.seeds ? " (per cell; per run: sweep_runs.csv)" : "",
      failures ? fmt::format(" ({} failed or stopped early)", RunCount(failures)).c_str() : "",
      not_run ? fmt::format("; interrupted: {} not run, finish with --resume", RunCount(not_run))
                    .c_str()
              : "");
  if (not_run) return InterruptRequested() ? InterruptExitCode() : 3;
  return failures ? 3 : 0;
}

void AddSweepCommand(CLI::App& app, CliCommands* c) {
  c->sweep = app.add_subcommand(
      "sweep", "Run an experiment over a grid of parameter values and seeds, several at once");
  c->sweep->add_option("experiment", c->experiment, "experiment file (TOML)")->required();
  c->sweep
      ->add_option("--vary", c->sweep_vary,
                   "a swept parameter: section.key=v1,v2,... (repeat for a grid)")
      ->allow_extra_args(false);
  c->sweep
      ->add_option("--seeds", c->sweep_seeds,
                   "Monte Carlo: N runs per grid cell with seeds run.seed + 0..N-1; "
                   "sweep.csv then holds per cell mean, std and 95 % CI of every metric")
      ->check(IntegerOption(1, 100000));
  c->sweep->add_option("--set", c->overrides, "fixed override: section.key=value");
  c->sweep->add_option("--out,-o", c->out, "sweep directory (default: runs/<run.name>_sweep)");
  c->sweep->add_option("--jobs,-j", c->sweep_jobs, "simulations at once (threads)")
      ->capture_default_str()
      ->check(IntegerOption(1, 1024));
  c->sweep->add_option("--plugin-path", c->plugin_path, "extra folder to search for plugins")
      ->check(CLI::ExistingDirectory);
  c->sweep->add_flag("--overwrite", c->overwrite, "replace an existing sweep directory");
  c->sweep
      ->add_flag("--resume", c->sweep_resume,
                 "finish an interrupted sweep: rerun only runs missing or incomplete")
      ->excludes("--overwrite");
  c->sweep->add_flag(
      "--no-render", c->no_render,
      "skip snapshots and video (and the render-only checks: snapshot times beyond the run)");
}

}  // namespace mjf::runner
