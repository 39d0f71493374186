// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The parameters of one simulated radio link (link.hpp): broadcast period, latency, jitter,
// loss (Bernoulli or Gilbert-Elliott bursts) and range. Plain data, so the experiment's struct
// (runner/config) carries them without the link.
#ifndef MJFORMATION_NETWORK_LINK_PARAMS_HPP_
#define MJFORMATION_NETWORK_LINK_PARAMS_HPP_

#include <cstdint>

namespace mjf::network {

enum class LossModel { kBernoulli, kGilbertElliott };

struct LinkParams {
  int64_t period_steps = 1;  // broadcast every period_steps physics steps (rate = 1 / (n dt))
  double latency = 0.0;      // s, fixed part of the delay
  double jitter = 0.0;       // s, uniform [0, jitter] added to each message's delay
  LossModel loss_model = LossModel::kBernoulli;
  double loss = 0.0;         // Bernoulli loss probability; Gilbert-Elliott: loss in the good state
  double burst_enter = 0.0;  // Gilbert-Elliott: P(good -> bad) per message
  double burst_exit = 1.0;   // Gilbert-Elliott: P(bad -> good) per message (mean burst 1/exit)
  double burst_loss = 1.0;   // Gilbert-Elliott: loss probability in the bad state
  double range = 0.0;        // m, the link exists only while the vehicles are within it; 0: always
};

}  // namespace mjf::network

#endif  // MJFORMATION_NETWORK_LINK_PARAMS_HPP_
