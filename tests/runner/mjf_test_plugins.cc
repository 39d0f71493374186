// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
// Plugins for the runner's tests: a guidance plugin with a required attribute, and one that
// goes non-finite after a given time (to test how a run that breaks mid-way is kept).
#include <limits>
#include <mjformation/plugin_util.hpp>

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

}  // namespace

MJF_EXPORT_PLUGINS(&kRequired, &kNan, &kHuge)
