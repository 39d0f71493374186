// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The directed follower graph of the paper (section 2): weights a_ij, leader links a_i0, and
// L_H = L + H (Lemma 1). Indices here are 0-based; messages use the paper's 1-based numbers.
#ifndef MJFORMATION_FORMATION_GRAPH_HPP_
#define MJFORMATION_FORMATION_GRAPH_HPP_

#include <mjformation/plugin.h>

#include <Eigen/SparseCore>
#include <vector>

namespace mjf::formation {

// Edge from -> to: follower `to` receives follower `from`'s state, a_{to,from} = weight.
struct Edge {
  int from;
  int to;
  double weight = 1.0;
};

class Graph {
 public:
  // Throws std::invalid_argument naming the bad entry (1-based follower numbers): index out
  // of range, self loop, duplicate edge, non-positive/non-finite weight, negative or non-finite
  // leader weight, leader_weight size != n_followers, n_followers < 1.
  Graph(int n_followers, std::vector<double> leader_weight, std::vector<Edge> edges);

  // From plugin.h's mjfGraph (same validation).
  static Graph FromAbi(const mjfGraph& g);

  int num_followers() const { return n_followers_; }
  double leader_weight(int i) const { return leader_weight_[i]; }  // a_i0
  const std::vector<Edge>& edges() const { return edges_; }

  // d_i = sum_j a_ij (in-degree from followers, leader excluded).
  double in_degree(int i) const { return in_degree_[i]; }
  // In-edges of follower i: positions in_begin(i)..in_end(i)-1 of in_neighbor()/in_weight().
  int in_begin(int i) const { return in_offsets_[i]; }
  int in_end(int i) const { return in_offsets_[i + 1]; }
  int in_neighbor(int k) const { return in_neighbors_[k]; }  // j
  double in_weight(int k) const { return in_weights_[k]; }   // a_ij

  // 0-based followers with no directed path from the leader; empty <=> Assumption 2.
  std::vector<int> UnreachableFromLeader() const;

  // Throws std::invalid_argument "topology has no directed spanning tree rooted at the leader
  // (Assumption 2): followers 3, 5 cannot be reached from the leader".
  void RequireSpanningTree() const;

  // L_H = L + H (Lemma 1): row i holds d_i + a_i0 on the diagonal and -a_ij for in-edges j -> i.
  const Eigen::SparseMatrix<double>& laplacian_h() const { return laplacian_h_; }

 private:
  int n_followers_;
  std::vector<double> leader_weight_;
  std::vector<Edge> edges_;
  std::vector<double> in_degree_;
  std::vector<int> in_offsets_;
  std::vector<int> in_neighbors_;
  std::vector<double> in_weights_;
  Eigen::SparseMatrix<double> laplacian_h_;
};

}  // namespace mjf::formation

#endif  // MJFORMATION_FORMATION_GRAPH_HPP_
