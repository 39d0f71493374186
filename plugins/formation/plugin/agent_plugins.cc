// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The per-agent formation plugins, for distributed execution ([execution] mode = "per_agent"):
// smc_discrete_agent (eq. (48), formation::DiscreteSmcAgent, sampled every T and held),
// smc_continuous_agent (eq. (30), formation::ContinuousSmcAgent, every step) and
// consensus_linear_agent (formation::LinearConsensusAgent, every step), with the attributes of
// their swarm-level versions. One adapter, a template over the law. The u_j coupling is closed by
// what the host hands the instance (docs/NETWORK.md):
//   - agent->solved (coupling = central_solve): the host's exact solve, the reference;
//   - round r > 0 (coupling = jacobi): the neighbours' round r-1 iterates w_j (payload[0..1]);
//   - otherwise (round 0, or a round message lost): the neighbours' last inputs u_j.
// Outgoing payload, on sample steps only (n_payload = 0 in between): [0..1] w_i of this round,
// [2..3] R_i, [4..7] the leader's px, py, vx, vy as this follower knows it (relayed, one hop per
// sample, for the reference slots of followers without a leader link).
#include <cmath>
#include <cstdint>
#include <mjformation/formation/agent_laws.hpp>
#include <mjformation/formation/discrete_smc_agent.hpp>
#include <vector>

#include "adapter.hpp"
#include "plugins.hpp"

