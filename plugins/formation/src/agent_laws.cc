// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include <mjformation/formation/agent_laws.hpp>
#include <stdexcept>
#include <utility>

namespace mjf::formation {
double AgentDegree(double leader_weight, const std::vector<double>& weights) {
  double degree = leader_weight;
  for (double a : weights) degree += a;
  if (!(degree > 0.0)) {
    throw std::invalid_argument("agent: this follower hears neither the leader nor a neighbour");
  }
  return degree;
}

void AgentError(double leader_weight, const std::vector<double>& weights, const double* own_pv,
                const double* leader_pv, const double* f_now, const double* neighbour_pv,
                const double* neighbour_f_now, double* e) {
  for (int k = 0; k < 4; ++k) {
    const double zi = own_pv[k] - f_now[k];
    e[k] = leader_weight > 0.0 ? leader_weight * (zi - leader_pv[k]) : 0.0;  // eq. (16)
    for (size_t j = 0; j < weights.size(); ++j) {
      e[k] += weights[j] * (zi - (neighbour_pv[4 * j + k] - neighbour_f_now[6 * j + k]));
    }
  }
}

AgentRow::AgentRow(double leader_weight, std::vector<double> weights)
    : leader_weight_(leader_weight),
      weights_(std::move(weights)),
      degree_(AgentDegree(leader_weight_, weights_)) {}  // refuses a follower that hears no one

SolvedAgentRow::SolvedAgentRow(double leader_weight, std::vector<double> weights)
    : AgentRow(leader_weight, std::move(weights)), neighbour_fa_(2 * weights_.size(), 0.0) {}

void SolvedAgentRow::KeepFeedForward(const double* f_now, const double* neighbour_f_now) {
  for (int axis = 0; axis < 2; ++axis) {
    own_fa_[axis] = f_now[4 + axis];
    for (size_t j = 0; j < weights_.size(); ++j) {
      neighbour_fa_[2 * j + axis] = neighbour_f_now[6 * j + 4 + axis];
    }
  }
}

void SolvedAgentRow::Solve(const double* w_neighbours) {
  for (int axis = 0; axis < 2; ++axis) {
    double sum = rhs_[axis];
    for (size_t j = 0; j < weights_.size(); ++j) sum += weights_[j] * w_neighbours[2 * j + axis];
    w_[axis] = sum / degree_;                        // row i of L_H W = R
    acceleration_[axis] = own_fa_[axis] + w_[axis];  // u_i = f_ia + w_i
  }
}

void SolvedAgentRow::UseSolved(const double* w_own) {
  for (int axis = 0; axis < 2; ++axis) {
    w_[axis] = w_own[axis];
    acceleration_[axis] = own_fa_[axis] + w_[axis];
  }
}

ContinuousSmcAgent::ContinuousSmcAgent(const ContinuousSmcParams& params, double leader_weight,
                                       std::vector<double> weights)
    : SolvedAgentRow(leader_weight, std::move(weights)), params_(Validated(params)) {}

void ContinuousSmcAgent::Prepare(const double* own_pv, const double* leader_pv, const double* f_now,
                                 const double*, const double* neighbour_pv,
                                 const double* neighbour_f_now, const double*) {
  const double k1 = params_.gains.k1, k2 = params_.gains.k2;
  const double mu1 = 0.5 * (params_.u_max + params_.u_min);
  const double mu2 = 0.5 * (params_.u_max - params_.u_min);
  double e[4];
  Error(own_pv, leader_pv, f_now, neighbour_pv, neighbour_f_now, e);
  for (int axis = 0; axis < 2; ++axis) {
    const double s = k1 * e[axis] + k2 * e[2 + axis];  // eq. (17)
    sliding_[axis] = s;
    const double sign = SwitchingSign(s, params_.sign, params_.boundary_layer);
    const double leader_input =
        params_.compensation == Compensation::kLowerBound ? params_.u_min : mu1 - mu2 * sign;
    double reaching = params_.rho * sign;  // rho sgn(s_i), eq. (30)
    if (params_.reaching == Reaching::kExponential) reaching += params_.q * s;
    rhs_[axis] = (-k1 * e[2 + axis] - reaching) / k2 + leader_weight_ * leader_input;  // (33)
  }
  KeepFeedForward(f_now, neighbour_f_now);
}

LinearConsensusAgent::LinearConsensusAgent(const LinearConsensusParams& params,
                                           double leader_weight, std::vector<double> weights)
    : LocalAgentRow(leader_weight, std::move(weights)), params_(Validated(params)) {}

void LinearConsensusAgent::Prepare(const double* own_pv, const double* leader_pv,
                                   const double* f_now, const double*, const double* neighbour_pv,
                                   const double* neighbour_f_now, const double*) {
  double e[4];
  Error(own_pv, leader_pv, f_now, neighbour_pv, neighbour_f_now, e);
  for (int axis = 0; axis < 2; ++axis) {
    acceleration_[axis] = f_now[4 + axis] - params_.kp * e[axis] - params_.kv * e[2 + axis];
  }
}

}  // namespace mjf::formation
