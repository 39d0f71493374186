// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The central solver: L_H W = R for the R_i published, no solution for a sample some follower
// did not publish, refusal of a plugin that samples without R_i, and the solver's star over the
// links handing back the same W_i one latency up and one down later.
#include "mjformation/control/central_solver.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <stdexcept>
#include <vector>

#include "mjformation/formation/graph.hpp"

namespace mjf::runner {
namespace {

// Leader -> 1, 1 <-> 2, 2 -> 3 (0-based followers 0, 1, 2).
formation::Graph Chain() { return formation::Graph(3, {1.0, 0.0, 0.0}, {{0, 1}, {1, 0}, {1, 2}}); }

std::vector<mjfMessage> Published(int n_payload) {
  std::vector<mjfMessage> out(3);
  for (int i = 0; i < 3; ++i) {
    out[i].n_payload = n_payload;
    out[i].payload[2] = 1.0 + i;   // R_i x
    out[i].payload[3] = -2.0 * i;  // R_i y
  }
  return out;
}

TEST(CentralSolverTest, SolvesLaplacianHForThePublishedRows) {
  const formation::Graph graph = Chain();
  CentralSolver solver(graph);
  EXPECT_EQ(solver.solution(0), nullptr);
  const std::vector<mjfMessage> out = Published(4);
  solver.SolvePublished(out, 0.0);
  Eigen::MatrixXd w(3, 2);
  for (int i = 0; i < 3; ++i) {
    ASSERT_NE(solver.solution(i), nullptr);
    w(i, 0) = solver.solution(i)[0];
    w(i, 1) = solver.solution(i)[1];
  }
  const Eigen::MatrixXd r = Eigen::MatrixXd(graph.laplacian_h()) * w;  // L_H W = R
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(r(i, 0), out[i].payload[2], 1e-12);
    EXPECT_NEAR(r(i, 1), out[i].payload[3], 1e-12);
  }
  solver.ClearSolution();
  EXPECT_EQ(solver.solution(1), nullptr);
}

TEST(CentralSolverTest, ASampleWithoutEveryRowIsSkippedAndNoRowIsRefused) {
  CentralSolver solver(Chain());
  solver.SolvePublished(Published(0), 0.0);  // between samples: nothing
  EXPECT_EQ(solver.skipped_samples(), 0);
  std::vector<mjfMessage> out = Published(4);
  out[2].n_payload = 0;  // follower 3 has not heard every in-neighbour yet
  solver.SolvePublished(out, 0.0);
  EXPECT_EQ(solver.skipped_samples(), 1);
  EXPECT_EQ(solver.solution(0), nullptr);
  out[2].n_payload = 2;  // sampled, but no R_i
  try {
    solver.SolvePublished(out, 1.5);
    FAIL() << "a plugin that samples without R_i was accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("t = 1.500 s: coupling = \"central_solve\": 2 of 3"),
              std::string::npos)
        << e.what();
  }
}

TEST(CentralSolverTest, TheStarHandsBackTheSameSolutionALatencyUpAndDownLater) {
  const formation::Graph graph = Chain();
  CentralSolver instant(graph);
  const std::vector<mjfMessage> out = Published(4);
  instant.SolvePublished(out, 0.0);
  CentralSolver star(graph);
  const network::Network network(3, {}, 0.001, 1);
  network::LinkParams params;
  params.latency = 0.003;  // 3 steps each way
  star.SetUpStar(network, params, 1);
  for (int i = 0; i < 3; ++i) star.PostR(i, 0, 0, out[i]);
  std::vector<network::RoundLetter> down;
  int64_t arrived = -1;
  for (int64_t step = 0; step <= 10 && down.empty(); ++step) {
    star.CollectAtSolver(step, 0.001 * static_cast<double>(step));
    star.CollectSolutions(step, &down);
    if (!down.empty()) arrived = step;
  }
  EXPECT_EQ(arrived, 6);
  EXPECT_EQ(star.solves(), 1);
  ASSERT_EQ(down.size(), 3u);
  for (const network::RoundLetter& w : down) {
    EXPECT_EQ(w.sample_step, 0);
    EXPECT_EQ(w.message.payload[0], instant.solution(w.link)[0]);  // the same bits
    EXPECT_EQ(w.message.payload[1], instant.solution(w.link)[1]);
  }
  EXPECT_EQ(star.up_link(0).stats().rounds_delivered, 1);
  star.CountLateSolution(2);
  EXPECT_EQ(star.down_late(2), 1);
  EXPECT_EQ(star.up_late(2), 0);
}

TEST(CentralSolverTest, TheStarSkipsASampleOvertakenBeforeItsLastRow) {
  CentralSolver star(Chain());
  star.SetUpStar(network::Network(3, {}, 0.001, 1), network::LinkParams{}, 1);
  const std::vector<mjfMessage> out = Published(4);
  star.PostR(0, 0, 0, out[0]);  // sample 0: follower 3's R_i never comes
  star.PostR(1, 0, 0, out[1]);
  star.CollectAtSolver(0, 0.0);
  for (int i = 0; i < 3; ++i) star.PostR(i, 1, 1, out[i]);
  star.PostR(2, 1, 0, out[2]);  // sample 0's last row, after sample 1 began
  star.CollectAtSolver(1, 0.001);
  EXPECT_EQ(star.skipped_samples(), 1);
  EXPECT_EQ(star.solves(), 1);
  EXPECT_EQ(star.up_late(2), 1);
}

}  // namespace
}  // namespace mjf::runner
