// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The predicted delay margin of the per-agent discrete protocol (48) over links with latency L
// (docs/NETWORK.md "Delay margin"). At the default broadcast rate (a message every
// step) a follower's neighbour data is L old; used as if current, the s_i it computes differs
// from the true one by L sum_j a_ij (k1 v_j + k2 u_j). The k2 u_j part closes the sample-level
// loop dU(k) = (1 - qT) (L / T) M dU(k-1), M = L_H^-1 A, which is stable iff
// (1 - qT) (L / T) rho(M) < 1: L* = T / ((1 - qT) rho(M)).
// With receiver-side prediction (predict = "input", in-phase clocks) a message sent after the
// sender's last sample carries the input it holds until now (u_j(k-1): the bus is one sample
// old), so for L < T the propagation is exact and no loop closes. From L = T on, the newest
// message predates the sender's sample at t_(k-1) and carries u_j(k-2) for the whole interval
// [t_(k-1), t_k): dU(k) = (1 - qT) M (dU(k-1) - dU(k-2)), per mode z^2 - a z + a = 0 with
// a = (1 - qT) lambda, stable iff a < 1 for the Perron root. Hence L* = T when
// (1 - qT) rho(M) >= 1 (a hard edge, not a gradual loss); otherwise this loop does not bound L
// below 2T (where the model stops) and 2T is reported as a lower bound.
// Linearisation: the sgn term, the k1 v_j term and the saturation are left out. Pure.
#ifndef MJFORMATION_CONTROL_DELAY_MARGIN_HPP_
#define MJFORMATION_CONTROL_DELAY_MARGIN_HPP_

#include <nlohmann/json.hpp>

namespace mjf::formation {
class Graph;
}  // namespace mjf::formation

namespace mjf::runner {

// rho(L_H^-1 A): the Perron root of the nonnegative M, by power iteration with sparse solves
// (M is positive on every connected part, so the root is dominant). O(N) per iteration.
double CouplingSpectralRadius(const formation::Graph& graph);

struct DelayMargin {
  double without_prediction = 0.0;      // s, L* = T / ((1 - qT) rho)
  double with_prediction = 0.0;         // s, L* = T, or 2T (a lower bound) when (1 - qT) rho < 1
  bool with_prediction_capped = false;  // the model's range (2T) reached: a lower bound
};

// period T, q of (48), rho = rho(L_H^-1 A). 1 - qT <= 0 or rho = 0: no loop (infinite margin).
DelayMargin PredictedDelayMargin(double period, double q, double rho);

// summary.json "network.delay_margin" (docs/NETWORK.md): rho and the margins predicted for the
// law's T and q, with and without prediction (an infinite margin is written as null).
nlohmann::json DelayMarginSummary(double period, double q, double rho);

}  // namespace mjf::runner

#endif  // MJFORMATION_CONTROL_DELAY_MARGIN_HPP_
