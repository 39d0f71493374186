// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// example_sampled_law: a formation law (one instance per swarm) that samples every `period` s and
// holds its input in between, with a linear reaching law on the sliding variable
// s_i = e_v + k1 e_p of each follower's slot error: u_i = f_ia - k1 e_v - q s_i. It shows the
// host-plugin contract (mjformation/plugin_contract.hpp): by declaring the attribute `period`
// and reporting its T and q, it gets the runner's checks against the sample period (clock
// offsets, exchange rounds) and summary.json's predicted delay margin, with nothing else to add.
#include <mjformation/plugin.h>

#include <cmath>
#include <mjformation/plugin_contract.hpp>
#include <mjformation/plugin_util.hpp>
#include <mjformation/time_steps.hpp>
#include <vector>

namespace {

namespace contract = mjf::plugin::contract;

class SampledLaw {
 public:
  explicit SampledLaw(const mjfCreateContext* ctx)
      : n_(ctx->n_vehicles - 1), shape_(ctx->shape), held_(2 * static_cast<size_t>(n_), 0.0) {
    const mjf::plugin::Attributes a(ctx);
    law_.period = a.Number(contract::kPeriod);
    law_.q = a.Number(contract::kQ);
    k1_ = a.Number("k1");
    mjf::plugin::Require(law_.q > 0 && law_.q * law_.period < 1, "q", "0 < q T < 1", law_.q);
    steps_ = mjf::WholeSteps(law_.period, ctx->timestep);  // the runner's rule for a time
    mjf::plugin::Require(steps_ >= 1, "period", "a whole number (>= 1) of physics steps",
                         law_.period);
  }

  int Compute(const mjfStepContext* ctx) {
    if (ctx->step % steps_ == 0) Sample(ctx);  // zero-order hold in between
    for (int i = 0; i < n_; ++i) {
      ctx->setpoints[i + 1].acc[0] = held_[2 * i];
      ctx->setpoints[i + 1].acc[1] = held_[2 * i + 1];
    }
    return 0;
  }

  void Report(mjfReportFn emit, void* user) const { contract::Emit(law_, emit, user); }

  // ABI 4: what one Compute() leaves for the next, the held input (its phase is ctx->step's).
  template <typename Visit>
  void VisitState(Visit& visit) {
    visit(held_);
  }

 private:
  void Sample(const mjfStepContext* ctx) {
    const mjfVehicleState& leader = ctx->states[0];
    double f[6];  // the slot's offset f_i: px, py, vx, vy, ax, ay
    for (int i = 0; i < n_; ++i) {
      shape_->evaluate_one(shape_->self, ctx->time, i, f);
      const mjfVehicleState& s = ctx->states[i + 1];
      for (int axis = 0; axis < 2; ++axis) {
        const double e_p = s.pos[axis] - leader.pos[axis] - f[axis];
        const double e_v = s.vel[axis] - leader.vel[axis] - f[2 + axis];
        const double sliding = e_v + k1_ * e_p;
        held_[2 * i + axis] = f[4 + axis] - k1_ * e_v - law_.q * sliding;
      }
    }
  }

  int n_;
  const mjfShape* shape_;
  contract::Law law_;  // period and q: what the runner reads of this law
  double k1_ = 0;
  int64_t steps_ = 1;
  std::vector<double> held_;  // [2 * follower + axis], m/s^2
};

const mjfAttribute kAttributes[] = {
    {contract::kPeriod, "0.02", "s: sample period T (a whole number of physics steps)"},
    {contract::kQ, "5", "1/s: reaching gain q (0 < q T < 1)"},
    {"k1", "1", "1/s: weight of the position error in the sliding variable"}};

void* Create(const mjfCreateContext* ctx) {
  return mjf::plugin::CreateOrExplain(ctx, [&] { return new SampledLaw(ctx); });
}
int Compute(void* instance, const mjfStepContext* ctx) {
  return mjf::plugin::ComputeOrExplain(
      ctx, [&] { return static_cast<SampledLaw*>(instance)->Compute(ctx); });
}
void Destroy(void* instance) { delete static_cast<SampledLaw*>(instance); }
void Report(void* instance, mjfReportFn emit, void* user) {
  static_cast<SampledLaw*>(instance)->Report(emit, user);
}

const mjfPlugin kSampledLaw = {MJF_ABI_VERSION,
                               "example_sampled_law",
                               MJF_KIND_FORMATION,
                               "example formation law: sampled, linear reaching law",
                               3,
                               kAttributes,
                               0,
                               nullptr,
                               Create,
                               Compute,
                               nullptr,
                               Destroy,
                               Report,
                               mjf::plugin::StateSizeOf<SampledLaw>,
                               mjf::plugin::GetStateOf<SampledLaw>,
                               mjf::plugin::SetStateOf<SampledLaw>};

}  // namespace

MJF_EXPORT_PLUGINS(&kSampledLaw)
