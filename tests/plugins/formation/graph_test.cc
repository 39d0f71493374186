// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <mjformation/formation/continuous_smc.hpp>
#include <mjformation/formation/graph.hpp>
#include <mjformation/formation/laplacian_solver.hpp>
#include <stdexcept>
#include <string>

#include "test_util.hpp"

namespace mjf::formation {
namespace {

// Expects `make` to throw std::invalid_argument whose message contains every fragment.
template <typename Make>
void ExpectRefused(Make make, std::initializer_list<const char*> fragments) {
  try {
    make();
    ADD_FAILURE() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    for (const char* fragment : fragments) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos)
          << "message '" << e.what() << "' lacks '" << fragment << "'";
    }
  }
}

TEST(GraphTest, LaplacianHMatchesDefinition) {
  const Graph g = testing::PaperGraph();
  const Eigen::MatrixXd lh(g.laplacian_h());
  Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(6, 6);
  for (const Edge& e : g.edges()) {
    expected(e.to, e.from) -= e.weight;
    expected(e.to, e.to) += e.weight;
  }
  expected(0, 0) += 1.0;  // H = diag(1, 0, ...)
  EXPECT_EQ((lh - expected).norm(), 0.0);
  EXPECT_DOUBLE_EQ(g.in_degree(2), 2.0);  // follower 3 hears 2 and 1
  EXPECT_TRUE(g.UnreachableFromLeader().empty());
  EXPECT_NO_THROW(g.RequireSpanningTree());
}

TEST(GraphTest, FromAbiCopiesTheGraph) {
  const double leader[] = {1, 0, 0};
  const int from[] = {0, 1};
  const int to[] = {1, 2};
  const double weight[] = {1.0, 2.5};
  const mjfGraph abi = {3, leader, 2, from, to, weight};
  const Graph g = Graph::FromAbi(abi);
  EXPECT_EQ(g.num_followers(), 3);
  EXPECT_DOUBLE_EQ(g.leader_weight(0), 1.0);
  EXPECT_DOUBLE_EQ(g.laplacian_h().coeff(2, 1), -2.5);
  EXPECT_DOUBLE_EQ(g.laplacian_h().coeff(2, 2), 2.5);
}

TEST(GraphTest, RefusesBadEntriesNamingThem) {
  ExpectRefused([] { Graph(3, {1, 0}, {}); }, {"2 entries", "3 followers"});
  ExpectRefused([] { Graph(3, {1, -1, 0}, {}); }, {"follower 2", ">= 0"});
  ExpectRefused([] { Graph(3, {1, 0, 0}, {{0, 3}}); }, {"follower 4", "out of range 1..3"});
  ExpectRefused([] { Graph(3, {1, 0, 0}, {{-1, 1}}); }, {"follower 0", "out of range"});
  ExpectRefused([] { Graph(3, {1, 0, 0}, {{1, 1}}); }, {"edge 1 (2 -> 2)", "self loop"});
  ExpectRefused(
      [] {
        Graph(3, {1, 0, 0}, {{0, 1}, {1, 2}, {0, 1}});
      },
      {"edge 3 (1 -> 2) duplicates edge 1 (1 -> 2)"});
  ExpectRefused([] { Graph(3, {1, 0, 0}, {{0, 1, 0.0}}); }, {"edge 1 (1 -> 2)", "a_2,1", "> 0"});
  ExpectRefused([] { Graph(3, {1, 0, 0}, {{0, 1, std::nan("")}}); }, {"finite"});
  ExpectRefused([] { Graph(0, {}, {}); }, {"at least one follower"});
}

TEST(GraphTest, NoSpanningTreeNamesTheUnreachableFollowers) {
  // Followers 1, 2, 4 reachable; 3 and 5 only hear each other.
  const Graph g(5, {1, 0, 0, 0, 0}, {{0, 1}, {1, 3}, {2, 4}, {4, 2}});
  EXPECT_EQ(g.UnreachableFromLeader(), (std::vector<int>{2, 4}));
  ExpectRefused([&] { g.RequireSpanningTree(); },
                {"topology has no directed spanning tree rooted at the leader (Assumption 2): "
                 "followers 3, 5 cannot be reached from the leader"});
  ExpectRefused([&] { ContinuousSmc(g, ContinuousSmcParams{}); }, {"followers 3, 5"});
  const Graph single(2, {0, 1}, {});
  ExpectRefused([&] { single.RequireSpanningTree(); }, {"follower 1 cannot be reached"});
  ExpectRefused([&] { LaplacianSolver solver(g.laplacian_h()); }, {"singular"});
}

// The per-evaluation cost is O(N + nnz(factor)); for a ring (N-cycle plus one leader link)
// the factor's nonzeros must grow linearly with N.
TEST(LaplacianSolverTest, FactorNonzerosGrowLinearlyOnARing) {
  for (int n : {10, 30, 100, 300, 1000}) {
    std::vector<double> leader(n, 0.0);
    leader[0] = 1.0;
    std::vector<Edge> edges;
    for (int i = 0; i < n; ++i) edges.push_back({i, (i + 1) % n});
    const Graph g(n, leader, edges);
    LaplacianSolver solver(g.laplacian_h());
    const double per_follower = static_cast<double>(solver.factor_nonzeros()) / n;
    RecordProperty("nnz_per_follower_n" + std::to_string(n), std::to_string(per_follower));
    EXPECT_LE(per_follower, 5.0) << "n = " << n << ", nnz = " << solver.factor_nonzeros();
    // And the solve is exact.
    Eigen::Matrix<double, Eigen::Dynamic, 2> b =
        Eigen::Matrix<double, Eigen::Dynamic, 2>::Random(n, 2);
    Eigen::Matrix<double, Eigen::Dynamic, 2> x = b;
    solver.SolveInPlace(x);
    EXPECT_LT((g.laplacian_h() * x - b).norm(), 1e-10 * b.norm());
  }
}

TEST(LaplacianSolverTest, InverseNormExactAndEstimatedAgree) {
  std::mt19937 rng(7);
  const Graph g = testing::RandomGraph(150, 300, true, &rng);
  LaplacianSolver solver(g.laplacian_h());
  ASSERT_TRUE(solver.inverse_two_norm_is_exact());
  const double exact = solver.InverseTwoNorm();
  // Same quantity through the power iteration path (N > 200): a block-diagonal copy.
  std::vector<double> leader(300);
  std::vector<Edge> edges;
  for (int copy = 0; copy < 2; ++copy) {
    for (int i = 0; i < 150; ++i) leader[150 * copy + i] = g.leader_weight(i);
    for (const Edge& e : g.edges())
      edges.push_back({e.from + 150 * copy, e.to + 150 * copy, e.weight});
  }
  const Graph doubled(300, leader, edges);
  LaplacianSolver big(doubled.laplacian_h());
  ASSERT_FALSE(big.inverse_two_norm_is_exact());
  EXPECT_NEAR(big.InverseTwoNorm(), exact, 1e-3 * exact);
}

}  // namespace
}  // namespace mjf::formation
