// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// One follower's share of the five laws from the literature, for distributed execution
// ([execution] mode = "per_agent"), with the interface of agent_laws.hpp (one plugin adapter,
// agent_adapter.hpp, serves them all). Each row is the swarm-level law's row i (the header of the
// same name states the law and its source), computed from e_i of eq. (16) of this follower's own
// data (AgentError):
//   - vs_tracking, adaptive_tracking, observer_tracking use e_i and the own state only: no
//     coupling through the neighbours' inputs (LocalAgentRow, like LinearConsensusAgent);
//   - super_twisting and terminal_smc close U = F_a + L_H^-1 R (the swarm-wide solve) row by row
//     (SolvedAgentRow, like ContinuousSmcAgent).
// A law whose state advances with time (the adaptive gain d_i, the estimate vbar_i, the
// super-twisting integral) takes the host's time in Advance() before Prepare(); the exchange
// rounds of one tick share the tick's time and recompute the tick from the state it started with.
#ifndef MJFORMATION_FORMATION_LITERATURE_AGENTS_HPP_
#define MJFORMATION_FORMATION_LITERATURE_AGENTS_HPP_

#include <mjformation/formation/adaptive_tracking.hpp>
#include <mjformation/formation/agent_laws.hpp>
#include <mjformation/formation/literature_laws.hpp>
#include <mjformation/formation/observer_tracking.hpp>
#include <mjformation/formation/super_twisting.hpp>
#include <mjformation/formation/terminal_smc.hpp>
#include <mjformation/formation/vs_tracking.hpp>
#include <vector>

namespace mjf::formation {

// The step of a law that integrates a state, once per tick: Advance(time) is true when `time`
// starts a new tick (the caller then takes its state after the last tick as this tick's start);
// dt() is StepClock's step from the previous tick (0 on the first).
class TickClock {
 public:
  bool Advance(double time) {
    if (time == tick_time_) return false;  // another exchange round of the same tick
    dt_ = clock_.Advance(time);
    tick_time_ = time;
    return true;
  }
  double dt() const { return dt_; }
  void Reset() {
    clock_.Reset();
    tick_time_ = std::numeric_limits<double>::quiet_NaN();
    dt_ = 0.0;
  }
  template <typename Visit>
  void VisitState(Visit& visit) {
    clock_.VisitState(visit);
    visit(tick_time_, dt_);
  }

 private:
  StepClock clock_;
  double tick_time_ = std::numeric_limits<double>::quiet_NaN();
  double dt_ = 0.0;
};

// vs_tracking.hpp's row: u_i = f_ia - (e_ip + alpha e_iv) - beta sgn(gamma e_ip + e_iv).
class VsTrackingAgent : public LocalAgentRow {
 public:
  VsTrackingAgent(const VsTrackingParams& params, double leader_weight,
                  std::vector<double> weights);
  void Prepare(const double* own_pv, const double* leader_pv, const double* f_now,
               const double* f_next, const double* neighbour_pv, const double* neighbour_f_now,
               const double* neighbour_f_next);
  template <typename Visit>
  void VisitState(Visit& visit) {  // plugin_state.hpp
    visit(acceleration_, sliding_);
  }

 private:
  VsTrackingParams params_;
};

// adaptive_tracking.hpp's row: u_i = f_ia + d_i w_i + d_i r(w_i), w_i = K xi_i, and d_i' of Li
// et al. over the tick.
class AdaptiveTrackingAgent : public LocalAgentRow {
 public:
  AdaptiveTrackingAgent(const AdaptiveTrackingParams& params, double leader_weight,
                        std::vector<double> weights);
  void Advance(double time);
  void Prepare(const double* own_pv, const double* leader_pv, const double* f_now,
               const double* f_next, const double* neighbour_pv, const double* neighbour_f_now,
               const double* neighbour_f_next);
  void Reset();  // d_i = d0, the clock as before the first tick
  double gain() const { return gain_; }
  template <typename Visit>
  void VisitState(Visit& visit) {
    visit(acceleration_, sliding_, gain_, gain_at_tick_);
    clock_.VisitState(visit);
  }

 private:
  AdaptiveTrackingParams params_;
  double gain_;          // d_i after this tick
  double gain_at_tick_;  // d_i at the tick's start
  TickClock clock_;
};

// observer_tracking.hpp's row: v_ref = f_iv + vbar_i - k e_ip, u_i = f_ia + vbar_i' +
// kv (v_ref - v_i), vbar_i' = -gamma k e_ip over the tick. The leader's velocity is not read.
class ObserverTrackingAgent : public LocalAgentRow {
 public:
  ObserverTrackingAgent(const ObserverTrackingParams& params, double leader_weight,
                        std::vector<double> weights);
  void Advance(double time);
  void Prepare(const double* own_pv, const double* leader_pv, const double* f_now,
               const double* f_next, const double* neighbour_pv, const double* neighbour_f_now,
               const double* neighbour_f_next);
  void Reset();  // vbar_i = 0, the clock as before the first tick
  template <typename Visit>
  void VisitState(Visit& visit) {
    visit(acceleration_, sliding_, vbar_, vbar_at_tick_);
    clock_.VisitState(visit);
  }

 private:
  ObserverTrackingParams params_;
  double vbar_[2] = {0, 0}, vbar_at_tick_[2] = {0, 0};
  TickClock clock_;
};

// super_twisting.hpp's row: R_i = (V_i - k1 e_iv) / k2, V_i = -lambda |s_i|^(1/2) sgn(s_i) + w_i,
// s_i = K e_i (eq. (17)), the integral w_i' = -alpha sgn(s_i) over the tick.
class SuperTwistingAgent : public SolvedAgentRow {
 public:
  SuperTwistingAgent(const SuperTwistingParams& params, double leader_weight,
                     std::vector<double> weights);
  void Advance(double time);
  void Prepare(const double* own_pv, const double* leader_pv, const double* f_now,
               const double* f_next, const double* neighbour_pv, const double* neighbour_f_now,
               const double* neighbour_f_next);
  void Reset();  // the integral 0, the clock as before the first tick
  template <typename Visit>
  void VisitState(Visit& visit) {
    VisitRow(visit);
    visit(integral_, integral_at_tick_);
    clock_.VisitState(visit);
  }

 private:
  SuperTwistingParams params_;
  double integral_[2] = {0, 0}, integral_at_tick_[2] = {0, 0};
  TickClock clock_;
};

// terminal_smc.hpp's row: R_i = nu_i = -beta (q/p) e_iv^(2 - p/q) - rho sgn(s_i),
// s_i = e_ip + e_iv^(p/q) / beta.
class TerminalSmcAgent : public SolvedAgentRow {
 public:
  TerminalSmcAgent(const TerminalSmcParams& params, double leader_weight,
                   std::vector<double> weights);
  void Prepare(const double* own_pv, const double* leader_pv, const double* f_now,
               const double* f_next, const double* neighbour_pv, const double* neighbour_f_now,
               const double* neighbour_f_next);
  template <typename Visit>
  void VisitState(Visit& visit) {  // stateless but for the row
    VisitRow(visit);
  }

 private:
  TerminalSmcParams params_;
};

}  // namespace mjf::formation

#endif  // MJFORMATION_FORMATION_LITERATURE_AGENTS_HPP_
