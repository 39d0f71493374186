// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// consensus_linear: the linear consensus-based formation tracking baseline (see the core's
// linear_consensus.hpp), evaluated every physics step. No sliding variable: sliding stays NaN.
#include <mjformation/core/linear_consensus.hpp>

#include "adapter.hpp"
#include "plugins.hpp"

namespace mjf::formation {

const mjfAttribute kConsensusAttributes[] = {
    {kKeyKp, "1", "position gain kp > 0, 1/s^2"},
    {kKeyKv, "2", "velocity gain kv > 0, 1/s"},
};
const int kConsensusAttributeCount =
    static_cast<int>(sizeof(kConsensusAttributes) / sizeof(kConsensusAttributes[0]));

core::LinearConsensusParams ParseConsensusParams(const plugin::Attributes& attributes) {
  core::LinearConsensusParams params;
  params.kp = attributes.Number(kKeyKp);
  params.kv = attributes.Number(kKeyKv);
  params.Validate();
  return params;
}

namespace {

using Instance = SwarmInstance<core::LinearConsensus>;

void* Create(const mjfCreateContext* ctx) {
  return plugin::CreateOrExplain(ctx, [&]() -> void* {
    const core::LinearConsensusParams params = ParseConsensusParams(plugin::Attributes(ctx));
    const SwarmSetup setup(ctx);
    return new Instance(setup, params);
  });
}

int Compute(void* instance, const mjfStepContext* ctx) {
  auto* self = static_cast<Instance*>(instance);
  SwarmBuffers& buffers = self->buffers;
  if (!buffers.Read(ctx))
    return mjf::plugin::Fail(
        ctx, "the step does not carry 1 + n_followers vehicle states and setpoints");
  self->shape.Evaluate(ctx->time, buffers.shape_now.data());
  self->controller.Update(buffers.Input());
  WriteSlots(buffers, ctx->setpoints);
  WriteCommands(buffers.n(), self->controller.acceleration().data(), nullptr, ctx->setpoints);
  return 0;
}

void Reset(void*) {}

void Destroy(void* instance) { delete static_cast<Instance*>(instance); }

}  // namespace

const mjfPlugin kConsensusLinear = {
    MJF_ABI_VERSION,
    "consensus_linear",
    MJF_KIND_FORMATION,
    "linear consensus-based time-varying formation tracking (baseline)",
    static_cast<int>(sizeof(kConsensusAttributes) / sizeof(kConsensusAttributes[0])),
    kConsensusAttributes,
    0,
    nullptr,
    &Create,
    &Compute,
    &Reset,
    &Destroy,
    nullptr,
};

}  // namespace mjf::formation
