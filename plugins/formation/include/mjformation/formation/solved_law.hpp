// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// What a swarm-wide law that closes its input through one solve with L_H keeps (the continuous
// SMC's U = F_a + L_H^-1 (...) of eq. (33), and the literature's super_twisting and
// terminal_smc on the same virtual input): the graph, L_H's factor, and the buffers one Update
// fills, all sized here so that Update allocates nothing.
#ifndef MJFORMATION_FORMATION_SOLVED_LAW_HPP_
#define MJFORMATION_FORMATION_SOLVED_LAW_HPP_

#include <Eigen/Core>
#include <mjformation/formation/graph.hpp>
#include <mjformation/formation/laplacian_solver.hpp>
#include <mjformation/formation/sliding.hpp>
#include <vector>

namespace mjf::formation {

class SolvedLaw {
 public:
  // Outputs of the last Update: acceleration()[2i + axis] = u_i (m/s^2), sliding()[2i + axis]
  // = the law's sliding variable, error()[4i + k] = e_i (k = px, py, vx, vy) of eq. (16).
  const std::vector<double>& acceleration() const { return acceleration_; }
  const std::vector<double>& sliding() const { return sliding_; }
  const std::vector<double>& error() const { return error_; }
  double norm_inv_lh() const { return solver_.InverseTwoNorm(); }
  const Graph& graph() const { return graph_; }

 protected:
  // Requires a spanning tree (Assumption 2) and factors L_H (throws std::invalid_argument).
  explicit SolvedLaw(const Graph& graph)
      : graph_(WithSpanningTree(graph)),
        solver_(graph_.laplacian_h()),
        acceleration_(2 * graph_.num_followers(), 0.0),
        sliding_(2 * graph_.num_followers(), 0.0),
        error_(4 * graph_.num_followers(), 0.0),
        rhs_(graph_.num_followers(), 2) {}

  Graph graph_;
  LaplacianSolver solver_;
  std::vector<double> acceleration_, sliding_, error_;
  Eigen::Matrix<double, Eigen::Dynamic, 2> rhs_;  // the right-hand side of the solve, per axis
};

}  // namespace mjf::formation

#endif  // MJFORMATION_FORMATION_SOLVED_LAW_HPP_
