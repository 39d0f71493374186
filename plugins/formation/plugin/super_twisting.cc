// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// super_twisting: the super-twisting algorithm (Levant 1993; Moreno & Osorio 2012) on the
// sliding variable s_i = K e_i of eq. (17) (the core's super_twisting.hpp), evaluated every
// physics step; its integral w_i advances with the host's time.
#include <mjformation/formation/super_twisting.hpp>

#include "adapter.hpp"

namespace mjf::formation::adapter {
// The attributes and their reading, shared with super_twisting_agent.cc.
const mjfAttribute kSuperTwistingAttributes[] = {
    {kKeyGains, "3 1", "K = [k1 k2] of the sliding variable s_i = K e_i, eq. (17); both > 0"},
    {"lambda", "1.5", "gain lambda > 0 of -lambda |s|^(1/2) sgn(s) (not tuned)"},
    {"alpha", "0.5", "integral gain alpha > 0 of w' = -alpha sgn(s); > k2 a_i0 (leader jerk)"},
};
const int kSuperTwistingAttributeCount =
    static_cast<int>(sizeof(kSuperTwistingAttributes) / sizeof(kSuperTwistingAttributes[0]));

formation::SuperTwistingParams ParseSuperTwistingParams(const plugin::Attributes& attributes) {
  formation::SuperTwistingParams params;
  params.gains = ParseGains(attributes);
  params.lambda = attributes.Number("lambda");
  params.alpha = attributes.Number("alpha");
  return params;
}

namespace {

struct Instance : SwarmInstance<formation::SuperTwisting> {
  using Config = formation::SuperTwistingParams;
  static void Read(const plugin::Attributes& attributes, Config* params) {
    *params = ParseSuperTwistingParams(attributes);
  }
  using SwarmInstance::SwarmInstance;
};

void Report(void* instance, mjfReportFn emit, void* user) {
  const auto* self = static_cast<const Instance*>(instance);
  emit(user, "norm_inv_lh", self->controller.norm_inv_lh());
  if (self->controller.reaching_time_bound() >= 0.0) {
    // Moreno & Osorio's bound for a leader without acceleration (d = 0), from s_i(0), w_i = 0.
    emit(user, "reaching_time_bound", self->controller.reaching_time_bound());
  }
}

}  // namespace

const mjfPlugin kSuperTwisting = SwarmPlugin<Instance>(
    "super_twisting", "super-twisting (second-order sliding, Levant 1993) on s_i = K e_i",
    kSuperTwistingAttributes, &Report);

}  // namespace mjf::formation::adapter
