// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The one linear solve of the compact protocols (33) and (53): L_H W = R. L_H is factored once
// (Eigen::SparseLU, COLAMD ordering) at construction; the factors are copied into plain
// compressed-column arrays so that a solve is two sparse triangular sweeps over preallocated
// memory: O(N + nnz(L) + nnz(U)) and no heap allocation (Eigen's own SparseLU::solve allocates
// a work array on every call).
#ifndef MJFORMATION_FORMATION_LAPLACIAN_SOLVER_HPP_
#define MJFORMATION_FORMATION_LAPLACIAN_SOLVER_HPP_

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace mjf::formation {

class LaplacianSolver {
 public:
  // Factors L_H; throws std::invalid_argument if it is singular (no spanning tree, Lemma 1).
  explicit LaplacianSolver(const Eigen::SparseMatrix<double>& laplacian_h);

  int size() const { return n_; }

  // Overwrites the n x 2 block (one column per horizontal axis) with L_H^-1 times it.
  // No heap allocation.
  void SolveInPlace(Eigen::Matrix<double, Eigen::Dynamic, 2>& columns);

  // Nonzeros of the stored factors L (strictly lower) + U (with diagonal): the per-solve cost.
  long factor_nonzeros() const;

  // ||L_H^-1||_2 (induced 2-norm) = 1 / sigma_min(L_H). Exact (dense SVD) for N <= 200; for
  // larger N an estimate from 300 power iterations on L_H^-T L_H^-1 (a lower bound that
  // converges to the norm). Computed once, on first call.
  double InverseTwoNorm() const;
  bool inverse_two_norm_is_exact() const { return n_ <= kDenseNormLimit; }

  static constexpr int kDenseNormLimit = 200;

 private:
  int n_;
  Eigen::SparseMatrix<double> laplacian_h_;
  std::vector<int> row_perm_;  // Pr: work[row_perm_[i]] = b[i]
  std::vector<int> col_perm_;  // Pc: x[i] = work[col_perm_[i]]
  // Unit lower L (strict part) and upper U (strict part + diagonal), compressed by column.
  std::vector<int> lower_offsets_, lower_rows_;
  std::vector<double> lower_values_;
  std::vector<int> upper_offsets_, upper_rows_;
  std::vector<double> upper_values_;
  std::vector<double> upper_diagonal_;
  std::vector<double> work_;
  mutable double inverse_two_norm_ = -1.0;
};

}  // namespace mjf::formation

#endif  // MJFORMATION_FORMATION_LAPLACIAN_SOLVER_HPP_
