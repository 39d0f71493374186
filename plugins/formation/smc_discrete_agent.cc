// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// smc_discrete_agent: the discrete sliding-mode protocol (48) run by one follower, for
// distributed execution ([execution] mode = "per_agent"). Same attributes and sampling as
// smc_discrete; the maths is core::DiscreteSmcAgent. The u_j(k) coupling of (48) is closed by
// what the host hands this instance (docs/NETWORK.md):
//   - agent->solved (coupling = central_solve): the host's exact solve, the reference;
//   - round r > 0 (coupling = jacobi): the neighbours' round r-1 iterates w_j (payload[0..1]);
//   - otherwise (round 0, or a round message lost): the neighbours' last inputs u_j.
// Outgoing payload, on sample steps only (n_payload = 0 in between): [0..1] w_i of this round,
// [2..3] R_i, [4..7] the leader's px, py, vx, vy as this follower knows it (relayed, one hop per
// sample, for the reference slots of followers without a leader link).
#include <cmath>
#include <cstdint>
#include <mjformation/core/discrete_smc_agent.hpp>
#include <vector>

#include "adapter.hpp"
#include "plugins.hpp"

namespace mjf::formation {
namespace {

constexpr int kPayloadUsed = 8;

struct Agent {
  Agent(const mjfCreateContext* ctx, const core::DiscreteSmcParams& params, int64_t steps)
      : follower(ctx->neighbourhood->follower),
        leader_weight(ctx->neighbourhood->leader_weight),
        neighbours(ctx->neighbourhood->neighbours,
                   ctx->neighbourhood->neighbours + ctx->neighbourhood->n_neighbours),
        core(params, ctx->neighbourhood->leader_weight,
             std::vector<double>(ctx->neighbourhood->weights,
                                 ctx->neighbourhood->weights + ctx->neighbourhood->n_neighbours)),
        shape(*ctx->shape),
        steps_per_sample(steps),
        shape_now(6 * static_cast<size_t>(shape.num_followers())),
        shape_next(shape_now.size()),
        neighbour_pv(4 * neighbours.size()),
        neighbour_f_now(6 * neighbours.size()),
        neighbour_f_next(6 * neighbours.size()),
        neighbour_w(2 * neighbours.size()),
        found(neighbours.size()) {}
  int follower;
  double leader_weight;         // a_i0
  std::vector<int> neighbours;  // follower indices j, 0-based
  core::DiscreteSmcAgent core;
  core::AbiShape shape;
  int64_t steps_per_sample;
  bool has_sample = false;
  double leader_pv[4] = {0, 0, 0, 0};
  bool knows_leader = false;
  std::vector<double> shape_now, shape_next;
  std::vector<double> neighbour_pv, neighbour_f_now, neighbour_f_next, neighbour_w;
  std::vector<const mjfMessage*> found;  // [m] the message of neighbour m this call
};

void* Create(const mjfCreateContext* ctx) {
  return plugin::CreateOrExplain(ctx, [&]() -> void* {
    if (!ctx->neighbourhood || !ctx->shape) {
      throw std::invalid_argument(
          "smc_discrete_agent: the host passed no neighbourhood or shape (per-agent execution)");
    }
    const core::DiscreteSmcParams params = ParseDiscreteParams(plugin::Attributes(ctx));
    return new Agent(ctx, params, StepsPerSample(params.period, ctx->timestep));
  });
}

void ReadPv(const mjfVehicleState& s, double* pv) {
  pv[0] = s.pos[0];
  pv[1] = s.pos[1];
  pv[2] = s.vel[0];
  pv[3] = s.vel[1];
}

// Finds each neighbour's message and the leader's state (own link, else a neighbour's relay);
// false while something the protocol needs has not arrived yet.
bool Gather(Agent& a, const mjfAgentInput& in) {
  std::fill(a.found.begin(), a.found.end(), nullptr);
  for (int k = 0; k < in.n_messages; ++k) {
    for (size_t m = 0; m < a.neighbours.size(); ++m) {
      if (in.messages[k].sender == a.neighbours[m] + 1) a.found[m] = &in.messages[k];
    }
  }
  if (in.leader) {
    ReadPv(in.leader->state, a.leader_pv);
    a.knows_leader = true;
  } else {
    for (const mjfMessage* m : a.found) {
      if (m && m->n_payload >= kPayloadUsed) {
        std::copy(m->payload + 4, m->payload + 8, a.leader_pv);
        a.knows_leader = true;
        break;
      }
    }
  }
  for (const mjfMessage* m : a.found) {
    if (!m) return false;
  }
  // a_i0 > 0: (48) needs the leader's own message; otherwise its state only feeds the slots.
  return a.leader_weight <= 0.0 || in.leader != nullptr;
}

// w_j for every neighbour: this round's iterate when it got through, else from u_j.
void NeighbourCoupling(Agent& a, const mjfAgentInput& in, double time) {
  for (size_t m = 0; m < a.neighbours.size(); ++m) {
    const mjfMessage& msg = *a.found[m];
    const bool fresh_round =
        in.round > 0 && msg.round == in.round - 1 && msg.send_time == time && msg.n_payload >= 2;
    for (int axis = 0; axis < 2; ++axis) {
      const double u_j = std::isfinite(msg.input[axis]) ? msg.input[axis] : 0.0;
      a.neighbour_w[2 * m + axis] = fresh_round
                                        ? msg.payload[axis]
                                        : a.core.CouplingFromInput(static_cast<int>(m), axis, u_j);
    }
  }
}

void Sample(Agent& a, const mjfStepContext& ctx) {
  const mjfAgentInput& in = *ctx.agent;
  const int i = a.follower;
  a.shape.Evaluate(ctx.time + a.core.params().period, a.shape_next.data());  // F(k+1)
  for (size_t m = 0; m < a.neighbours.size(); ++m) {
    const int j = a.neighbours[m];
    ReadPv(a.found[m]->state, &a.neighbour_pv[4 * m]);
    std::copy_n(&a.shape_now[6 * j], 6, &a.neighbour_f_now[6 * m]);
    std::copy_n(&a.shape_next[6 * j], 6, &a.neighbour_f_next[6 * m]);
  }
  double own_pv[4];
  ReadPv(*in.self, own_pv);
  a.core.Prepare(own_pv, a.leader_pv, &a.shape_now[6 * i], &a.shape_next[6 * i],
                 a.neighbour_pv.data(), a.neighbour_f_now.data(), a.neighbour_f_next.data());
  if (in.solved) {
    a.core.UseSolved(in.solved);
  } else {
    NeighbourCoupling(a, in, ctx.time);
    a.core.Solve(a.neighbour_w.data());
  }
  a.has_sample = true;
}

int Compute(void* instance, const mjfStepContext* ctx) {
  return plugin::ComputeOrExplain(ctx, [&] {
    auto& a = *static_cast<Agent*>(instance);
    if (!ctx->agent || !ctx->agent->self || !ctx->setpoints || !ctx->agent->outgoing) {
      return plugin::Fail(ctx, "smc_discrete_agent needs per-agent execution (ctx->agent)");
    }
    const mjfAgentInput& in = *ctx->agent;
    const bool ready = Gather(a, in);
    if (!ready && !a.has_sample) return 0;  // nothing heard yet: hold the initial setpoint
    a.shape.Evaluate(ctx->time, a.shape_now.data());
    const bool sample_step = !a.has_sample || ctx->step % a.steps_per_sample == 0;
    // A sample needs a message from every neighbour (and the leader when a_i0 > 0): until
    // each has been heard once, the initial setpoint holds.
    const bool sampled = ready && sample_step;
    if (sampled) Sample(a, *ctx);
    mjfSetpoint& sp = *ctx->setpoints;
    for (int axis = 0; axis < 2; ++axis) {
      // The reference slot x_0 + f_i (a diagnostic: attitude plugins use acc and pos[2]); the
      // own state until the leader's state has been heard or relayed.
      const double* f = &a.shape_now[6 * a.follower];
      sp.pos[axis] = a.knows_leader ? a.leader_pv[axis] + f[axis] : in.self->pos[axis];
      sp.vel[axis] = a.knows_leader ? a.leader_pv[2 + axis] + f[2 + axis] : in.self->vel[axis];
      sp.acc[axis] = a.core.acceleration()[axis];  // zero-order hold between samples
      sp.sliding[axis] = a.core.sliding()[axis];
    }
    mjfMessage& out = *in.outgoing;
    // Between samples there is nothing new to exchange (no Jacobi round, no central solve).
    out.n_payload = sampled ? kPayloadUsed : 0;
    out.payload[0] = a.core.coupling()[0];
    out.payload[1] = a.core.coupling()[1];
    out.payload[2] = a.core.rhs()[0];
    out.payload[3] = a.core.rhs()[1];
    std::copy(a.leader_pv, a.leader_pv + 4, out.payload + 4);
    return 0;
  });
}

void Reset(void* instance) { static_cast<Agent*>(instance)->has_sample = false; }

void Destroy(void* instance) { delete static_cast<Agent*>(instance); }

void Report(void* instance, mjfReportFn emit, void* user) {
  const auto& a = *static_cast<const Agent*>(instance);
  emit(user, "delta", a.core.delta());  // the host reports the largest over the followers
  emit(user, "period", a.core.params().period);
  emit(user, "steps_per_sample", static_cast<double>(a.steps_per_sample));
}

}  // namespace

const mjfPlugin kSmcDiscreteAgent = {
    MJF_ABI_VERSION,
    "smc_discrete_agent",
    MJF_KIND_FORMATION_AGENT,
    "discrete sliding-mode formation tracking, eq. (48), one instance per follower",
    kDiscreteAttributeCount,
    kDiscreteAttributes,
    0,
    nullptr,
    &Create,
    &Compute,
    &Reset,
    &Destroy,
    &Report,
};

}  // namespace mjf::formation
