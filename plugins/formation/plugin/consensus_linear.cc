// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// consensus_linear: the linear consensus-based formation tracking baseline (see the core's
// linear_consensus.hpp), evaluated every physics step. No sliding variable: sliding stays NaN.
#include <mjformation/formation/linear_consensus.hpp>

#include "adapter.hpp"

namespace mjf::formation::adapter {

const mjfAttribute kConsensusAttributes[] = {
    {kKeyKp, "1", "position gain kp > 0, 1/s^2"},
    {kKeyKv, "2", "velocity gain kv > 0, 1/s"},
};
const int kConsensusAttributeCount =
    static_cast<int>(sizeof(kConsensusAttributes) / sizeof(kConsensusAttributes[0]));

formation::LinearConsensusParams ParseConsensusParams(const plugin::Attributes& attributes) {
  formation::LinearConsensusParams params;
  params.kp = attributes.Number(kKeyKp);
  params.kv = attributes.Number(kKeyKv);
  params.Validate();
  return params;
}

namespace {

struct Instance : SwarmInstance<formation::LinearConsensus> {
  using Config = formation::LinearConsensusParams;
  static Config Configure(const mjfCreateContext* ctx) {
    return ParseConsensusParams(plugin::Attributes(ctx));
  }
  using SwarmInstance::SwarmInstance;
  const double* sliding() const { return nullptr; }  // no sliding variable: it stays NaN
};

}  // namespace

const mjfPlugin kConsensusLinear = SwarmPlugin<Instance>(
    "consensus_linear", "linear consensus-based time-varying formation tracking (baseline)",
    kConsensusAttributes);

}  // namespace mjf::formation::adapter
