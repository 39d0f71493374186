// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "adapter.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "agent_adapter.hpp"

namespace mjf::formation::adapter {
namespace {

const mjfGraph& RequireGraph(const mjfCreateContext* ctx) {
  if (ctx->graph == nullptr) {
    throw std::invalid_argument("formation plugin: the host passed no graph (ctx->graph)");
  }
  return *ctx->graph;
}

const mjfShape& RequireShape(const mjfCreateContext* ctx) {
  if (ctx->shape == nullptr) {
    throw std::invalid_argument("formation plugin: the host passed no shape (ctx->shape)");
  }
  return *ctx->shape;
}

}  // namespace

SwarmSetup::SwarmSetup(const mjfCreateContext* ctx)
    : graph(formation::Graph::FromAbi(RequireGraph(ctx))), shape(RequireShape(ctx)) {
  const int n = graph.num_followers();
  if (shape.num_followers() != n) {
    throw std::invalid_argument("formation plugin: the shape has " +
                                std::to_string(shape.num_followers()) +
                                " followers but the graph has " + std::to_string(n));
  }
  if (ctx->n_vehicles != n + 1) {
    throw std::invalid_argument(
        "formation plugin: n_vehicles = " + std::to_string(ctx->n_vehicles) +
        " but the graph has " + std::to_string(n) + " followers (expected 1 + " +
        std::to_string(n) + ")");
  }
  graph.RequireSpanningTree();
}

formation::SlidingGains ParseGains(const plugin::Attributes& attributes) {
  const std::vector<double> k = attributes.Numbers(kKeyGains, 2);
  return formation::SlidingGains{k[0], k[1]};
}

double ParseAccelLimit(const plugin::Attributes& attributes) {
  const std::string text = attributes.String(kKeyAccelLimit);
  if (text == "none") return std::numeric_limits<double>::infinity();
  if (text == plugin::contract::kFromVehicle) {
    throw std::invalid_argument(
        "attribute 'accel_limit': \"vehicle\" must be resolved by the host from the followers' "
        "vehicle info (this host did not)");
  }
  const double value = attributes.Number(kKeyAccelLimit);
  if (!std::isfinite(value)) {
    throw std::invalid_argument(
        "attribute 'accel_limit': must be \"none\", \"vehicle\" or a "
        "finite number of m/s^2 (got '" +
        text + "')");
  }
  return value;
}

SwarmBuffers::SwarmBuffers(int n_followers)
    : leader_pv(4, 0.0),
      follower_pv(4 * n_followers, 0.0),
      shape_now(6 * n_followers, 0.0),
      shape_next(6 * n_followers, 0.0),
      n_(n_followers) {}

bool SwarmBuffers::Read(const mjfStepContext* ctx) {
  if (ctx->n_vehicles != n_ + 1 || ctx->states == nullptr || ctx->setpoints == nullptr) {
    return false;
  }
  for (int vehicle = 0; vehicle <= n_; ++vehicle) {
    const mjfVehicleState& state = ctx->states[vehicle];
    double* pv = vehicle == 0 ? leader_pv.data() : follower_pv.data() + 4 * (vehicle - 1);
    plugin::ReadPlanarPv(state, pv);
    for (int k = 0; k < 4; ++k) {
      if (!std::isfinite(pv[k])) return false;
    }
  }
  return true;
}

formation::FormationInput SwarmBuffers::Input() const {
  formation::FormationInput input;
  input.leader_pv = leader_pv.data();
  input.follower_pv = follower_pv.data();
  input.shape_now = shape_now.data();
  input.shape_next = shape_next.data();
  return input;
}

void WriteSlots(const SwarmBuffers& buffers, mjfSetpoint* setpoints) {
  for (int i = 0; i < buffers.n(); ++i) {
    mjfSetpoint& sp = setpoints[i + 1];
    for (int axis = 0; axis < 2; ++axis) {
      sp.pos[axis] = buffers.leader_pv[axis] + buffers.shape_now[6 * i + axis];
      sp.vel[axis] = buffers.leader_pv[2 + axis] + buffers.shape_now[6 * i + 2 + axis];
    }
  }
}

void WriteCommands(int n, const double* acceleration, const double* sliding,
                   mjfSetpoint* setpoints) {
  for (int i = 0; i < n; ++i) {
    mjfSetpoint& sp = setpoints[i + 1];
    for (int axis = 0; axis < 2; ++axis) {
      sp.acc[axis] = acceleration[2 * i + axis];
      if (sliding != nullptr) sp.sliding[axis] = sliding[2 * i + axis];
    }
  }
}

void RequireNeighbourhood(const mjfCreateContext* ctx) {
  if (!ctx->neighbourhood || !ctx->shape) {
    throw std::invalid_argument(
        "per-agent formation plugin: the host passed no neighbourhood or shape (per-agent "
        "execution)");
  }
}

}  // namespace mjf::formation::adapter
