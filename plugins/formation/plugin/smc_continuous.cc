// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// smc_continuous: the continuous sliding-mode protocol, eq. (30) via its compact form (33),
// evaluated every physics step.
#include <mjformation/formation/continuous_smc.hpp>

#include "adapter.hpp"

namespace mjf::formation::adapter {

const mjfAttribute kContinuousAttributes[] = {
    {kKeyGains, "3 1", "K = [k1 k2] of the sliding variable s_i = K e_i, eq. (17); both > 0"},
    {kKeyRho, "0.05", "switching gain rho > 0 of eq. (30)"},
    {kKeyQ, "4.5", "exponential reaching gain q > 0, 1/s (reaching = exponential only)"},
    {kKeyUMin, "-1", "lower bound u_min of the leader's acceleration, m/s^2"},
    {kKeyUMax, "1", "upper bound u_max of the leader's acceleration, m/s^2 (switching only)"},
    {kKeyCompensation, "lower_bound",
     "leader input compensation: lower_bound (u_min, as printed in (30)) or switching "
     "(mu1 - mu2 sgn(s_i), as in (48))"},
    {kKeyReaching, "constant", "reaching law: constant (rho sgn s) or exponential (+ q s)"},
    {kKeySign, "sgn", "sign function: sgn (paper) or sat (boundary layer)"},
    {kKeyBoundaryLayer, "0.1", "boundary-layer width phi of sat (sign = sat only)"},
};
const int kContinuousAttributeCount =
    static_cast<int>(sizeof(kContinuousAttributes) / sizeof(kContinuousAttributes[0]));

formation::ContinuousSmcParams ParseContinuousParams(const plugin::Attributes& attributes) {
  formation::ContinuousSmcParams params;
  params.gains = ParseGains(attributes);
  params.rho = attributes.Number(kKeyRho);
  params.q = attributes.Number(kKeyQ);
  params.u_min = attributes.Number(kKeyUMin);
  params.u_max = attributes.Number(kKeyUMax);
  params.compensation = formation::ParseCompensation(attributes.String(kKeyCompensation));
  params.reaching = formation::ParseReaching(attributes.String(kKeyReaching));
  params.sign = formation::ParseSignFunction(attributes.String(kKeySign));
  params.boundary_layer = attributes.Number(kKeyBoundaryLayer);
  params.Validate();
  return params;
}

namespace {

struct Instance : SwarmInstance<formation::ContinuousSmc> {
  using Config = formation::ContinuousSmcParams;
  static Config Configure(const mjfCreateContext* ctx) {
    return ParseContinuousParams(plugin::Attributes(ctx));
  }
  using SwarmInstance::SwarmInstance;
  void Reset() { controller.ResetReachingTime(); }
};

void Report(void* instance, mjfReportFn emit, void* user) {
  const auto* self = static_cast<const Instance*>(instance);
  emit(user, "norm_inv_lh", self->controller.norm_inv_lh());
  if (self->controller.reaching_time_bound() >= 0.0) {
    emit(user, "reaching_time_bound", self->controller.reaching_time_bound());
  }
  emit(user, "switching_compensation",
       self->controller.params().compensation == formation::Compensation::kSwitching ? 1.0 : 0.0);
}

}  // namespace

const mjfPlugin kSmcContinuous = SwarmPlugin<Instance>(
    "smc_continuous", "continuous sliding-mode formation tracking, eq. (30) via compact form (33)",
    kContinuousAttributes, &Report);

}  // namespace mjf::formation::adapter
