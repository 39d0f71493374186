// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// What a leader guidance plugin costs per physics step: compute() through the plugin ABI
// (dlopen, as the runner calls it), timed over many steps of a leader flying on an ideal double
// integrator. Not a test (timing): `leader_cost [steps]` prints ns per call for every leader;
// docs/PERFORMANCE.md compares it with a step of the full pipeline.
#include <dlfcn.h>
#include <mjformation/plugin.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  const long steps = argc > 1 ? std::atol(argv[1]) : 2000000;
  void* handle = dlopen(MJF_GUIDANCE_PLUGIN, RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    std::fprintf(stderr, "%s\n", dlerror());
    return 1;
  }
  auto entry = reinterpret_cast<mjfEntryFn>(dlsym(handle, MJF_ENTRY_SYMBOL));
  int count = 0;
  const mjfPlugin* const* plugins = entry(&count);
  const std::map<std::string, std::map<std::string, std::string>> overrides = {
      {"trajectory", {{"file", MJF_SOURCE_DIR "/experiments/leaders/data/recorded_path.csv"}}},
      {"hover", {{"position", "0 0 5"}}},
  };
  std::printf("%-14s %10s\n", "leader", "ns/step");
  for (int p = 0; p < count; ++p) {
    const mjfPlugin& plugin = *plugins[p];
    std::vector<std::string> keys, values;
    for (int i = 0; i < plugin.n_attributes; ++i) {
      keys.push_back(plugin.attributes[i].key);
      auto o = overrides.find(plugin.name);
      auto v = o == overrides.end() ? o->second.end() : o->second.find(keys.back());
      values.push_back(o != overrides.end() && v != o->second.end()
                           ? v->second
                           : plugin.attributes[i].default_value);
    }
    std::vector<const char*> key_ptrs, value_ptrs;
    for (auto& k : keys) key_ptrs.push_back(k.c_str());
    for (auto& v : values) value_ptrs.push_back(v.c_str());
    char error[512] = {0};
    mjfCreateContext ctx{};
    ctx.n_attributes = plugin.n_attributes;
    ctx.keys = key_ptrs.data();
    ctx.values = value_ptrs.data();
    ctx.timestep = 0.001;
    ctx.vehicle = 0;
    ctx.n_vehicles = 1;
    const double start[3] = {20, 0, 5};
    ctx.initial_pos = start;
    ctx.error = error;
    ctx.error_size = sizeof(error);
    void* instance = plugin.create(&ctx);
    if (!instance) {
      std::fprintf(stderr, "%s: %s\n", plugin.name, error);
      continue;
    }
    mjfVehicleState state{};
    state.pos[0] = 20;
    state.pos[2] = 5;
    mjfSetpoint setpoint{};
    mjfStepContext step{};
    step.timestep = 0.001;
    step.n_vehicles = 1;
    step.states = &state;
    step.setpoints = &setpoint;
    step.error = error;
    step.error_size = sizeof(error);
    const auto t0 = std::chrono::steady_clock::now();
    for (long k = 0; k < steps; ++k) {
      step.step = k;
      step.time = k * 0.001;
      if (plugin.compute(instance, &step) != 0) {
        std::fprintf(stderr, "%s: %s\n", plugin.name, error);
        break;
      }
      for (int a = 0; a < 2; ++a) {  // the leader flies its own command (ideal, 1 ms)
        state.pos[a] += 0.001 * state.vel[a] + 0.5e-6 * setpoint.acc[a];
        state.vel[a] += 0.001 * setpoint.acc[a];
      }
    }
    const double ns =
        std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count();
    std::printf("%-14s %10.1f\n", plugin.name, ns / steps);
    plugin.destroy(instance);
  }
  dlclose(handle);
  return 0;
}
