// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// vs_tracking: Cao & Ren (IEEE TAC 2012)'s variable-structure coordinated tracking (the core's
// vs_tracking.hpp), evaluated every physics step. sliding = gamma e_ip + e_iv.
#include <mjformation/formation/vs_tracking.hpp>

#include "adapter.hpp"

namespace mjf::formation::adapter {
// The attributes and their reading, shared with vs_tracking_agent.cc.
const mjfAttribute kVsTrackingAttributes[] = {
    {"alpha", "2", "velocity weight alpha > 0 of the linear term, s (not tuned)"},
    {"beta", "1.5", "switching gain beta > 0, m/s^2, above the leader's acceleration bound"},
    {"gamma", "1", "position weight gamma > 0 inside sgn, 1/s"},
    {kKeySign, "sgn", "sign function: sgn (as published) or sat (boundary layer)"},
    {kKeyBoundaryLayer, "0.1", "boundary-layer width phi of sat, m/s (sign = sat only)"},
};
const int kVsTrackingAttributeCount =
    static_cast<int>(sizeof(kVsTrackingAttributes) / sizeof(kVsTrackingAttributes[0]));

formation::VsTrackingParams ParseVsTrackingParams(const plugin::Attributes& attributes) {
  formation::VsTrackingParams params;
  params.alpha = attributes.Number("alpha");
  params.beta = attributes.Number("beta");
  params.gamma = attributes.Number("gamma");
  params.sign = formation::ParseSignFunction(attributes.String(kKeySign));
  params.boundary_layer = attributes.Number(kKeyBoundaryLayer);
  return params;
}

namespace {

struct Instance : SwarmInstance<formation::VsTracking> {
  using Config = formation::VsTrackingParams;
  static void Read(const plugin::Attributes& attributes, Config* params) {
    *params = ParseVsTrackingParams(attributes);
  }
  using SwarmInstance::SwarmInstance;
};

}  // namespace

const mjfPlugin kVsTracking = SwarmPlugin<Instance>(
    "vs_tracking",
    "variable-structure coordinated tracking, Cao & Ren (IEEE TAC 2012), double integrators",
    kVsTrackingAttributes);

}  // namespace mjf::formation::adapter
