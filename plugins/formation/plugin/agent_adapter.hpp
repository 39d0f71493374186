// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// What the per-agent formation plugins share, for distributed execution ([execution] mode =
// "per_agent"; one file each: smc_discrete_agent.cc, smc_continuous_agent.cc,
// consensus_linear_agent.cc and the laws from the literature, <law>_agent.cc): AgentPlugin<Law>,
// the descriptor with the compute, reset and destroy of one instance per follower, over the law's
// per-agent core (formation::DiscreteSmcAgent, ContinuousSmcAgent, LinearConsensusAgent,
// literature_agents.hpp). A core whose state advances with time has Advance(time), called before
// each Prepare, and Reset(), called by reset(). The u_j coupling is closed by what the host hands
// the instance (docs/NETWORK.md):
//   - agent->solved (coupling = central_solve): the host's exact solve, the reference;
//   - round r > 0 (coupling = jacobi): the neighbours' round r-1 iterates w_j (payload[0..1]);
//   - otherwise (round 0, or a round message lost): the neighbours' last inputs u_j.
// Outgoing payload, on sample steps only (n_payload = 0 in between): [0..1] w_i of this round,
// [2..3] R_i, [4..7] the leader's px, py, vx, vy as this follower knows it (relayed, one hop per
// sample, for the reference slots of followers without a leader link).
#ifndef MJFORMATION_PLUGINS_FORMATION_AGENT_ADAPTER_HPP_
#define MJFORMATION_PLUGINS_FORMATION_AGENT_ADAPTER_HPP_

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <type_traits>
#include <utility>
#include <vector>

#include "adapter.hpp"

namespace mjf::formation::adapter {

namespace law_detail {
template <typename Law, typename = void>
struct AdvancesWithTime : std::false_type {};
template <typename Law>
struct AdvancesWithTime<Law, std::void_t<decltype(std::declval<Law&>().Advance(0.0))>>
    : std::true_type {};
}  // namespace law_detail

template <typename Law>
struct AgentInstance {
  // horizon: the law's look-ahead (T for the discrete law: F(k+1) at t + T), 0 otherwise.
  template <typename Params>
  AgentInstance(const mjfCreateContext* ctx, const Params& params, int64_t steps, double horizon_s)
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

// Throws unless the host handed a per-agent create its neighbourhood and shape (per-agent
// execution only).
void RequireNeighbourhood(const mjfCreateContext* ctx);

// The create of a per-agent law evaluated every physics step (no sample period, no look-ahead),
// with the params Parse reads (its swarm-level version's).
template <typename Law, auto Parse>
void* EveryStepAgentCreate(const mjfCreateContext* ctx) {
  return plugin::CreateOrExplain(ctx, [&]() -> void* {
    RequireNeighbourhood(ctx);
    return new AgentInstance<Law>(ctx, Parse(plugin::Attributes(ctx)), 1, 0.0);
  });
}

// w_j for every neighbour: this round's iterate when it got through, else from u_j.
template <typename Law>
void AgentCoupling(AgentInstance<Law>& a, const mjfAgentInput& in) {
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
void AgentSample(AgentInstance<Law>& a, const mjfStepContext& ctx) {
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
  if constexpr (law_detail::AdvancesWithTime<Law>::value) a.core.Advance(ctx.time);
  a.core.Prepare(own_pv, a.inbox.leader_pv(), a.own_f_now, a.own_f_next, a.neighbour_pv.data(),
                 a.neighbour_f_now.data(), a.neighbour_f_next.data());
  if (in.solved) {
    a.core.UseSolved(in.solved);
  } else {
    AgentCoupling(a, in);
    a.core.Solve(a.neighbour_w.data());
  }
  a.has_sample = true;
}

template <typename Law>
int AgentCompute(void* instance, const mjfStepContext* ctx) {
  return plugin::ComputeOrExplain(ctx, [&] {
    auto& a = *static_cast<AgentInstance<Law>*>(instance);
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
    if (sampled) AgentSample(a, *ctx);
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
    out.n_payload = sampled ? plugin::kPayloadUsed : 0;
    out.payload[0] = a.core.coupling()[0];
    out.payload[1] = a.core.coupling()[1];
    out.payload[2] = a.core.rhs()[0];
    out.payload[3] = a.core.rhs()[1];
    std::copy(a.inbox.leader_pv(), a.inbox.leader_pv() + 4, out.payload + plugin::kPayloadLeader);
    return 0;
  });
}

template <typename Law>
void AgentReset(void* instance) {
  static_cast<AgentInstance<Law>*>(instance)->has_sample = false;
  static_cast<AgentInstance<Law>*>(instance)->last_round = -1;
  if constexpr (law_detail::HasReset<Law>::value)
    static_cast<AgentInstance<Law>*>(instance)->core.Reset();
}

template <typename Law>
void AgentDestroy(void* instance) {
  delete static_cast<AgentInstance<Law>*>(instance);
}

// The descriptor of a per-agent formation plugin whose instance is AgentInstance<Law>, with the
// attributes of its swarm-level version (report: null for a law with nothing to report).
template <typename Law>
constexpr mjfPlugin AgentPlugin(const char* name, const char* doc, int n_attributes,
                                const mjfAttribute* attributes,
                                void* (*create)(const mjfCreateContext*),
                                void (*report)(void*, mjfReportFn, void*) = nullptr) {
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
          &AgentCompute<Law>,
          &AgentReset<Law>,
          &AgentDestroy<Law>,
          report,
          &plugin::StateSizeOf<AgentInstance<Law>>,
          &plugin::GetStateOf<AgentInstance<Law>>,
          &plugin::SetStateOf<AgentInstance<Law>>};
}

}  // namespace mjf::formation::adapter

#endif  // MJFORMATION_PLUGINS_FORMATION_AGENT_ADAPTER_HPP_
