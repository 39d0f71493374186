// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include <Eigen/Dense>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseLU>
#include <cmath>
#include <mjformation/formation/laplacian_solver.hpp>
#include <stdexcept>
#include <string>

namespace mjf::formation {
namespace {

using SparseLuSolver = Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>>;

void CompressColumns(const std::vector<std::vector<std::pair<int, double>>>& columns,
                     std::vector<int>* offsets, std::vector<int>* rows,
                     std::vector<double>* values) {
  offsets->assign(1, 0);
  rows->clear();
  values->clear();
  for (const auto& column : columns) {
    for (const auto& [row, value] : column) {
      rows->push_back(row);
      values->push_back(value);
    }
    offsets->push_back(static_cast<int>(rows->size()));
  }
}

// Self-check of the copied factors against L_H (guards against an Eigen layout change): solves
// two probe columns with the copied factors and compares L_H x with them.
void CheckFactors(const Eigen::SparseMatrix<double>& laplacian_h, LaplacianSolver* solver) {
  const int n = static_cast<int>(laplacian_h.rows());
  Eigen::Matrix<double, Eigen::Dynamic, 2> probe(n, 2), solution(n, 2);
  for (int i = 0; i < n; ++i) {
    probe(i, 0) = 1.0 + (i % 7);
    probe(i, 1) = std::sin(0.37 * i);
  }
  solution = probe;
  solver->SolveInPlace(solution);
  const double residual = (laplacian_h * solution - probe).norm();
  const double scale = probe.norm() + laplacian_h.norm() * solution.norm();
  if (!(residual <= 1e-10 * scale)) {
    throw std::logic_error("LaplacianSolver: copied LU factors do not reproduce L_H (residual " +
                           std::to_string(residual) + ")");
  }
}

}  // namespace

LaplacianSolver::LaplacianSolver(const Eigen::SparseMatrix<double>& laplacian_h)
    : n_(static_cast<int>(laplacian_h.rows())), laplacian_h_(laplacian_h) {
  if (laplacian_h.rows() != laplacian_h.cols() || n_ < 1) {
    throw std::invalid_argument("L_H must be square and non-empty");
  }
  laplacian_h_.makeCompressed();
  SparseLuSolver lu;
  lu.analyzePattern(laplacian_h_);
  lu.factorize(laplacian_h_);
  if (lu.info() != Eigen::Success) {
    throw std::invalid_argument(
        "L_H is singular: the topology has no directed spanning tree rooted at the leader "
        "(Lemma 1 / Assumption 2)");
  }

  // Copy the supernodal factors into plain compressed columns: Pr L_H Pc^T = L U.
  row_perm_.resize(n_);
  col_perm_.resize(n_);
  for (int i = 0; i < n_; ++i) {
    row_perm_[i] = lu.rowsPermutation().indices()(i);
    col_perm_[i] = lu.colsPermutation().indices()(i);
  }
  const auto& supernodal = lu.matrixL().m_mapL;  // L (and U's diagonal blocks), by column
  const auto& upper_rest = lu.matrixU().m_mapU;  // U outside the supernodes' diagonal blocks
  std::vector<std::vector<std::pair<int, double>>> lower(n_), upper(n_);
  upper_diagonal_.assign(n_, 0.0);
  using SupernodalMatrix = std::decay_t<decltype(supernodal)>;
  using UpperMatrix = std::decay_t<decltype(upper_rest)>;
  for (int j = 0; j < n_; ++j) {
    for (typename SupernodalMatrix::InnerIterator it(supernodal, j); it; ++it) {
      const int row = static_cast<int>(it.row());
      if (row > j) {
        lower[j].emplace_back(row, it.value());
      } else if (row == j) {
        upper_diagonal_[j] = it.value();
      } else {
        upper[j].emplace_back(row, it.value());
      }
    }
    for (typename UpperMatrix::InnerIterator it(upper_rest, j); it; ++it) {
      upper[j].emplace_back(static_cast<int>(it.index()), it.value());
    }
  }
  for (int j = 0; j < n_; ++j) {
    if (!(std::abs(upper_diagonal_[j]) > 0.0)) {
      throw std::invalid_argument(
          "L_H is singular: the topology has no directed spanning tree rooted at the leader "
          "(Lemma 1 / Assumption 2)");
    }
  }
  CompressColumns(lower, &lower_offsets_, &lower_rows_, &lower_values_);
  CompressColumns(upper, &upper_offsets_, &upper_rows_, &upper_values_);
  work_.assign(n_, 0.0);

  CheckFactors(laplacian_h_, this);
}

void LaplacianSolver::SolveInPlace(Eigen::Matrix<double, Eigen::Dynamic, 2>& columns) {
  double* work = work_.data();
  for (int c = 0; c < 2; ++c) {
    for (int i = 0; i < n_; ++i) work[row_perm_[i]] = columns(i, c);
    for (int j = 0; j < n_; ++j) {  // forward sweep with unit lower L
      const double xj = work[j];
      for (int k = lower_offsets_[j]; k < lower_offsets_[j + 1]; ++k) {
        work[lower_rows_[k]] -= lower_values_[k] * xj;
      }
    }
    for (int j = n_ - 1; j >= 0; --j) {  // backward sweep with U
      const double xj = work[j] / upper_diagonal_[j];
      work[j] = xj;
      for (int k = upper_offsets_[j]; k < upper_offsets_[j + 1]; ++k) {
        work[upper_rows_[k]] -= upper_values_[k] * xj;
      }
    }
    for (int i = 0; i < n_; ++i) columns(i, c) = work[col_perm_[i]];
  }
}

long LaplacianSolver::factor_nonzeros() const {
  return static_cast<long>(lower_values_.size() + upper_values_.size() + upper_diagonal_.size());
}

double LaplacianSolver::InverseTwoNorm() const {
  if (inverse_two_norm_ >= 0.0) return inverse_two_norm_;
  if (n_ <= kDenseNormLimit) {
    const Eigen::MatrixXd dense(laplacian_h_);
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(dense);
    inverse_two_norm_ = 1.0 / svd.singularValues()(n_ - 1);
    return inverse_two_norm_;
  }
  // Power iteration on (L_H^T L_H)^-1: its largest eigenvalue is ||L_H^-1||_2^2.
  SparseLuSolver lu;
  lu.compute(laplacian_h_);
  Eigen::VectorXd x = Eigen::VectorXd::Ones(n_).normalized();
  double estimate = 0.0;
  for (int iteration = 0; iteration < 300; ++iteration) {
    const Eigen::VectorXd y = lu.solve(x);
    const Eigen::VectorXd z = lu.transpose().solve(y);
    estimate = std::sqrt(z.norm());
    x = z.normalized();
  }
  inverse_two_norm_ = estimate;
  return inverse_two_norm_;
}

}  // namespace mjf::formation
