// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include <algorithm>
#include <cmath>
#include <mjformation/formation/graph.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace mjf::formation {
namespace {

std::string EdgeName(size_t k, const Edge& e) {
  std::ostringstream out;
  out << "edge " << k + 1 << " (" << e.from + 1 << " -> " << e.to + 1 << ")";
  return out.str();
}

// Every a_i0 finite and >= 0.
void CheckLeaderWeights(const std::vector<double>& leader_weight) {
  for (int i = 0; i < static_cast<int>(leader_weight.size()); ++i) {
    const double w = leader_weight[i];
    if (!std::isfinite(w) || w < 0.0) {
      std::ostringstream out;
      out << "graph: leader weight a_" << i + 1 << "0 of follower " << i + 1
          << " must be finite and >= 0 (got " << w << ")";
      throw std::invalid_argument(out.str());
    }
  }
}

// Every edge between followers 0..n_followers-1, no self loop, a finite positive weight, no
// duplicate (the later of two is named).
void CheckEdges(int n_followers, const std::vector<Edge>& edges) {
  std::vector<std::pair<long, size_t>> keys;  // (to * n + from, edge index) to find duplicates
  keys.reserve(edges.size());
  for (size_t k = 0; k < edges.size(); ++k) {
    const Edge& e = edges[k];
    for (int end : {e.from, e.to}) {
      if (end < 0 || end >= n_followers) {
        std::ostringstream out;
        out << "graph: " << EdgeName(k, e) << ": follower " << end + 1 << " is out of range 1.."
            << n_followers;
        throw std::invalid_argument(out.str());
      }
    }
    if (e.from == e.to) {
      throw std::invalid_argument("graph: " + EdgeName(k, e) + " is a self loop (a_ii = 0)");
    }
    if (!std::isfinite(e.weight) || e.weight <= 0.0) {
      std::ostringstream out;
      out << "graph: " << EdgeName(k, e) << ": weight a_" << e.to + 1 << "," << e.from + 1
          << " must be finite and > 0 (got " << e.weight << ")";
      throw std::invalid_argument(out.str());
    }
    keys.emplace_back(static_cast<long>(e.to) * n_followers + e.from, k);
  }
  std::sort(keys.begin(), keys.end());
  for (size_t k = 1; k < keys.size(); ++k) {
    if (keys[k].first == keys[k - 1].first) {
      const size_t later = std::max(keys[k].second, keys[k - 1].second);
      const size_t earlier = std::min(keys[k].second, keys[k - 1].second);
      throw std::invalid_argument("graph: " + EdgeName(later, edges[later]) + " duplicates " +
                                  EdgeName(earlier, edges[earlier]));
    }
  }
}

}  // namespace

Graph::Graph(int n_followers, std::vector<double> leader_weight, std::vector<Edge> edges)
    : n_followers_(n_followers),
      leader_weight_(std::move(leader_weight)),
      edges_(std::move(edges)) {
  if (n_followers_ < 1) {
    throw std::invalid_argument("graph: at least one follower is required (got " +
                                std::to_string(n_followers_) + ")");
  }
  if (static_cast<int>(leader_weight_.size()) != n_followers_) {
    throw std::invalid_argument("graph: leader_weight has " +
                                std::to_string(leader_weight_.size()) + " entries for " +
                                std::to_string(n_followers_) + " followers");
  }
  CheckLeaderWeights(leader_weight_);
  CheckEdges(n_followers_, edges_);

  // In-edge adjacency (row i of L_H) and L_H = L + H (Lemma 1).
  in_degree_.assign(n_followers_, 0.0);
  in_offsets_.assign(n_followers_ + 1, 0);
  for (const Edge& e : edges_) {
    in_degree_[e.to] += e.weight;
    ++in_offsets_[e.to + 1];
  }
  for (int i = 0; i < n_followers_; ++i) in_offsets_[i + 1] += in_offsets_[i];
  in_neighbors_.resize(edges_.size());
  in_weights_.resize(edges_.size());
  std::vector<int> fill(in_offsets_.begin(), in_offsets_.end() - 1);
  for (const Edge& e : edges_) {
    in_neighbors_[fill[e.to]] = e.from;
    in_weights_[fill[e.to]] = e.weight;
    ++fill[e.to];
  }
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(edges_.size() + n_followers_);
  for (int i = 0; i < n_followers_; ++i) {
    triplets.emplace_back(i, i, in_degree_[i] + leader_weight_[i]);  // d_i + a_i0
  }
  for (const Edge& e : edges_) triplets.emplace_back(e.to, e.from, -e.weight);  // -a_ij
  laplacian_h_.resize(n_followers_, n_followers_);
  laplacian_h_.setFromTriplets(triplets.begin(), triplets.end());
  laplacian_h_.makeCompressed();
}

Graph Graph::FromAbi(const mjfGraph& g) {
  if (g.n_followers < 1) {
    throw std::invalid_argument("graph: at least one follower is required (got " +
                                std::to_string(g.n_followers) + ")");
  }
  if (g.leader_weight == nullptr) throw std::invalid_argument("graph: leader_weight is NULL");
  if (g.n_edges < 0) throw std::invalid_argument("graph: negative edge count");
  if (g.n_edges > 0 && (!g.edge_from || !g.edge_to || !g.edge_weight)) {
    throw std::invalid_argument("graph: edge arrays are NULL");
  }
  std::vector<double> leader(g.leader_weight, g.leader_weight + g.n_followers);
  std::vector<Edge> edges;
  edges.reserve(g.n_edges);
  for (int k = 0; k < g.n_edges; ++k) {
    edges.push_back(Edge{g.edge_from[k], g.edge_to[k], g.edge_weight[k]});
  }
  return Graph(g.n_followers, std::move(leader), std::move(edges));
}

std::vector<int> Graph::UnreachableFromLeader() const {
  // Breadth-first search from the leader along edges from -> to.
  std::vector<std::vector<int>> out_neighbors(n_followers_);
  for (const Edge& e : edges_) out_neighbors[e.from].push_back(e.to);
  std::vector<char> reached(n_followers_, 0);
  std::vector<int> queue;
  for (int i = 0; i < n_followers_; ++i) {
    if (leader_weight_[i] > 0.0) {
      reached[i] = 1;
      queue.push_back(i);
    }
  }
  for (size_t head = 0; head < queue.size(); ++head) {
    for (int next : out_neighbors[queue[head]]) {
      if (!reached[next]) {
        reached[next] = 1;
        queue.push_back(next);
      }
    }
  }
  std::vector<int> unreachable;
  for (int i = 0; i < n_followers_; ++i) {
    if (!reached[i]) unreachable.push_back(i);
  }
  return unreachable;
}

void Graph::RequireSpanningTree() const {
  const std::vector<int> unreachable = UnreachableFromLeader();
  if (unreachable.empty()) return;
  std::ostringstream out;
  out << "topology has no directed spanning tree rooted at the leader (Assumption 2): "
      << (unreachable.size() == 1 ? "follower " : "followers ");
  for (size_t k = 0; k < unreachable.size(); ++k) {
    out << (k ? ", " : "") << unreachable[k] + 1;
  }
  out << " cannot be reached from the leader";
  throw std::invalid_argument(out.str());
}

}  // namespace mjf::formation
