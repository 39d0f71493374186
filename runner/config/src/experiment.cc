// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/config/experiment.hpp"

#include <cstddef>

namespace mjf::runner {
namespace {

template <typename E, size_t N>
const char* WordOf(const EnumWord<E> (&words)[N], E value) {
  for (const auto& [word, v] : words) {
    if (v == value) return word;
  }
  return words[0].first;  // unreachable: every table names every value
}

}  // namespace

const char* ToString(RotorModel value) { return WordOf(kRotorModelWords, value); }
const char* ToString(CameraMode value) { return WordOf(kCameraModeWords, value); }
const char* ToString(ShapeType value) { return WordOf(kShapeTypeWords, value); }
const char* ToString(Execution value) { return WordOf(kExecutionWords, value); }
const char* ToString(Coupling value) { return WordOf(kCouplingWords, value); }
const char* ToString(Predict value) { return WordOf(kPredictWords, value); }
const char* ToString(ExchangeRounds value) { return WordOf(kExchangeRoundsWords, value); }
const char* ToString(RoundPolicy value) { return WordOf(kRoundPolicyWords, value); }

}  // namespace mjf::runner
