// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// compute() must not allocate: this binary replaces malloc/calloc/realloc (forwarding to
// glibc's __libc_* entry points) and counts calls while the plugins' compute() and the core's
// Update() run. operator new and Eigen's allocator both end in malloc.
#include <dlfcn.h>
#include <gtest/gtest.h>
#include <mjformation/plugin.h>

#include <atomic>
#include <cmath>
#include <cstddef>
#include <mjformation/formation/continuous_smc.hpp>
#include <mjformation/formation/discrete_smc.hpp>
#include <mjformation/formation/shape.hpp>
#include <string>
#include <vector>

#include "count_allocations.hpp"

namespace {

constexpr double kPi = 3.14159265358979323846;

struct Swarm {
  std::vector<double> leader_weight = {1, 0, 0, 0, 0, 0};
  std::vector<int> from = {0, 1, 2, 3, 4, 0, 2, 5};
  std::vector<int> to = {1, 2, 3, 4, 5, 2, 4, 3};
  std::vector<double> weight = std::vector<double>(8, 1.0);
  std::unique_ptr<mjf::formation::Shape> shape =
      mjf::formation::MakeCircleShape(6, 10, 0.314, 0, kPi / 3);
  mjfGraph graph{6, leader_weight.data(), 8, from.data(), to.data(), weight.data()};
  mjfShape abi_shape = mjf::formation::ToAbi(*shape);
  std::vector<mjfVehicleState> states = std::vector<mjfVehicleState>(7);
  std::vector<mjfSetpoint> setpoints = std::vector<mjfSetpoint>(7);
};

TEST(NoAllocationTest, PluginComputeDoesNotAllocate) {
  void* handle = dlopen(MJF_FORMATION_PLUGIN_PATH, RTLD_NOW | RTLD_LOCAL);
  ASSERT_NE(handle, nullptr) << dlerror();
  auto entry = reinterpret_cast<mjfEntryFn>(dlsym(handle, MJF_ENTRY_SYMBOL));
  ASSERT_NE(entry, nullptr);
  int count = 0;
  const mjfPlugin* const* plugins = entry(&count);
  Swarm swarm;
  for (int k = 0; k < count; ++k) {
    const mjfPlugin* plugin = plugins[k];
    std::vector<const char*> keys, values;
    for (int a = 0; a < plugin->n_attributes; ++a) {
      keys.push_back(plugin->attributes[a].key);
      values.push_back(plugin->attributes[a].default_value);
    }
    char error[256] = "";
    mjfCreateContext ctx{};
    ctx.n_attributes = plugin->n_attributes;
    ctx.keys = keys.data();
    ctx.values = values.data();
    ctx.timestep = 0.01;
    ctx.vehicle = -1;
    ctx.n_vehicles = 7;
    ctx.graph = &swarm.graph;
    ctx.shape = &swarm.abi_shape;
    // Per-agent plugins: follower 0 hears the leader and follower 1 (messages built below).
    const bool agent = plugin->kind == MJF_KIND_FORMATION_AGENT;
    const int neighbours[1] = {1};
    const double weights[1] = {1.0};
    const mjfNeighbourhood hood{0, 6, 1.0, 1, neighbours, weights};
    if (agent) {
      ctx.graph = nullptr;
      ctx.vehicle = 1;
      ctx.neighbourhood = &hood;
    }
    ctx.error = error;
    ctx.error_size = sizeof(error);
    void* instance = plugin->create(&ctx);
    ASSERT_NE(instance, nullptr) << error;
    mjfStepContext step{};
    step.timestep = 0.01;
    step.n_vehicles = 7;
    step.states = swarm.states.data();
    step.setpoints = swarm.setpoints.data();
    mjfMessage messages[2] = {};  // [0] follower 1, [1] the leader
    messages[0].sender = 2;
    messages[1].sender = 0;
    mjfMessage outgoing{};
    mjfAgentInput input{};
    input.follower = 0;
    input.self = &swarm.states[1];
    input.n_messages = 1;
    input.messages = messages;
    input.leader = &messages[1];
    input.n_rounds = 1;
    input.outgoing = &outgoing;
    if (agent) {
      step.states = nullptr;
      step.setpoints = &swarm.setpoints[1];
      step.agent = &input;
    }
    for (int i = 1; i <= 6; ++i) swarm.states[i].pos[0] = i;
    allocations = 0;
    counting = true;
    int status = 0;
    for (int64_t s = 0; s < 200; ++s) {
      step.step = s;
      step.time = 0.01 * s;
      swarm.states[0].pos[0] = 20 * std::cos(0.157 * step.time);
      messages[1].state = swarm.states[0];
      messages[0].state = swarm.states[2];
      status |= plugin->compute(instance, &step);
    }
    counting = false;
    EXPECT_EQ(status, 0);
    EXPECT_EQ(allocations.load(), 0) << plugin->name << " allocated in compute()";
    plugin->destroy(instance);
  }
  dlclose(handle);
}

TEST(NoAllocationTest, CoreUpdateDoesNotAllocate) {
  const mjf::formation::Graph graph(6, {1, 0, 0, 0, 0, 0},
                                    {{0, 1}, {1, 2}, {2, 3}, {3, 4}, {4, 5}});
  mjf::formation::ContinuousSmc continuous(graph, {});
  mjf::formation::DiscreteSmc discrete(graph, {});
  mjf::formation::DiscreteSmcParams limited;
  limited.accel_limit = 3.6;  // the input-constrained reaching law, active from this start
  mjf::formation::DiscreteSmc constrained(graph, limited);
  std::vector<double> leader = {20, 0, 0, 3}, followers(24, 1.0), f(36, 0.5), g(36, 0.4);
  allocations = 0;
  counting = true;
  for (int k = 0; k < 100; ++k) {
    continuous.Update({leader.data(), followers.data(), f.data(), nullptr});
    discrete.Update({leader.data(), followers.data(), f.data(), g.data()});
    constrained.Update({leader.data(), followers.data(), f.data(), g.data()});
  }
  counting = false;
  EXPECT_EQ(allocations.load(), 0);
  EXPECT_GT(constrained.constraint_stats().constrained, 0);  // the constrained path ran
  // The counter works: a vector allocates.
  counting = true;
  std::vector<double>* probe = new std::vector<double>(100);
  counting = false;
  EXPECT_GT(allocations.load(), 0);
  delete probe;
}

}  // namespace
