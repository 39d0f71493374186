// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
// Plugins for the runner's tests: a guidance plugin with a required attribute, one that goes
// non-finite after a given time, and the fault corpus of the failure contract: one that fails
// with a message, one that throws a C++ exception out of compute(), one that raises a MuJoCo
// engine error (mju_error) from inside the step, each from a given time on.
#include <mujoco/mujoco.h>

#include <cstdio>
#include <limits>
#include <mjformation/plugin_util.hpp>
#include <stdexcept>
#include <vector>

namespace {

struct Hold {
  int vehicle;
  double position[3];
  double nan_after;     // s; negative: never
  double broken_value;  // what is commanded from nan_after on
};

const mjfAttribute kRequiredAttributes[] = {{"value", nullptr, "a required number"}};
const mjfAttribute kNanAttributes[] = {{"after", "1.0", "s: from this time on, command NaN"}};
const mjfAttribute kHugeAttributes[] = {
    {"after", "1.0", "s: from this time on, command an absurd (finite) acceleration"}};

void* CreateHold(const mjfCreateContext* ctx, bool nan, double broken_value) {
  return mjf::plugin::CreateOrExplain(ctx, [&]() -> void* {
    mjf::plugin::Attributes attributes(ctx);
    auto* h = new Hold{ctx->vehicle, {0, 0, 0}, -1, broken_value};
    if (nan) {
      h->nan_after = attributes.Number("after");
    } else {
      attributes.Number("value");
    }
    for (int k = 0; k < 3; ++k) h->position[k] = ctx->initial_pos[k];
    return h;
  });
}

int ComputeHold(void* instance, const mjfStepContext* ctx) {
  auto* h = static_cast<Hold*>(instance);
  mjfSetpoint& sp = ctx->setpoints[h->vehicle];
  const mjfVehicleState& s = ctx->states[h->vehicle];
  const bool broken = h->nan_after >= 0 && ctx->time >= h->nan_after;
  for (int k = 0; k < 2; ++k) {
    sp.pos[k] = h->position[k];
    sp.vel[k] = 0;
    sp.acc[k] = broken ? h->broken_value : 2.0 * (h->position[k] - s.pos[k]) - 2.5 * s.vel[k];
  }
  return 0;
}

void Destroy(void* instance) { delete static_cast<Hold*>(instance); }

const mjfPlugin kRequired = {MJF_ABI_VERSION,
                             "test_required",
                             MJF_KIND_GUIDANCE,
                             "holds position; needs attribute 'value'",
                             1,
                             kRequiredAttributes,
                             0,
                             nullptr,
                             [](const mjfCreateContext* c) { return CreateHold(c, false, 0.0); },
                             ComputeHold,
                             nullptr,
                             Destroy,
                             nullptr,
                             nullptr,
                             nullptr,
                             nullptr};
const mjfPlugin kNan = {MJF_ABI_VERSION,
                        "test_nan",
                        MJF_KIND_GUIDANCE,
                        "holds position, then commands NaN",
                        1,
                        kNanAttributes,
                        0,
                        nullptr,
                        [](const mjfCreateContext* c) {
                          return CreateHold(c, true, std::numeric_limits<double>::quiet_NaN());
                        },
                        ComputeHold,
                        nullptr,
                        Destroy,
                        nullptr,
                        nullptr,
                        nullptr,
                        nullptr};

const mjfPlugin kHuge = {MJF_ABI_VERSION,
                         "test_huge",
                         MJF_KIND_GUIDANCE,
                         "holds position, then commands 1e12 m/s^2",
                         1,
                         kHugeAttributes,
                         0,
                         nullptr,
                         [](const mjfCreateContext* c) { return CreateHold(c, true, 1e12); },
                         ComputeHold,
                         nullptr,
                         Destroy,
                         nullptr,
                         nullptr,
                         nullptr,
                         nullptr};

// The faults: each holds position until `after`, then fails its own way.
enum class Fault { kMessage, kThrow, kEngineError };

template <Fault kFault>
int ComputeFault(void* instance, const mjfStepContext* ctx) {
  auto* h = static_cast<Hold*>(instance);
  if (ctx->time < h->nan_after) return ComputeHold(instance, ctx);
  switch (kFault) {
    case Fault::kMessage:
      return mjf::plugin::Fail(ctx, "rotor 2 reports an over-temperature", 7);
    case Fault::kThrow:
      throw std::runtime_error("std::vector::at: index out of range (a plugin bug)");
    case Fault::kEngineError:
      mju_error("test_engine_error: an engine error raised inside a step");
      return 0;  // not reached: the runner's handler does not return
  }
  return 0;
}

template <Fault kFault>
constexpr mjfPlugin FaultPlugin(const char* name, const char* doc) {
  return {MJF_ABI_VERSION,
          name,
          MJF_KIND_GUIDANCE,
          doc,
          1,
          kNanAttributes,
          0,
          nullptr,
          [](const mjfCreateContext* c) { return CreateHold(c, true, 0.0); },
          ComputeFault<kFault>,
          nullptr,
          Destroy,
          nullptr,
          nullptr,
          nullptr,
          nullptr};
}

const mjfPlugin kFailMessage =
    FaultPlugin<Fault::kMessage>("test_fail_message", "holds position, then fails with a reason");
const mjfPlugin kThrow =
    FaultPlugin<Fault::kThrow>("test_throw", "holds position, then throws a C++ exception");
const mjfPlugin kEngineError =
    FaultPlugin<Fault::kEngineError>("test_engine_error", "holds position, then calls mju_error");

// test_agent_recorder: a per-agent formation plugin that records what the host hands it. It fails
// the run on any swarm-wide data (states, model, data) or on a message from a vehicle that is
// not one of its in-neighbours (or the leader without a leader link); it reports whether it ever
// saw a non-neighbour (must stay 0) and whether some neighbour was never heard (0 proves the
// check was not vacuous). It commands zero horizontal acceleration.
struct Recorder {
  std::vector<int> allowed;  // vehicle indices it may hear
  std::vector<bool> heard;   // [allowed]
  bool saw_non_neighbour = false;
  int64_t messages = 0;
};

void* CreateRecorder(const mjfCreateContext* ctx) {
  if (!ctx->neighbourhood || ctx->graph) {
    std::snprintf(ctx->error, ctx->error_size, "expected a neighbourhood and no graph");
    return nullptr;
  }
  auto* r = new Recorder;
  const mjfNeighbourhood& n = *ctx->neighbourhood;
  for (int k = 0; k < n.n_neighbours; ++k) r->allowed.push_back(n.neighbours[k] + 1);
  if (n.leader_weight > 0) r->allowed.push_back(0);
  r->heard.assign(r->allowed.size(), false);
  return r;
}

int ComputeRecorder(void* instance, const mjfStepContext* ctx) {
  auto* r = static_cast<Recorder*>(instance);
  if (ctx->states || ctx->model || ctx->data || !ctx->agent) {
    return mjf::plugin::Fail(ctx, "handed swarm-wide data (states, model or data)");
  }
  auto check = [&](const mjfMessage& m) {
    ++r->messages;
    bool ok = false;
    for (size_t k = 0; k < r->allowed.size(); ++k) {
      if (r->allowed[k] == m.sender) ok = r->heard[k] = true;
    }
    if (!ok) r->saw_non_neighbour = true;
    return ok;
  };
  for (int k = 0; k < ctx->agent->n_messages; ++k) {
    if (!check(ctx->agent->messages[k])) return mjf::plugin::Fail(ctx, "saw a non-neighbour");
  }
  if (ctx->agent->leader && !check(*ctx->agent->leader)) {
    return mjf::plugin::Fail(ctx, "saw the leader without a leader link");
  }
  ctx->setpoints->acc[0] = ctx->setpoints->acc[1] = 0.0;
  return 0;
}

void ReportRecorder(void* instance, mjfReportFn emit, void* user) {
  const auto* r = static_cast<const Recorder*>(instance);
  bool missing = false;
  for (bool h : r->heard) missing = missing || !h;
  emit(user, "saw_non_neighbour", r->saw_non_neighbour ? 1.0 : 0.0);
  emit(user, "missing_neighbour", missing ? 1.0 : 0.0);
  emit(user, "messages", static_cast<double>(r->messages));
}

const mjfPlugin kAgentRecorder = {MJF_ABI_VERSION,
                                  "test_agent_recorder",
                                  MJF_KIND_FORMATION_AGENT,
                                  "records the messages a per-agent instance is handed",
                                  0,
                                  nullptr,
                                  0,
                                  nullptr,
                                  CreateRecorder,
                                  ComputeRecorder,
                                  nullptr,
                                  [](void* p) { delete static_cast<Recorder*>(p); },
                                  ReportRecorder,
                                  nullptr,
                                  nullptr,
                                  nullptr};

}  // namespace

MJF_EXPORT_PLUGINS(&kRequired, &kNan, &kHuge, &kFailMessage, &kThrow, &kEngineError,
                   &kAgentRecorder)
