// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The input-constrained reaching law of the discrete protocol: equations (C0)-(C9) are ours,
// derived in docs/DISCUSSION.md ("The protocol under an acceleration limit"). Law (48) asks for
// the input that moves s_i to (1 - qT) s_i - eps T sgn(s_i) in one sample; from a large error
// that is far beyond what a vehicle can give, and the clipped loop overshoots because the
// linear surface s = 0 can only be slid on at consensus speeds |e_v| <= k2 a / k1. The law
// below keeps (48) whenever its demand is feasible and otherwise moves each consensus velocity
// error at a bounded rate towards a braking curve, so the follower arrives on the surface at a
// speed the bound can stop.
#include <algorithm>
#include <cmath>
#include <mjformation/formation/discrete_smc.hpp>
#include <mjformation/formation/shape.hpp>
#include <sstream>
#include <stdexcept>

namespace mjf::formation {
namespace {

constexpr double kSqrt2 = 1.41421356237309504880;
// b of (C4): the braking curve asks for b * beta, leaving (1 - b) beta for the sampling.
constexpr double kBrakingShare = 0.5;

double Norm2(double x, double y) { return std::sqrt(x * x + y * y); }

// Largest lambda in [0, 1] with ||c + lambda d|| <= a, given ||c|| <= a (C5).
double LargestFeasibleStep(double cx, double cy, double dx, double dy, double a) {
  if (Norm2(cx + dx, cy + dy) <= a) return 1.0;
  if (Norm2(cx, cy) > a) return 0.0;
  const double dd = dx * dx + dy * dy, cd = cx * dx + cy * dy, cc = cx * cx + cy * cy;
  const double root = std::sqrt(std::max(0.0, cd * cd - dd * (cc - a * a)));
  return std::clamp((-cd + root) / dd, 0.0, 1.0);  // positive root of ||c + l d||^2 = a^2
}

}  // namespace

void DiscreteSmcParams::ValidateAccelLimit() const {
  const double leader = kSqrt2 * std::max(std::abs(u_min), std::abs(u_max));
  if (!(accel_limit > 0.0) || std::isnan(accel_limit)) {
    std::ostringstream out;
    out << "attribute 'accel_limit': the acceleration bound must be > 0 m/s^2 (got " << accel_limit
        << ")";
    throw std::invalid_argument(out.str());
  }
  if (std::isfinite(accel_limit) && !(accel_limit > leader)) {
    std::ostringstream out;
    out << "attribute 'accel_limit': " << accel_limit
        << " m/s^2 does not exceed the leader's acceleration bound sqrt(2) max(|u_min|, "
           "|u_max|) = "
        << leader << " m/s^2: no follower can track every leader of Assumption 1 (C0)";
    throw std::invalid_argument(out.str());
  }
  if (!(reach_accel >= 0.0 && std::isfinite(reach_accel))) {
    std::ostringstream out;
    out << "attribute 'reach_accel': must be finite and >= 0 (0: derived, (C3)) (got "
        << reach_accel << ")";
    throw std::invalid_argument(out.str());
  }
}

void DiscreteSmc::InitAccelLimit() {
  const int n = graph_.num_followers();
  constrained_rhs_.resize(n, 2);
  // L_H is a nonsingular M-matrix (Lemma 1), so L_H^-1 >= 0 and its row sums are L_H^-1 1.
  constrained_rhs_.setOnes();
  solver_.SolveInPlace(constrained_rhs_);
  norm_inf_inv_lh_ = constrained_rhs_.col(0).maxCoeff();
}

// (C2)-(C6) for follower i: the constrained demand u^C_i. z = L_H^-1 e is the follower's own
// deviation x_i - f_i - x_0 (e = L_H z, eq. (16)); as in (53), it is computed from the leader
// state directly. compensation = (L_H^-1 H U0~)_i, the leader input (48) attributes to it.
void DiscreteSmc::ConstrainedDemand(const FormationInput& input, int i, const double* compensation,
                                    double* demand) const {
  const double k1 = params_.gains.k1, k2 = params_.gains.k2, T = params_.period;
  const double a = params_.accel_limit;
  const double* x0 = input.leader_pv;
  const double* xi = input.follower_pv + 4 * i;
  const double* f = input.shape_next + 6 * i;
  double zp[2], zv_free[2];
  for (int axis = 0; axis < 2; ++axis) {
    const double p = xi[axis] - x0[axis], v = xi[2 + axis] - x0[2 + axis];
    zp[axis] = p + T * v - f[axis];   // (C2): z_p(k+1), whatever u_i is
    zv_free[axis] = v - f[2 + axis];  // (C2): z_v(k+1) if u_i equals the leader's input
  }
  // (C3): what is left of the bound once the leader and the slot are tracked.
  const double slot_accel =
      Norm2(input.shape_now[6 * i + kShapeAx], input.shape_now[6 * i + kShapeAy]);
  const double beta = params_.reach_accel > 0.0
                          ? params_.reach_accel
                          : std::max(0.0, a - Norm2(compensation[0], compensation[1]) - slot_accel);
  // (C4): towards the slot along the surface's own law z_v = -(k1/k2) z_p where the bound can
  // hold it, else at the speed from which b * beta stops the follower at the slot.
  const double distance = Norm2(zp[0], zp[1]);
  const double speed =
      std::min(k1 / k2 * distance, std::sqrt(2.0 * kBrakingShare * beta * distance));
  const double scale = distance > 0.0 ? speed / distance : 0.0;
  double w[2];
  for (int axis = 0; axis < 2; ++axis) w[axis] = (-scale * zp[axis] - zv_free[axis]) / T;
  // (C5): u^C = compensation + t w, the largest t in [0, 1] the disc allows. The rows of
  // L_H^-1 H are >= 0 and sum to 1 (L_H 1 = H 1), so ||compensation|| <= sqrt(2) max(|u_min|,
  // |u_max|) < a by (C0), (C6): the projection below only guards a caller that skipped
  // Validate.
  const double c0 = compensation[0], c1 = compensation[1];
  if (Norm2(c0, c1) <= a) {
    const double t = LargestFeasibleStep(c0, c1, w[0], w[1], a);
    demand[0] = c0 + t * w[0];
    demand[1] = c1 + t * w[1];
  } else {
    demand[0] = c0 * a / Norm2(c0, c1);
    demand[1] = c1 * a / Norm2(c0, c1);
  }
}

// (C7)-(C8) per follower: law (48)'s u_i if feasible, else u^C_i. The followers decouple in
// sigma = L_H^-1 S (C1), so each one's choice is a reaching target of (53) of its own.
void DiscreteSmc::ApplyAccelLimit(const FormationInput& input) {
  const int n = graph_.num_followers();
  const double a = params_.accel_limit;
  const double mu1 = 0.5 * (params_.u_max + params_.u_min);
  const double mu2 = 0.5 * (params_.u_max - params_.u_min);
  ++stats_.samples;
  double peak = 0.0;
  bool all_feasible = true;
  for (int i = 0; i < n; ++i) {
    const double norm = Norm2(acceleration_[2 * i], acceleration_[2 * i + 1]);
    peak = std::max(peak, norm);
    all_feasible = all_feasible && norm <= a;
  }
  stats_.peak_paper_demand = std::max(stats_.peak_paper_demand, peak);
  if (all_feasible) {  // (C7): the paper's demand, bit for bit
    ++stats_.paper;
    return;
  }
  for (int i = 0; i < n; ++i) {
    for (int axis = 0; axis < 2; ++axis) {
      const double sign =
          SwitchingSign(sliding_[2 * i + axis], params_.sign, params_.boundary_layer);
      constrained_rhs_(i, axis) = graph_.leader_weight(i) * (mu1 - mu2 * sign);  // H U0~
    }
  }
  solver_.SolveInPlace(constrained_rhs_);
  for (int i = 0; i < n; ++i) {
    double* u = acceleration_.data() + 2 * i;
    if (Norm2(u[0], u[1]) <= a) continue;  // (C7) for this follower
    const double compensation[2] = {constrained_rhs_(i, 0), constrained_rhs_(i, 1)};
    double demand[2];
    ConstrainedDemand(input, i, compensation, demand);
    ++stats_.constrained;
    u[0] = demand[0];  // (C8)
    u[1] = demand[1];
  }
}

}  // namespace mjf::formation
