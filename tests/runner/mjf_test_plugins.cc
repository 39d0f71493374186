// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
// Plugins for the runner's tests: a guidance plugin with a required attribute, one that goes
// non-finite after a given time, and the fault corpus of the failure contract: one that fails
// with a message, one that throws a C++ exception out of compute(), one that raises a MuJoCo
// engine error (mju_error) from inside the step, each from a given time on.
#include <mujoco/mujoco.h>

#include <limits>
#include <mjformation/plugin_util.hpp>
#include <stdexcept>

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
          nullptr};
}

const mjfPlugin kFailMessage =
    FaultPlugin<Fault::kMessage>("test_fail_message", "holds position, then fails with a reason");
const mjfPlugin kThrow =
    FaultPlugin<Fault::kThrow>("test_throw", "holds position, then throws a C++ exception");
const mjfPlugin kEngineError =
    FaultPlugin<Fault::kEngineError>("test_engine_error", "holds position, then calls mju_error");

}  // namespace

MJF_EXPORT_PLUGINS(&kRequired, &kNan, &kHuge, &kFailMessage, &kThrow, &kEngineError)
