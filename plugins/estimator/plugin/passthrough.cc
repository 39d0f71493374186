// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// passthrough: the estimate is the sensor stage's held samples, bit for bit (what the
// controllers saw before estimators existed); the covariance is unknown (NaN).
#include <cmath>
#include <limits>

#include "adapter.hpp"

namespace mjf::estimator::adapter {
namespace {

struct Passthrough {
  int vehicle;
  template <typename Visit>
  void VisitState(Visit&) {}  // no state: the held samples are the sensor stage's
};

void* PassthroughCreate(const mjfCreateContext* ctx) { return new Passthrough{ctx->vehicle}; }

int PassthroughCompute(void* instance, const mjfStepContext* ctx) {
  (void)instance;
  ctx->estimate->state = *ctx->estimator->held;
  for (double& c : ctx->estimate->covariance) c = std::numeric_limits<double>::quiet_NaN();
  return 0;
}

}  // namespace

const mjfPlugin kPassthrough = EstimatorPlugin<Passthrough>(
    "passthrough", "no estimator: the controllers see the held sensor samples", 0, nullptr,
    PassthroughCreate, PassthroughCompute);

}  // namespace mjf::estimator::adapter
