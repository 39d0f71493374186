// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Helpers shared by the formation tests: random graphs with a spanning tree, the paper's
// topology and swarm states.
#ifndef MJFORMATION_TESTS_FORMATION_TEST_UTIL_HPP_
#define MJFORMATION_TESTS_FORMATION_TEST_UTIL_HPP_

#include <algorithm>
#include <mjformation/formation/graph.hpp>
#include <numeric>
#include <random>
#include <set>
#include <utility>
#include <vector>

namespace mjf::formation::testing {

// A random digraph with a spanning tree rooted at the leader: a random tree (each follower,
// in random order, hears the leader or an earlier follower) plus `extra_edges` random edges.
inline Graph RandomGraph(int n, int extra_edges, bool weighted, std::mt19937* rng) {
  std::uniform_real_distribution<double> weight(0.2, 2.0);
  auto draw = [&]() { return weighted ? weight(*rng) : 1.0; };
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), *rng);
  std::vector<double> leader(n, 0.0);
  std::vector<Edge> edges;
  std::set<std::pair<int, int>> used;
  leader[order[0]] = draw();
  for (int k = 1; k < n; ++k) {
    const int parent = std::uniform_int_distribution<int>(-1, k - 1)(*rng);
    if (parent < 0) {
      leader[order[k]] = draw();
    } else {
      edges.push_back({order[parent], order[k], draw()});
      used.insert({order[parent], order[k]});
    }
  }
  std::uniform_int_distribution<int> pick(0, n - 1);
  for (int k = 0; k < extra_edges && n > 1; ++k) {
    const int from = pick(*rng), to = pick(*rng);
    if (from == to || used.count({from, to})) continue;
    used.insert({from, to});
    edges.push_back({from, to, draw()});
  }
  return Graph(n, leader, edges);
}

// Paper section 6 (Fig. 8 as we choose it): only follower 1 hears the leader; a chain
// 1 -> 2 -> ... -> 6 with the extra links 1 -> 3, 3 -> 5 and 6 -> 4 (0-1 weights).
inline Graph PaperGraph() {
  std::vector<double> leader = {1, 0, 0, 0, 0, 0};
  std::vector<Edge> edges = {{0, 1}, {1, 2}, {2, 3}, {3, 4}, {4, 5}, {0, 2}, {2, 4}, {5, 3}};
  return Graph(6, leader, edges);
}

}  // namespace mjf::formation::testing

#endif  // MJFORMATION_TESTS_FORMATION_TEST_UTIL_HPP_
