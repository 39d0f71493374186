// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include <cmath>
#include <mjformation/formation/sliding.hpp>
#include <sstream>
#include <stdexcept>

namespace mjf::formation {

double SwitchingSign(double s, SignFunction function, double boundary_layer) {
  if (function == SignFunction::kSat) {
    const double ratio = s / boundary_layer;
    return ratio > 1.0 ? 1.0 : (ratio < -1.0 ? -1.0 : ratio);
  }
  return s > 0.0 ? 1.0 : (s < 0.0 ? -1.0 : 0.0);
}

SignFunction ParseSignFunction(const std::string& text, const char* key) {
  if (text == "sgn") return SignFunction::kSgn;
  if (text == "sat") return SignFunction::kSat;
  throw std::invalid_argument(std::string("attribute '") + key + "': '" + text +
                              "' is not one of 'sgn', 'sat'");
}

void ValidateGains(const SlidingGains& gains) {
  if (!(gains.k1 > 0.0 && gains.k2 > 0.0 && std::isfinite(gains.k1) && std::isfinite(gains.k2))) {
    std::ostringstream out;
    out << "attribute 'k': k1 > 0 and k2 > 0 are required by Theorems 1 and 2 (got k1 = "
        << gains.k1 << ", k2 = " << gains.k2 << ")";
    throw std::invalid_argument(out.str());
  }
}

void ValidateLeaderBounds(double u_min, double u_max) {
  if (!(std::isfinite(u_min) && std::isfinite(u_max) && u_min <= u_max)) {
    std::ostringstream out;
    out << "attribute 'u_min' with 'u_max': finite u_min <= u_max is required (bounds of the "
           "leader's input, Algorithms 1/2) (got u_min = "
        << u_min << ", u_max = " << u_max << ")";
    throw std::invalid_argument(out.str());
  }
}

void ValidateSign(SignFunction function, double boundary_layer) {
  if (function == SignFunction::kSat && !(boundary_layer > 0.0 && std::isfinite(boundary_layer))) {
    std::ostringstream out;
    out << "attribute 'boundary_layer' with 'sign' = 'sat': boundary_layer > 0 is required "
           "(got "
        << boundary_layer << ")";
    throw std::invalid_argument(out.str());
  }
}

void ComputeErrorAndSliding(const Graph& graph, const SlidingGains& gains, const double* leader_pv,
                            const double* follower_pv, const double* shape, double* error,
                            double* sliding) {
  const int n = graph.num_followers();
  // With z_i = x_i - f_i - x_0 (per component), eq. (16) reads e_i = (L_H z)_i: the leader's
  // state cancels in the neighbour differences.
  auto z = [&](int i, int k) { return follower_pv[4 * i + k] - shape[6 * i + k] - leader_pv[k]; };
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < 4; ++k) {
      const double zi = z(i, k);
      double e = graph.leader_weight(i) * zi;  // a_i0 (x_i - f_i - x_0), eq. (16)
      for (int m = graph.in_begin(i); m < graph.in_end(i); ++m) {
        e += graph.in_weight(m) * (zi - z(graph.in_neighbor(m), k));  // a_ij (...), eq. (16)
      }
      error[4 * i + k] = e;
    }
    for (int axis = 0; axis < 2; ++axis) {
      sliding[2 * i + axis] = gains.k1 * error[4 * i + axis] +
                              gains.k2 * error[4 * i + 2 + axis];  // s_i = K e_i, eq. (17)
    }
  }
}

}  // namespace mjf::formation