namespace mjf::formation::adapter {
namespace {

using plugin::kPayloadUsed;

template <typename Law>
struct Agent {
  // horizon: the law's look-ahead (T for the discrete law: F(k+1) at t + T), 0 otherwise.
  template <typename Params>
  Agent(const mjfCreateContext* ctx, const Params& params, int64_t steps, double horizon_s)
      : follower(ctx->neighbourhood->follower),
        leader_weight(ctx->neighbourhood->leader_weight),
        inbox(std::vector<int>(ctx->neighbourhood->neighbours,
                               ctx->neighbourhood->neighbours + ctx->neighbourhood->n_neighbours)),
        core(params, ctx->neighbourhood->leader_weight,
             std::vector<double>(ctx->neighbourhood->weights,
                                 ctx->neighbourhood->weights + ctx->neighbourhood->n_neighbours)),
        shape(*ctx->shape),
        steps_per_sample(steps),
        horizon(horizon_s),
        neighbour_pv(4 * inbox.neighbours().size()),
        neighbour_f_now(6 * inbox.neighbours().size()),
        neighbour_f_next(6 * inbox.neighbours().size()),
        neighbour_w(2 * inbox.neighbours().size()) {}
  int follower;
  double leader_weight;          // a_i0
  plugin::NeighbourInbox inbox;  // the neighbours' messages and the leader's state
  Law core;
  formation::AbiShape shape;
  int64_t steps_per_sample;
  double horizon;
  bool has_sample = false;
  // Sample k is due when the step the follower's clock reads enters a new period (step / steps
  // per sample changes; the host hands the step the follower's own clock reads): decided in round
  // 0; the later rounds of that sample take it again (last_round below).
  int64_t due_index = -1;
  bool sample_due = false;
  // The last exchange round computed for the current sample (-1: none, the sample was not
  // taken). A round r > 0 continues the sample when it is the next one and its step is still
  // in the sample's period: rounds carried over links run at later ticks, with the sample's
  // time and step handed back by the host (docs/NETWORK.md); between samples round r > 0 holds.
  int last_round = -1;
  // f_i(t) and f_i(t + horizon) of this follower, and the same for each neighbour: evaluated
  // one follower at a time (mjfShape.evaluate_one), so the cost is O(degree), not O(N).
  double own_f_now[6] = {0, 0, 0, 0, 0, 0};
  double own_f_now_time = NAN;  // the time own_f_now was evaluated at (NaN: not yet)
  double own_f_next[6] = {0, 0, 0, 0, 0, 0};
  std::vector<double> neighbour_pv, neighbour_f_now, neighbour_f_next, neighbour_w;
  // Everything above that a call leaves for the next (plugin_state.hpp).
  template <typename Visit>
  void VisitState(Visit& visit) {
    visit(has_sample, due_index, sample_due, last_round, own_f_now, own_f_now_time, own_f_next);
    visit(neighbour_pv, neighbour_f_now, neighbour_f_next, neighbour_w, inbox, core);
  }
};

void RequireNeighbourhood(const mjfCreateContext* ctx) {
  if (!ctx->neighbourhood || !ctx->shape) {
    throw std::invalid_argument(
        "per-agent formation plugin: the host passed no neighbourhood or shape (per-agent "
        "execution)");
  }
}

void* CreateDiscrete(const mjfCreateContext* ctx) {
  return plugin::CreateOrExplain(ctx, [&]() -> void* {
    RequireNeighbourhood(ctx);
    const formation::DiscreteSmcParams params = ParseDiscreteParams(plugin::Attributes(ctx));
    if (std::isfinite(params.accel_limit)) {
      // The constrained law needs c_i and z_i = (L_H^-1 e)_i, the swarm-wide solve (C1).
      throw std::invalid_argument(
          "attribute 'accel_limit': the per-agent protocol has no input-constrained variant "
          "(it needs the swarm-wide solve with L_H); use mode = \"central\" or accel_limit = "
          "\"none\"");
    }
    return new Agent<formation::DiscreteSmcAgent>(
        ctx, params, StepsPerSample(params.period, ctx->timestep), params.period);
  });
}

void* CreateContinuous(const mjfCreateContext* ctx) {
  return plugin::CreateOrExplain(ctx, [&]() -> void* {
    RequireNeighbourhood(ctx);
    const formation::ContinuousSmcParams params = ParseContinuousParams(plugin::Attributes(ctx));
    return new Agent<formation::ContinuousSmcAgent>(ctx, params, 1, 0.0);
  });
}

void* CreateConsensus(const mjfCreateContext* ctx) {
  return plugin::CreateOrExplain(ctx, [&]() -> void* {
    RequireNeighbourhood(ctx);
    const formation::LinearConsensusParams params = ParseConsensusParams(plugin::Attributes(ctx));
    return new Agent<formation::LinearConsensusAgent>(ctx, params, 1, 0.0);
  });
}

// w_j for every neighbour: this round's iterate when it got through, else from u_j.
template <typename Law>
void NeighbourCoupling(Agent<Law>& a, const mjfAgentInput& in) {
  for (size_t m = 0; m < a.inbox.neighbours().size(); ++m) {
    const mjfMessage& msg = *a.inbox.message(m);
    // The host marks a neighbour's message with round r - 1 only when that round's message got
    // through this tick (its state part stays the newest one held, which may be older).
    const bool fresh_round = in.round > 0 && msg.round == in.round - 1 && msg.n_payload >= 2;
    for (int axis = 0; axis < 2; ++axis) {
      const double u_j = std::isfinite(msg.input[axis]) ? msg.input[axis] : 0.0;
      a.neighbour_w[2 * m + axis] = fresh_round
                                        ? msg.payload[axis]
                                        : a.core.CouplingFromInput(static_cast<int>(m), axis, u_j);
    }
  }
}

template <typename Law>
void Sample(Agent<Law>& a, const mjfStepContext& ctx) {
  const mjfAgentInput& in = *ctx.agent;
  const int i = a.follower;
  const double next = ctx.time + a.horizon;  // F(k+1) for the discrete law
  a.shape.EvaluateOne(next, i, a.own_f_next);
  for (size_t m = 0; m < a.inbox.neighbours().size(); ++m) {
    const int j = a.inbox.neighbours()[m];
    plugin::ReadPlanarPv(a.inbox.message(m)->state, &a.neighbour_pv[4 * m]);
    a.shape.EvaluateOne(ctx.time, j, &a.neighbour_f_now[6 * m]);
    a.shape.EvaluateOne(next, j, &a.neighbour_f_next[6 * m]);
  }
  double own_pv[4];
  plugin::ReadPlanarPv(*in.self, own_pv);
  a.core.Prepare(own_pv, a.inbox.leader_pv(), a.own_f_now, a.own_f_next, a.neighbour_pv.data(),
                 a.neighbour_f_now.data(), a.neighbour_f_next.data());
  if (in.solved) {
    a.core.UseSolved(in.solved);
  } else {
    NeighbourCoupling(a, in);
    a.core.Solve(a.neighbour_w.data());
  }
  a.has_sample = true;
}

template <typename Law>
int Compute(void* instance, const mjfStepContext* ctx) {
  return plugin::ComputeOrExplain(ctx, [&] {
    auto& a = *static_cast<Agent<Law>*>(instance);
    if (!ctx->agent || !ctx->agent->self || !ctx->setpoints || !ctx->agent->outgoing) {
      return plugin::Fail(ctx,
                          "a per-agent formation plugin needs per-agent execution (ctx->agent)");
    }
    const mjfAgentInput& in = *ctx->agent;
    const bool ready = a.inbox.Gather(in, a.leader_weight);
    if (!ready && !a.has_sample) return 0;  // nothing heard yet: hold the initial setpoint
    // Every round of a tick runs at the same time: f_i(t) once per tick, not once per round.
    if (!(ctx->time == a.own_f_now_time)) {
      a.shape.EvaluateOne(ctx->time, a.follower, a.own_f_now);
      a.own_f_now_time = ctx->time;
    }
    const int64_t index = ctx->step / a.steps_per_sample;
    if (in.round == 0) {
      a.sample_due = !a.has_sample || index != a.due_index;
      a.due_index = index;
    } else {
      // Instantaneous rounds run in the tick of round 0, so this is true exactly when round 0
      // sampled in this tick; rounds over links may come ticks later.
      a.sample_due = a.last_round == in.round - 1 && index == a.due_index;
    }
    const bool sample_step = a.sample_due;
    // A sample needs a message from every neighbour (and the leader when a_i0 > 0): until
    // each has been heard once, the initial setpoint holds.
    const bool sampled = ready && sample_step;
    if (sampled) Sample(a, *ctx);
    if (in.round == 0 && sample_step) a.last_round = sampled ? 0 : -1;
    if (in.round > 0 && sampled) a.last_round = in.round;
    mjfSetpoint& sp = *ctx->setpoints;
    for (int axis = 0; axis < 2; ++axis) {
      // The reference slot x_0 + f_i (a diagnostic: attitude plugins use acc and pos[2]); the
      // own state until the leader's state has been heard or relayed.
      const double* f = a.own_f_now;
      const double* leader = a.inbox.leader_pv();
      sp.pos[axis] = a.inbox.knows_leader() ? leader[axis] + f[axis] : in.self->pos[axis];
      sp.vel[axis] = a.inbox.knows_leader() ? leader[2 + axis] + f[2 + axis] : in.self->vel[axis];
      sp.acc[axis] = a.core.acceleration()[axis];  // zero-order hold between samples
      if (a.core.sliding()) sp.sliding[axis] = a.core.sliding()[axis];
    }
    mjfMessage& out = *in.outgoing;
    // Between samples there is nothing new to exchange (no Jacobi round, no central solve).
    out.n_payload = sampled ? kPayloadUsed : 0;
    out.payload[0] = a.core.coupling()[0];
    out.payload[1] = a.core.coupling()[1];
    out.payload[2] = a.core.rhs()[0];
    out.payload[3] = a.core.rhs()[1];
    std::copy(a.inbox.leader_pv(), a.inbox.leader_pv() + 4, out.payload + plugin::kPayloadLeader);
    return 0;
  });
}

template <typename Law>
void Reset(void* instance) {
  static_cast<Agent<Law>*>(instance)->has_sample = false;
  static_cast<Agent<Law>*>(instance)->last_round = -1;
}

template <typename Law>
void Destroy(void* instance) {
  delete static_cast<Agent<Law>*>(instance);
}

void ReportDiscrete(void* instance, mjfReportFn emit, void* user) {
  const auto& a = *static_cast<const Agent<formation::DiscreteSmcAgent>*>(instance);
  emit(user, plugin::contract::kDelta,
       a.core.delta());  // the host reports the largest over the followers
  emit(user, plugin::contract::kPeriod, a.core.params().period);
  emit(user, "steps_per_sample", static_cast<double>(a.steps_per_sample));
  emit(user, plugin::contract::kQ,
       a.core.params().q);  // for the predicted delay margin (docs/NETWORK.md)
}

template <typename Law>
constexpr mjfPlugin AgentPlugin(const char* name, const char* doc, int n_attributes,
                                const mjfAttribute* attributes,
                                void* (*create)(const mjfCreateContext*),
                                void (*report)(void*, mjfReportFn, void*)) {
  static_assert(plugin::kHasVisitState<Law>,
                "a per-agent formation law lists its state: template <typename Visit> void "
                "VisitState(Visit&) (mjformation/plugin_state.hpp)");
  return {MJF_ABI_VERSION,
          name,
          MJF_KIND_FORMATION_AGENT,
          doc,
          n_attributes,
          attributes,
          0,
          nullptr,
          create,
          &Compute<Law>,
          &Reset<Law>,
          &Destroy<Law>,
          report,
          &plugin::StateSizeOf<Agent<Law>>,
          &plugin::GetStateOf<Agent<Law>>,
          &plugin::SetStateOf<Agent<Law>>};
}

}  // namespace

const mjfPlugin kSmcDiscreteAgent = AgentPlugin<formation::DiscreteSmcAgent>(
    "smc_discrete_agent",
    "discrete sliding-mode formation tracking, eq. (48), one instance per follower",
    kDiscreteAttributeCount, kDiscreteAttributes, &CreateDiscrete, &ReportDiscrete);
const mjfPlugin kSmcContinuousAgent = AgentPlugin<formation::ContinuousSmcAgent>(
    "smc_continuous_agent",
    "continuous sliding-mode formation tracking, eq. (30), one instance per follower",
    kContinuousAttributeCount, kContinuousAttributes, &CreateContinuous, nullptr);
const mjfPlugin kConsensusLinearAgent = AgentPlugin<formation::LinearConsensusAgent>(
    "consensus_linear_agent", "linear consensus formation tracking, one instance per follower",
    kConsensusAttributeCount, kConsensusAttributes, &CreateConsensus, nullptr);

}  // namespace mjf::formation::adapter
