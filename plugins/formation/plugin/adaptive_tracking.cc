// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// adaptive_tracking: Li, Liu, Ren & Xie (IEEE TAC 2013)'s adaptive-gain tracking of a leader
// whose input bound is unknown (the core's adaptive_tracking.hpp), evaluated every physics
// step; the gains d_i advance with the host's time. sliding = e_ip + sqrt(3) e_iv.
#include <mjformation/formation/adaptive_tracking.hpp>

#include "adapter.hpp"

namespace mjf::formation::adapter {
// The attributes and their reading, shared with adaptive_tracking_agent.cc.
const mjfAttribute kAdaptiveTrackingAttributes[] = {
    {"tau", "0.02", "adaptation rate tau > 0 of d_i' (not tuned)"},
    {"phi", "0.05", "leakage phi >= 0 of d_i', 1/s (0 with kappa = 0: the discontinuous law)"},
    {"kappa", "0.1", "width kappa >= 0 of r(w) = w / (||w|| + kappa), m/s^2"},
    {"d0", "1", "initial adaptive gain d_i(0) > 0"},
};
const int kAdaptiveTrackingAttributeCount =
    static_cast<int>(sizeof(kAdaptiveTrackingAttributes) / sizeof(kAdaptiveTrackingAttributes[0]));

formation::AdaptiveTrackingParams ParseAdaptiveTrackingParams(
    const plugin::Attributes& attributes) {
  formation::AdaptiveTrackingParams params;
  params.tau = attributes.Number("tau");
  params.phi = attributes.Number("phi");
  params.kappa = attributes.Number("kappa");
  params.d0 = attributes.Number("d0");
  return params;
}

namespace {

struct Instance : SwarmInstance<formation::AdaptiveTracking> {
  using Config = formation::AdaptiveTrackingParams;
  static void Read(const plugin::Attributes& attributes, Config* params) {
    *params = ParseAdaptiveTrackingParams(attributes);
  }
  using SwarmInstance::SwarmInstance;
};

void Report(void* instance, mjfReportFn emit, void* user) {
  emit(user, "max_adaptive_gain", static_cast<const Instance*>(instance)->controller.max_gain());
}

}  // namespace

const mjfPlugin kAdaptiveTracking = SwarmPlugin<Instance>(
    "adaptive_tracking",
    "adaptive-gain tracking of a leader with unknown input bound, Li, Liu, Ren & Xie (TAC 2013)",
    kAdaptiveTrackingAttributes, &Report);

}  // namespace mjf::formation::adapter
