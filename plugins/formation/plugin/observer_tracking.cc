// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// observer_tracking: Hong, Hu & Gao (Automatica 2006)'s tracking with a leader-velocity
// estimator, with an inner velocity loop for our double integrators (the core's
// observer_tracking.hpp), evaluated every physics step; the estimates advance with the host's
// time. It never reads the leader's velocity. sliding = e_ip.
#include <mjformation/formation/observer_tracking.hpp>

#include "adapter.hpp"

namespace mjf::formation::adapter {
// The attributes and their reading, shared with observer_tracking_agent.cc.
const mjfAttribute kObserverTrackingAttributes[] = {
    {"k", "1", "position consensus gain k > 0, 1/s (not tuned)"},
    {"gamma", "1", "leader-velocity estimator gain gamma > 0, 1/s"},
    {kKeyKv, "4", "inner velocity-loop gain kv > 0, 1/s (our adaptation to double integrators)"},
};
const int kObserverTrackingAttributeCount =
    static_cast<int>(sizeof(kObserverTrackingAttributes) / sizeof(kObserverTrackingAttributes[0]));

formation::ObserverTrackingParams ParseObserverTrackingParams(
    const plugin::Attributes& attributes) {
  formation::ObserverTrackingParams params;
  params.k = attributes.Number("k");
  params.gamma = attributes.Number("gamma");
  params.kv = attributes.Number(kKeyKv);
  return params;
}

namespace {

struct Instance : SwarmInstance<formation::ObserverTracking> {
  using Config = formation::ObserverTrackingParams;
  static void Read(const plugin::Attributes& attributes, Config* params) {
    *params = ParseObserverTrackingParams(attributes);
  }
  using SwarmInstance::SwarmInstance;
};

}  // namespace

const mjfPlugin kObserverTracking = SwarmPlugin<Instance>(
    "observer_tracking",
    "tracking with a leader-velocity estimator, Hong, Hu & Gao (Automatica 2006)",
    kObserverTrackingAttributes);

}  // namespace mjf::formation::adapter
