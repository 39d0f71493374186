// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include <cmath>
#include <mjformation/formation/literature_agents.hpp>
#include <utility>

namespace mjf::formation {

VsTrackingAgent::VsTrackingAgent(const VsTrackingParams& params, double leader_weight,
                                 std::vector<double> weights)
    : LocalAgentRow(leader_weight, std::move(weights)), params_(Validated(params)) {}

void VsTrackingAgent::Prepare(const double* own_pv, const double* leader_pv, const double* f_now,
                              const double*, const double* neighbour_pv,
                              const double* neighbour_f_now, const double*) {
  double e[4];
  Error(own_pv, leader_pv, f_now, neighbour_pv, neighbour_f_now, e);
  for (int axis = 0; axis < 2; ++axis) {
    const double ep = e[axis], ev = e[2 + axis];
    const double sigma = params_.gamma * ep + ev;  // sum a_ij [gamma (r_i - r_j) + (v_i - v_j)]
    sliding_[axis] = sigma;
    acceleration_[axis] = f_now[4 + axis] - (ep + params_.alpha * ev) -
                          params_.beta * SwitchingSign(sigma, params_.sign,
                                                       params_.boundary_layer);  // - beta sgn{.}
  }
}

AdaptiveTrackingAgent::AdaptiveTrackingAgent(const AdaptiveTrackingParams& params,
                                             double leader_weight, std::vector<double> weights)
    : LocalAgentRow(leader_weight, std::move(weights)),
      params_(Validated(params)),
      gain_(params_.d0),
      gain_at_tick_(params_.d0) {}

void AdaptiveTrackingAgent::Advance(double time) {
  if (clock_.Advance(time)) gain_at_tick_ = gain_;
}

void AdaptiveTrackingAgent::Reset() {
  gain_ = gain_at_tick_ = params_.d0;
  clock_.Reset();
}

void AdaptiveTrackingAgent::Prepare(const double* own_pv, const double* leader_pv,
                                    const double* f_now, const double*, const double* neighbour_pv,
                                    const double* neighbour_f_now, const double*) {
  double e[4], w[2];
  Error(own_pv, leader_pv, f_now, neighbour_pv, neighbour_f_now, e);  // xi_i
  for (int axis = 0; axis < 2; ++axis) {
    w[axis] = -(e[axis] + kAdaptiveVelocityWeight * e[2 + axis]);  // K xi_i
    sliding_[axis] = -w[axis];
  }
  const double norm = std::hypot(w[0], w[1]);  // ||K xi_i||
  const double d = gain_at_tick_;
  for (int axis = 0; axis < 2; ++axis) {
    const double r = norm + params_.kappa > 0.0 ? w[axis] / (norm + params_.kappa) : 0.0;
    acceleration_[axis] = f_now[4 + axis] + d * w[axis] + d * r;  // d_i K xi_i + d_i r(K xi_i)
  }
  // d_i' = tau [-phi d_i + xi' Gamma xi + ||K xi||], xi' Gamma xi = ||K xi||^2.
  gain_ = d + clock_.dt() * params_.tau * (-params_.phi * d + norm * norm + norm);
}

ObserverTrackingAgent::ObserverTrackingAgent(const ObserverTrackingParams& params,
                                             double leader_weight, std::vector<double> weights)
    : LocalAgentRow(leader_weight, std::move(weights)), params_(Validated(params)) {}

void ObserverTrackingAgent::Advance(double time) {
  if (!clock_.Advance(time)) return;
  vbar_at_tick_[0] = vbar_[0];
  vbar_at_tick_[1] = vbar_[1];
}

void ObserverTrackingAgent::Reset() {
  vbar_[0] = vbar_[1] = vbar_at_tick_[0] = vbar_at_tick_[1] = 0.0;
  clock_.Reset();
}

void ObserverTrackingAgent::Prepare(const double* own_pv, const double* leader_pv,
                                    const double* f_now, const double*, const double* neighbour_pv,
                                    const double* neighbour_f_now, const double*) {
  double e[4];
  // Only the position rows of e_i are used: they do not involve the leader's velocity.
  Error(own_pv, leader_pv, f_now, neighbour_pv, neighbour_f_now, e);
  for (int axis = 0; axis < 2; ++axis) {
    const double ep = e[axis];
    sliding_[axis] = ep;
    const double vbar_rate = -params_.gamma * params_.k * ep;  // vbar_i', a_0 -> 0
    const double v_ref = f_now[2 + axis] + vbar_at_tick_[axis] - params_.k * ep;  // u_i of Hong
    acceleration_[axis] =
        f_now[4 + axis] + vbar_rate + params_.kv * (v_ref - own_pv[2 + axis]);  // inner loop
    vbar_[axis] = vbar_at_tick_[axis] + clock_.dt() * vbar_rate;
  }
}

SuperTwistingAgent::SuperTwistingAgent(const SuperTwistingParams& params, double leader_weight,
                                       std::vector<double> weights)
    : SolvedAgentRow(leader_weight, std::move(weights)), params_(Validated(params)) {}

void SuperTwistingAgent::Advance(double time) {
  if (!clock_.Advance(time)) return;
  integral_at_tick_[0] = integral_[0];
  integral_at_tick_[1] = integral_[1];
}

void SuperTwistingAgent::Reset() {
  integral_[0] = integral_[1] = integral_at_tick_[0] = integral_at_tick_[1] = 0.0;
  clock_.Reset();
}

void SuperTwistingAgent::Prepare(const double* own_pv, const double* leader_pv, const double* f_now,
                                 const double*, const double* neighbour_pv,
                                 const double* neighbour_f_now, const double*) {
  const double k1 = params_.gains.k1, k2 = params_.gains.k2;
  double e[4];
  Error(own_pv, leader_pv, f_now, neighbour_pv, neighbour_f_now, e);
  for (int axis = 0; axis < 2; ++axis) {
    const double s = k1 * e[axis] + k2 * e[2 + axis];  // s_i = K e_i, eq. (17)
    sliding_[axis] = s;
    // w_i' = -alpha sgn(s_i) over the step that ends now (Euler, sign taken at its end).
    integral_[axis] = integral_at_tick_[axis] -
                      clock_.dt() * params_.alpha * (s > 0.0 ? 1.0 : (s < 0.0 ? -1.0 : 0.0));
    const double v = -params_.lambda * SignedPower(s, 0.5) + integral_[axis];  // V_i of the STA
    rhs_[axis] = (v - k1 * e[2 + axis]) / k2;                                  // (V - k1 E_v) / k2
  }
  KeepFeedForward(f_now, neighbour_f_now);
}

TerminalSmcAgent::TerminalSmcAgent(const TerminalSmcParams& params, double leader_weight,
                                   std::vector<double> weights)
    : SolvedAgentRow(leader_weight, std::move(weights)), params_(Validated(params)) {}

void TerminalSmcAgent::Prepare(const double* own_pv, const double* leader_pv, const double* f_now,
                               const double*, const double* neighbour_pv,
                               const double* neighbour_f_now, const double*) {
  const double pq = static_cast<double>(params_.p) / params_.q;  // p/q in (1, 2)
  double e[4];
  Error(own_pv, leader_pv, f_now, neighbour_pv, neighbour_f_now, e);
  for (int axis = 0; axis < 2; ++axis) {
    const double x1 = e[axis], x2 = e[2 + axis];               // e_ip, e_iv
    const double s = x1 + SignedPower(x2, pq) / params_.beta;  // s = x1 + x2^(p/q) / beta
    sliding_[axis] = s;
    rhs_[axis] = -params_.beta / pq * SignedPower(x2, 2.0 - pq)  // -beta (q/p) x2^(2-p/q)
                 - params_.rho * SwitchingSign(s, params_.sign,
                                               params_.boundary_layer);  // -(l+eta) sgn(s)
  }
  KeepFeedForward(f_now, neighbour_f_now);
}

}  // namespace mjf::formation
