// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// smc_discrete: the discrete sliding-mode protocol, eq. (48) via its compact form (53), sampled
// every `period` seconds (an integer number of physics steps, chosen on ctx->step) and held
// in between (zero-order hold).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <mjformation/formation/discrete_smc.hpp>
#include <mjformation/time_steps.hpp>
#include <sstream>
#include <stdexcept>

#include "adapter.hpp"

namespace mjf::formation::adapter {

const mjfAttribute kDiscreteAttributes[] = {
    {kKeyGains, "3 1", "K = [k1 k2] of the sliding variable s_i = K e_i, eq. (17); both > 0"},
    {kKeyEps, "0.05", "switching gain eps > 0 of eq. (48)"},
    {kKeyQ, "4.5", "reaching gain q > 0 of eq. (48), 1/s; 1 - q T > 0"},
    {kKeyPeriod, "0.05", "sample period T, s: an integer multiple of the physics timestep"},
    {kKeyUMin, "-1", "lower bound u_min of the leader's acceleration, m/s^2"},
    {kKeyUMax, "1", "upper bound u_max of the leader's acceleration, m/s^2"},
    {kKeySign, "sgn", "sign function: sgn (paper) or sat (boundary layer)"},
    {kKeyBoundaryLayer, "0.1", "boundary-layer width phi of sat (sign = sat only)"},
    {kKeyEta0, "1e-6", "the small eta_0 > 0 of Delta_1, eq. (49) (reporting only)"},
    {kKeyAccelLimit, "none",
     "followers' horizontal acceleration bound: none (law (48) as printed), vehicle (from the "
     "vehicles: tilt limit, thrust, actuator range) or a number in m/s^2 above the leader's "
     "bound sqrt(2) max(|u_min|, |u_max|): the input-constrained reaching law (C0)-(C9)"},
    {kKeyReachAccel, "0",
     "beta of (C3), m/s^2: the acceleration the constrained law spends on reaching (it brakes "
     "at beta / 2); 0 derives it per follower from accel_limit, the leader and the slot (C3)"},
};
const int kDiscreteAttributeCount =
    static_cast<int>(sizeof(kDiscreteAttributes) / sizeof(kDiscreteAttributes[0]));

formation::DiscreteSmcParams ParseDiscreteParams(const plugin::Attributes& attributes) {
  formation::DiscreteSmcParams params;
  params.gains = ParseGains(attributes);
  params.eps = attributes.Number(kKeyEps);
  params.q = attributes.Number(kKeyQ);
  params.period = attributes.Number(kKeyPeriod);
  params.u_min = attributes.Number(kKeyUMin);
  params.u_max = attributes.Number(kKeyUMax);
  params.sign = formation::ParseSignFunction(attributes.String(kKeySign));
  params.boundary_layer = attributes.Number(kKeyBoundaryLayer);
  params.eta0 = attributes.Number(kKeyEta0);
  params.accel_limit = ParseAccelLimit(attributes);
  params.reach_accel = attributes.Number(kKeyReachAccel);
  params.Validate();
  return params;
}

int64_t StepsPerSample(double period, double timestep) {
  if (!(timestep > 0.0) || !std::isfinite(timestep)) {
    throw std::invalid_argument("smc_discrete: the physics timestep must be > 0");
  }
  const int64_t steps = WholeSteps(period, timestep);
  if (steps < 1) {
    std::ostringstream out;
    out << "attribute 'period': T = " << period
        << " s is not an integer multiple of the physics timestep " << timestep
        << " s (zero-order hold samples every round(T / timestep) steps)";
    throw std::invalid_argument(out.str());
  }
  return steps;
}

namespace {

struct Instance : SwarmInstance<formation::DiscreteSmc> {
  // The params and the physics steps per sample period T they imply.
  struct Config {
    formation::DiscreteSmcParams params;
    int64_t steps_per_sample;
  };
  static Config Configure(const mjfCreateContext* ctx) {
    const formation::DiscreteSmcParams params = ParseDiscreteParams(plugin::Attributes(ctx));
    return {params, StepsPerSample(params.period, ctx->timestep)};
  }
  Instance(const SwarmSetup& setup, const Config& config)
      : SwarmInstance(setup, config.params), steps_per_sample(config.steps_per_sample) {}
  void Sample(const mjfStepContext* ctx) {
    if (!has_sample || ctx->step % steps_per_sample == 0) {
      // Sample k: F(k) at t, F(k+1) at t + T, eq. (53).
      shape.Evaluate(ctx->time + controller.params().period, buffers.shape_next.data());
      controller.Update(buffers.Input());
      has_sample = true;
    }
  }
  // Zero-order hold: the last sample's u_i and s_i until the next sample.
  const double* sliding() const { return controller.sliding().data(); }
  void Reset() {
    has_sample = false;
    controller.ResetConstraintStats();
  }
  // The law's held sample and whether one was taken (the phase is the step's, ctx->step).
  template <typename Visit>
  void VisitState(Visit& visit) {
    SwarmInstance::VisitState(visit);
    visit(has_sample);
  }
  int64_t steps_per_sample;  // zero-order hold: physics steps per sample period T
  bool has_sample = false;
};

void Report(void* instance, mjfReportFn emit, void* user) {
  const auto* self = static_cast<const Instance*>(instance);
  const formation::DiscreteSmc& c = self->controller;
  double delta1 = 0.0, delta2 = 0.0;
  for (int i = 0; i < c.graph().num_followers(); ++i) {
    delta1 = std::max(delta1, c.delta1(i));
    delta2 = std::max(delta2, c.delta2(i));
  }
  emit(user, plugin::contract::kDelta, c.delta());
  emit(user, "delta1", delta1);
  emit(user, "delta2", delta2);
  emit(user, "error_bound", c.error_bound());
  emit(user, "error_bound_rederived", c.ultimate_error_bound());
  emit(user, "norm_inv_lh", c.norm_inv_lh());
  emit(user, plugin::contract::kPeriod, c.params().period);
  emit(user, "steps_per_sample", static_cast<double>(self->steps_per_sample));
  if (!c.constrained()) return;  // the paper's law reports what it always did
  const formation::DiscreteSmc::ConstraintStats& stats = c.constraint_stats();
  emit(user, plugin::contract::kAccelLimit, c.params().accel_limit);
  emit(user, "constraint_samples", static_cast<double>(stats.samples));
  emit(user, "constraint_paper_samples", static_cast<double>(stats.paper));
  emit(user, "constraint_follower_samples", static_cast<double>(stats.constrained));
  emit(user, "peak_unconstrained_demand", stats.peak_paper_demand);
  emit(user, "norm_inf_inv_lh", c.norm_inf_inv_lh());
}

}  // namespace

const mjfPlugin kSmcDiscrete = SwarmPlugin<Instance>(
    "smc_discrete",
    "discrete sliding-mode formation tracking, eq. (48) via compact form (53), zero-order hold",
    kDiscreteAttributes, &Report);

}  // namespace mjf::formation::adapter
