// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// A scene stepped in MuJoCo's own C loop, as a C program embedding stock MuJoCo steps it: the
// plugin library loaded, the scene compiled, then mj_step `steps` times from the initial state,
// timed (wall clock) with nothing else in the loop. Not a test (timing): dev/native_overhead.py
// --stepper c puts it beside `mjformation run --no-render`.
//   scene_step_time PLUGIN_LIBRARY SCENE_XML STEPS   ->  prints the seconds of the loop
#include <mujoco/mujoco.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: %s PLUGIN_LIBRARY SCENE_XML STEPS\n", argv[0]);
    return 2;
  }
  mj_loadPluginLibrary(argv[1]);
  char error[1024] = {0};
  mjModel* m = mj_loadXML(argv[2], nullptr, error, sizeof(error));
  if (!m) {
    std::fprintf(stderr, "%s: %s\n", argv[2], error);
    return 1;
  }
  mjData* d = mj_makeData(m);
  const long steps = std::atol(argv[3]);
  const auto start = std::chrono::steady_clock::now();
  for (long k = 0; k < steps; ++k) mj_step(m, d);
  const std::chrono::duration<double> seconds = std::chrono::steady_clock::now() - start;
  std::printf("%.6f\n", seconds.count());
  mj_deleteData(d);
  mj_deleteModel(m);
  return 0;
}
