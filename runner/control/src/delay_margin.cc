// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/control/delay_margin.hpp"

#include <Eigen/Core>
#include <cmath>
#include <limits>

#include "mjformation/formation/graph.hpp"
#include "mjformation/formation/laplacian_solver.hpp"

namespace mjf::runner {

double CouplingSpectralRadius(const formation::Graph& graph) {
  const int n = graph.num_followers();
  formation::LaplacianSolver solver(graph.laplacian_h());
  Eigen::Matrix<double, Eigen::Dynamic, 2> x(n, 2), ax(n, 2);
  x.setOnes();
  double rho = 0.0;
  for (int it = 0; it < 500; ++it) {
    ax.setZero();
    for (int i = 0; i < n; ++i) {  // (A x)_i = sum_j a_ij x_j
      for (int k = graph.in_begin(i); k < graph.in_end(i); ++k) {
        ax.row(i) += graph.in_weight(k) * x.row(graph.in_neighbor(k));
      }
    }
    solver.SolveInPlace(ax);
    const double norm = ax.col(0).norm();
    const double previous = rho;
    rho = norm / x.col(0).norm();
    if (norm == 0.0) return 0.0;
    x = ax / norm;
    if (it > 10 && std::abs(rho - previous) <= 1e-13 * rho) break;
  }
  return rho;
}

DelayMargin PredictedDelayMargin(double period, double q, double rho) {
  const double gain = (1.0 - q * period) * rho;  // (1 - qT) rho(M)
  DelayMargin m;
  if (!(gain > 0.0)) {
    m.without_prediction = m.with_prediction = std::numeric_limits<double>::infinity();
    return m;
  }
  m.without_prediction = period / gain;
  // From L = T on the whole last hold interval is predicted with the input before it.
  m.with_prediction_capped = gain < 1.0;
  m.with_prediction = m.with_prediction_capped ? 2.0 * period : period;
  return m;
}

nlohmann::json DelayMarginSummary(double period, double q, double rho) {
  const DelayMargin m = PredictedDelayMargin(period, q, rho);
  auto finite = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
  return {{"coupling_spectral_radius", rho},
          {"period_s", period},
          {"q", q},
          {"without_prediction_s", finite(m.without_prediction)},
          {"with_prediction_s", finite(m.with_prediction)},
          {"with_prediction_is_lower_bound", m.with_prediction_capped},
          {"assumes", "a message every step, in-phase clocks, no loss (docs/NETWORK.md)"}};
}

}  // namespace mjf::runner
