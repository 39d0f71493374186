// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Continuous sliding-mode formation tracking protocol, eq. (30), computed in its compact form
// eq. (33) with one solve against the factored L_H (both horizontal axes at once).
#ifndef MJFORMATION_FORMATION_CONTINUOUS_SMC_HPP_
#define MJFORMATION_FORMATION_CONTINUOUS_SMC_HPP_

#include <Eigen/Core>
#include <mjformation/formation/graph.hpp>
#include <mjformation/formation/laplacian_solver.hpp>
#include <mjformation/formation/sliding.hpp>
#include <mjformation/formation/solved_law.hpp>
#include <vector>

namespace mjf::formation {

// How the unknown leader input u_0 is compensated.
enum class Compensation {
  kLowerBound,  // u_min alone, exactly as printed in (30): s_i' = -rho sgn(s_i) - a_i0 k2 (u_0 -
                // u_min)
  kSwitching,   // u0~_i = mu1 - mu2 sgn(s_i) as in (48): s_i s_i' <= -rho |s_i|
};
// Reaching law.
enum class Reaching {
  kConstant,     // rho sgn(s_i), as printed
  kExponential,  // rho sgn(s_i) + q s_i: the T -> 0 limit of (48)
};

struct ContinuousSmcParams {
  SlidingGains gains;   // 'k'
  double rho = 0.05;    // 'rho', switching gain (m/s^3 in s units per s)
  double q = 4.5;       // 'q', 1/s, exponential reaching only
  double u_min = -1.0;  // 'u_min', m/s^2, lower bound of the leader's input
  double u_max = 1.0;   // 'u_max', m/s^2, upper bound (switching compensation)
  Compensation compensation = Compensation::kLowerBound;
  Reaching reaching = Reaching::kConstant;
  SignFunction sign = SignFunction::kSgn;
  double boundary_layer = 0.1;  // 'boundary_layer', phi of sat (sign = sat only)

  // Algorithm 1: k1, k2 > 0, rho > 0, q > 0 (exponential), u_min <= u_max, phi > 0 (sat).
  // Throws std::invalid_argument naming the key and the condition.
  void Validate() const;
};

Compensation ParseCompensation(const std::string& text);  // "lower_bound" / "switching"
Reaching ParseReaching(const std::string& text);          // "constant" / "exponential"

class ContinuousSmc : public SolvedLaw {
 public:
  // Validates params, requires a spanning tree and factors L_H (throws std::invalid_argument).
  ContinuousSmc(const Graph& graph, const ContinuousSmcParams& params);

  // Evaluates eq. (33) for the state in `input` (shape_now needed, shape_next ignored).
  // O(N + edges + nnz(factor)), no heap allocation.
  void Update(const FormationInput& input);

  // Outputs of the last Update (SolvedLaw): acceleration() u_i, sliding() s_i, error() e_i.

  // Reaching-time bound from the first Update's s_i(0): max_i |s_i(0)| / rho (constant) or
  // max_i ln(1 + q |s_i(0)| / rho) / q (exponential); < 0 before the first Update. Valid only
  // with switching compensation: with lower_bound it is Theorem 1's claim, which the closed
  // loop (35) does not satisfy when k2 a_i0 (u_0 - u_min) > rho.
  double reaching_time_bound() const { return reaching_time_bound_; }
  void ResetReachingTime() { reaching_time_bound_ = -1.0; }
  const ContinuousSmcParams& params() const { return params_; }
  long factor_nonzeros() const { return solver_.factor_nonzeros(); }

  // The last outputs and the reaching-time bound of the first Update (plugin_state.hpp).
  template <typename Visit>
  void VisitState(Visit& visit) {
    visit(acceleration_, sliding_, error_, reaching_time_bound_);
  }

 private:
  ContinuousSmcParams params_;
  double reaching_time_bound_ = -1.0;
};

}  // namespace mjf::formation

#endif  // MJFORMATION_FORMATION_CONTINUOUS_SMC_HPP_
