// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include <cmath>
#include <mjformation/formation/literature_laws.hpp>
#include <mjformation/formation/terminal_smc.hpp>
#include <sstream>
#include <stdexcept>

namespace mjf::formation {

void TerminalSmcParams::Validate() const {
  RequirePositive(beta, "beta", "Feng, Yu & Man (2002)'s surface");
  RequirePositive(rho, "rho", "Feng, Yu & Man (2002)'s reaching law");
  if (!(p > 0 && q > 0 && p % 2 == 1 && q % 2 == 1 && q < p && p < 2 * q)) {
    std::ostringstream out;
    out << "attributes 'p' and 'q': positive odd integers with 1 < p/q < 2 are required by "
           "Feng, Yu & Man (2002) (got p = "
        << p << ", q = " << q << "); e.g. p = 5, q = 3";
    throw std::invalid_argument(out.str());
  }
  ValidateSign(sign, boundary_layer);
}

double TerminalSlidingTime(const TerminalSmcParams& params, double x1) {
  const double ratio = static_cast<double>(params.q) / params.p;  // q/p
  return params.p / (std::pow(params.beta, ratio) * (params.p - params.q)) *
         std::pow(std::abs(x1), 1.0 - ratio);  // t_s = p / (beta^(q/p) (p - q)) |x1|^(1 - q/p)
}

TerminalSmc::TerminalSmc(const Graph& graph, const TerminalSmcParams& params)
    : SolvedLaw(graph),
      params_(Validated(params)),
      unused_sliding_(2 * graph_.num_followers(), 0.0) {}

void TerminalSmc::Update(const FormationInput& input) {
  const int n = graph_.num_followers();
  const double pq = static_cast<double>(params_.p) / params_.q;  // p/q in (1, 2)
  ComputeErrorAndSliding(graph_, SlidingGains{}, input.leader_pv, input.follower_pv,
                         input.shape_now, error_.data(), unused_sliding_.data());
  for (int i = 0; i < n; ++i) {
    for (int axis = 0; axis < 2; ++axis) {
      const double x1 = error_[4 * i + axis], x2 = error_[4 * i + 2 + axis];  // e_ip, e_iv
      const double s = x1 + SignedPower(x2, pq) / params_.beta;  // s = x1 + x2^(p/q) / beta
      sliding_[2 * i + axis] = s;
      rhs_(i, axis) = -params_.beta / pq * SignedPower(x2, 2.0 - pq)  // -beta (q/p) x2^(2-p/q)
                      - params_.rho * SwitchingSign(s, params_.sign,
                                                    params_.boundary_layer);  // -(l+eta) sgn(s)
    }
  }
  solver_.SolveInPlace(rhs_);  // U - F_a = L_H^-1 nu
  for (int i = 0; i < n; ++i) {
    for (int axis = 0; axis < 2; ++axis) {
      acceleration_[2 * i + axis] = input.shape_now[6 * i + 4 + axis] + rhs_(i, axis);
    }
  }
}

}  // namespace mjf::formation
