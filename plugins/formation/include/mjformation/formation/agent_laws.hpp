// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// One follower's share of the continuous sliding-mode protocol (30) and of the linear consensus
// baseline, for distributed execution (the discrete protocol is DiscreteSmcAgent), and the rows
// they and the laws from the literature (literature_agents.hpp) are made of. Same interface as
// DiscreteSmcAgent so that one plugin adapter serves them all.
//
// (30) row i, multiplied out, is row i of L_H W = R in w_i = u_i - f_ia with
//   R_i = (-k1 e_iv - rho sgn(s_i) [- q s_i]) / k2 + a_i0 u~_i,
// the compact form (33) solving all rows at once: w_i = (R_i + sum_j a_ij w_j) / (d_i + a_i0).
#ifndef MJFORMATION_FORMATION_AGENT_LAWS_HPP_
#define MJFORMATION_FORMATION_AGENT_LAWS_HPP_

#include <mjformation/formation/continuous_smc.hpp>
#include <mjformation/formation/linear_consensus.hpp>
#include <utility>
#include <vector>

namespace mjf::formation {

// e_i of eq. (16) from follower i's own data: e[k], k = (px, py, vx, vy). leader_pv is read only
// when leader_weight > 0.
void AgentError(double leader_weight, const std::vector<double>& weights, const double* own_pv,
                const double* leader_pv, const double* f_now, const double* neighbour_pv,
                const double* neighbour_f_now, double* e);

// d_i + a_i0, the follower's row sum of L_H; throws std::invalid_argument when it is 0 (the
// follower hears neither the leader nor a neighbour).
double AgentDegree(double leader_weight, const std::vector<double>& weights);

// What every follower's row starts from: its weights, e_i of eq. (16) from its own data, and the
// acceleration and sliding variable it reports.
class AgentRow {
 public:
  const double* acceleration() const { return acceleration_; }
  const double* sliding() const { return sliding_; }

 protected:
  AgentRow(double leader_weight, std::vector<double> weights);
  // e_i of eq. (16), e[k], k = (px, py, vx, vy).
  void Error(const double* own_pv, const double* leader_pv, const double* f_now,
             const double* neighbour_pv, const double* neighbour_f_now, double* e) const {
    AgentError(leader_weight_, weights_, own_pv, leader_pv, f_now, neighbour_pv, neighbour_f_now,
               e);
  }
  double leader_weight_;
  std::vector<double> weights_;
  double degree_;  // d_i + a_i0
  double acceleration_[2] = {0, 0};
  double sliding_[2] = {0, 0};
};

// A row without coupling through the neighbours' inputs (u_i from e_i and the own state): nothing
// to exchange (coupling and rhs are zero, Solve a no-op).
class LocalAgentRow : public AgentRow {
 public:
  double CouplingFromInput(int, int, double) const { return 0.0; }
  void Solve(const double*) {}
  void UseSolved(const double*) {}
  const double* coupling() const { return zero_; }
  const double* rhs() const { return zero_; }

 protected:
  LocalAgentRow(double leader_weight, std::vector<double> weights)
      : AgentRow(leader_weight, std::move(weights)) {}
  double zero_[2] = {0, 0};
};

// A row closed through L_H (U = F_a + L_H^-1 R, the swarm-wide solve, row by row): row i of
// L_H W = R in w_i = u_i - f_ia, w_i = (R_i + sum_j a_ij w_j) / (d_i + a_i0), with w_j from the
// host (its central solve, a Jacobi round, or the neighbours' last inputs: agent_adapter.hpp),
// and the feed-forward f_ia, f_ja that turn inputs into w and back.
class SolvedAgentRow : public AgentRow {
 public:
  double CouplingFromInput(int m, int axis, double u_j) const {
    return u_j - neighbour_fa_[2 * m + axis];  // w_j = u_j - f_ja
  }
  void Solve(const double* w_neighbours);
  void UseSolved(const double* w_own);
  const double* coupling() const { return w_; }
  const double* rhs() const { return rhs_; }

 protected:
  SolvedAgentRow(double leader_weight, std::vector<double> weights);
  // Keeps f_ia and the neighbours' f_ja of this tick (u = f_a + w).
  void KeepFeedForward(const double* f_now, const double* neighbour_f_now);
  template <typename Visit>
  void VisitRow(Visit& visit) {
    visit(neighbour_fa_, own_fa_, rhs_, w_, acceleration_, sliding_);
  }
  std::vector<double> neighbour_fa_;  // [2m + axis]
  double own_fa_[2] = {0, 0};
  double rhs_[2] = {0, 0}, w_[2] = {0, 0};
};

class ContinuousSmcAgent : public SolvedAgentRow {
 public:
  ContinuousSmcAgent(const ContinuousSmcParams& params, double leader_weight,
                     std::vector<double> weights);
  // f_next and neighbour_f_next are unused (a continuous law); kept for the common interface.
  void Prepare(const double* own_pv, const double* leader_pv, const double* f_now,
               const double* f_next, const double* neighbour_pv, const double* neighbour_f_now,
               const double* neighbour_f_next);
  const ContinuousSmcParams& params() const { return params_; }

  template <typename Visit>
  void VisitState(Visit& visit) {  // plugin_state.hpp
    VisitRow(visit);
  }

 private:
  ContinuousSmcParams params_;
};

// u_i = f_ia - kp e_ip - kv e_iv: no coupling through the neighbours' inputs.
class LinearConsensusAgent : public LocalAgentRow {
 public:
  LinearConsensusAgent(const LinearConsensusParams& params, double leader_weight,
                       std::vector<double> weights);
  void Prepare(const double* own_pv, const double* leader_pv, const double* f_now,
               const double* f_next, const double* neighbour_pv, const double* neighbour_f_now,
               const double* neighbour_f_next);
  const double* sliding() const { return nullptr; }  // no sliding variable

  template <typename Visit>
  void VisitState(Visit& visit) {  // plugin_state.hpp
    visit(acceleration_);
  }

 private:
  LinearConsensusParams params_;
};

}  // namespace mjf::formation

#endif  // MJFORMATION_FORMATION_AGENT_LAWS_HPP_
